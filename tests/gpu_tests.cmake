# svgf_gpu_tests: CPU vs CUDA (exact: bitwise; fast: within tolerance), determinism and error
# tests. A plain executable with its own main (not catch_discover_tests: ctest must see one test
# that reports "skipped" (exit 77) on a machine without a CUDA device, never "passed").
if(TARGET svgf_cuda)
  # The tests run single kernels through the generic launcher: compiled by nvcc with the
  # backend's exact flags. The main (Catch2's runner and the device query) needs no device
  # code, so the host compiler takes it: through nvcc it was the slowest file of the build.
  svgf_cuda_unity(gpu_test_sources svgf_gpu_tests
    gpu_test.cpp gpu_test_pipeline.cpp gpu_test_device_frames.cpp)
  set_source_files_properties(${gpu_test_sources} PROPERTIES LANGUAGE CUDA
    COMPILE_OPTIONS "${SVGF_CUDA_EXACT_FLAGS}")
  add_executable(svgf_gpu_tests gpu_test_main.cpp ${gpu_test_sources})
  target_link_libraries(svgf_gpu_tests PRIVATE
    Catch2::Catch2 svgf_core svgf_cpu svgf_pipeline svgf_cuda svgf_io svgf_metrics)
  target_include_directories(svgf_gpu_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(svgf_gpu_tests PRIVATE SVGF_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SVGF_HAVE_CUDA=1)
  svgf_tests_at_o1(svgf_gpu_tests)
  add_test(NAME svgf_gpu_tests COMMAND svgf_gpu_tests)
  set_tests_properties(svgf_gpu_tests PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 900)
endif()
