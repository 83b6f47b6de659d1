svgf_add_device_tests(svgf_pipeline_tests DENOISERS_ONLY
  SOURCES svgf_pipeline_test.cpp svgf_asvgf_test.cpp svgf_split_test.cpp bad_input_test.cpp gaussian_test.cpp svgf_params_test.cpp gaussian_params_test.cpp numerical_stress_test.cpp
          svgf_packed_exact_test.cpp
  LIBS svgf_pipeline svgf_metrics svgf_io)
# The CPU kernels' instruction-set variants: same bits on each, the run-time pick; a variant this
# CPU cannot run reports Skipped. And the proof on the built archive that no variant's code can
# be bound from outside it (kernels_cpu/CMakeLists.txt says why it must not).
svgf_add_tests(svgf_cpu_variant_tests SOURCES cpu_variants_test.cpp
  LIBS svgf_pipeline svgf_io SKIP_REGEX "SKIPPED:")
string(REPLACE ";" "," svgf_cpu_variant_ids "${SVGF_CPU_VARIANTS}")
add_test(NAME svgf_cpu_variants_isolated
  COMMAND ${CMAKE_COMMAND} -DLIBRARY=$<TARGET_FILE:svgf_cpu> -DVARIANTS=${svgf_cpu_variant_ids}
          -DWORK=${CMAKE_CURRENT_BINARY_DIR}/variant_isolation -DAR=${CMAKE_AR} -DNM=${CMAKE_NM}
          -DOBJDUMP=${CMAKE_OBJDUMP} -DSANITIZED=$<OR:$<BOOL:${SVGF_SANITIZE}>,$<BOOL:${SVGF_FUZZ}>>
          -P ${PROJECT_SOURCE_DIR}/kernels_cpu/check_variant_isolation.cmake)
# The device path's host side (views, layout rules, a CPU denoiser's refusal): no GPU needed.
svgf_add_tests(svgf_device_frame_tests SOURCES device_frame_test.cpp LIBS svgf_pipeline)
