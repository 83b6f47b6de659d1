# cmake --install BUILD [--prefix DIR]: the libraries a program needs to read, write and denoise
# frames, their headers, the tools, and the CMake package `svgf` (docs/api.md). A consumer
# writes find_package(svgf) and links svgf::svgf.
include(CMakePackageConfigHelpers)

# The one target a consumer links: frames in and out (io), every method on every backend this
# build has (pipeline), the metrics.
add_library(svgf_package INTERFACE)
target_link_libraries(svgf_package INTERFACE svgf_pipeline svgf_io svgf_metrics)
add_library(svgf::svgf ALIAS svgf_package)

set(svgf_exported svgf_strict_fp svgf_core svgf_io svgf_metrics svgf_cpu svgf_pipeline svgf_package)
if(TARGET svgf_cuda)
  list(APPEND svgf_exported svgf_cuda)
endif()
foreach(target ${svgf_exported})
  string(REGEX REPLACE "^svgf_" "" name ${target})  # svgf::io, svgf::pipeline, ...
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
endforeach()
set_target_properties(svgf_package PROPERTIES EXPORT_NAME svgf)

install(TARGETS ${svgf_exported} EXPORT svgfTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
set(svgf_tools svgf)
foreach(tool svgf-fixtures svgf-bench)
  if(TARGET ${tool})
    list(APPEND svgf_tools ${tool})
  endif()
endforeach()
install(TARGETS ${svgf_tools} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# Headers keep their paths ("core/frame.h", "io/sequence.h"), under include/svgf/, which is on
# svgf::core's include path.
set(svgf_header_dirs core io methods pipeline metrics kernels_cpu)
if(TARGET svgf_cuda)
  list(APPEND svgf_header_dirs kernels_cuda)
endif()
foreach(dir ${svgf_header_dirs})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/svgf/${dir}
          FILES_MATCHING PATTERN "*.h" PATTERN "*.cuh")
endforeach()

set(svgf_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/svgf)
install(EXPORT svgfTargets NAMESPACE svgf:: DESTINATION ${svgf_cmake_dir})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/svgfConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/svgfConfig.cmake
                              INSTALL_DESTINATION ${svgf_cmake_dir})
# 0.x: a new minor version may change the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/svgfConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/svgfConfig.cmake ${PROJECT_BINARY_DIR}/svgfConfigVersion.cmake
        DESTINATION ${svgf_cmake_dir})
