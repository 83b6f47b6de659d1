# cmake -DLIBRARY=libsvgf_cpu.a -DVARIANTS=v2,v3,v4 -DWORK=dir -DAR=ar -DNM=nm -DOBJDUMP=objdump
#       -P check_variant_isolation.cmake
# Proves on the built archive that the CPU kernel variants cannot share code (kernels_cpu/
# CMakeLists.txt says why they must not): each variant's object defines exactly one global
# symbol, its entry point, so no inline function or template instantiation of one variant can be
# bound by another or by the rest of the program. And that each variant's code is what its name
# says: x86-64-v2 has no AVX register (ymm, zmm) in it, x86-64-v3 no AVX-512 one, x86-64-v4 does
# use zmm (-mprefer-vector-width=512). And that no variant holds a static variable that is
# written: made local, it would exist once per variant. And that no variant holds an
# out-of-line copy of the exp (core/hd.h, SVGF_HD_INLINE). -DSANITIZED=ON (a sanitized build):
# the symbol rule only.
foreach(var LIBRARY VARIANTS WORK AR NM OBJDUMP)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_variant_isolation: -D${var}=... missing")
  endif()
endforeach()
string(REPLACE "," ";" VARIANTS "${VARIANTS}")
get_filename_component(LIBRARY "${LIBRARY}" ABSOLUTE)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(failures "")
foreach(id ${VARIANTS})
  set(object svgf_cpu_${id}.o)
  execute_process(COMMAND ${AR} x ${LIBRARY} ${object} WORKING_DIRECTORY ${WORK}
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    list(APPEND failures "${object}: not in ${LIBRARY} (${err})")
    continue()
  endif()
  execute_process(COMMAND ${NM} -g --defined-only ${WORK}/${object}
                  OUTPUT_VARIABLE globals RESULT_VARIABLE rc)
  string(STRIP "${globals}" globals)
  string(REGEX REPLACE "\n" ";" globals "${globals}")
  list(LENGTH globals count)
  if(NOT rc EQUAL 0 OR NOT count EQUAL 1 OR NOT globals MATCHES " T svgf_cpu_variant_${id}$")
    list(APPEND failures
         "${object}: defines ${count} global symbols, must be only svgf_cpu_variant_${id}: ${globals}")
  endif()
  if(SANITIZED)
    # The sanitizers' per-object metadata is writable data, and instrumented code has no ymm
    # instruction (GCC 12): only the symbol rule above applies to an instrumented build.
    continue()
  endif()
  # Localized, a static variable of an inline function would exist once per variant: there
  # must be none that is written (writable sections empty, but the exception personality's
  # pointer; vtables and typeinfo are read-only, .data.rel.ro).
  execute_process(COMMAND ${OBJDUMP} -h ${WORK}/${object} OUTPUT_VARIABLE sections)
  string(REGEX MATCHALL "\\.(data|bss|tdata|tbss)[^ \n]* +[0-9a-f]+" writable "${sections}")
  foreach(entry ${writable})
    string(REGEX REPLACE " +" ";" entry "${entry}")
    list(GET entry 0 name)
    list(GET entry 1 size)
    if(NOT size MATCHES "^0+$" AND NOT name MATCHES "^\\.data\\.rel\\.ro|DW\\.ref\\.__gxx_personality_v0$")
      list(APPEND failures "${object}: writable static data in ${name} (0x${size} bytes), one copy per variant")
    endif()
  endforeach()
  # Its own copies of the inline functions are there, local.
  execute_process(COMMAND ${NM} --defined-only ${WORK}/${object} OUTPUT_VARIABLE all)
  string(REGEX MATCHALL "\n[0-9a-f]+ t [^\n]*" locals "${all}")
  list(LENGTH locals local_count)
  message(STATUS "${object}: 1 global symbol, ${local_count} local functions")
  # The exp's parts and its ExactArith wrappers are inlined everywhere (core/hd.h,
  # SVGF_HD_INLINE): an out-of-line copy is a call inside a tap loop, which GCC then leaves
  # scalar (the gradient a-trous row ran 4x slower so, with a copy of exp_neg_sum).
  set(exp_parts "det_exp_reduce|det_exp_poly|exp_nonpositive|exp_neg_sum")
  string(REGEX MATCHALL "\n[0-9a-f]+ [tTwW] [^\n]*(${exp_parts})[^\n]*" outlined "${all}")
  if(outlined)
    string(REPLACE "\n" "" outlined "${outlined}")
    list(APPEND failures "${object}: the exp out of line, a call in the vector loops:${outlined}")
  endif()
  if(id MATCHES "^v[234]$")
    # Instructions naming a ymm or a zmm register (grep: CMake's regex takes seconds on 20 MB).
    execute_process(COMMAND ${OBJDUMP} -d --no-show-raw-insn ${WORK}/${object}
                    OUTPUT_FILE ${WORK}/${id}.s RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
      list(APPEND failures "${object}: ${OBJDUMP} -d failed")
    endif()
    execute_process(COMMAND grep -c "%ymm" ${WORK}/${id}.s OUTPUT_VARIABLE ymm_count
                    OUTPUT_STRIP_TRAILING_WHITESPACE)
    execute_process(COMMAND grep -c "%zmm" ${WORK}/${id}.s OUTPUT_VARIABLE zmm_count
                    OUTPUT_STRIP_TRAILING_WHITESPACE)
    message(STATUS "${object}: ${ymm_count} instructions on ymm, ${zmm_count} on zmm registers")
    if(id STREQUAL "v2" AND (ymm_count GREATER 0 OR zmm_count GREATER 0))
      list(APPEND failures "${object}: x86-64-v2 code uses AVX registers")
    elseif(id STREQUAL "v3" AND (ymm_count EQUAL 0 OR zmm_count GREATER 0))
      list(APPEND failures "${object}: x86-64-v3 code must use ymm and no zmm registers")
    elseif(id STREQUAL "v4" AND zmm_count EQUAL 0)
      list(APPEND failures "${object}: x86-64-v4 code uses no zmm register")
    endif()
  endif()
endforeach()
if(failures)
  string(REPLACE ";" "\n  " failures "${failures}")
  message(FATAL_ERROR "CPU kernel variants not isolated:\n  ${failures}")
endif()
message(STATUS "every CPU kernel variant exports only its entry point")
