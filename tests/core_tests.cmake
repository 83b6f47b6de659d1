# Host-only tests: the deterministic math, the CPU row drivers, the test harness.
svgf_add_tests(svgf_core_tests
  SOURCES det_math_test.cpp previous_depth_test.cpp svgf_cpu_rows_test.cpp
          svgf_cpu_reproject_rows_test.cpp
          svgf_cpu_gradient_rows_test.cpp sanitize_rows_test.cpp
          wavelet_cpu_rows_test.cpp jbf_cpu_rows_test.cpp test_device_test.cpp
          metrics_lighting_change_test.cpp metrics_stability_test.cpp
          metrics_filters_test.cpp
  LIBS svgf_cpu svgf_io svgf_metrics)
# Every method's stages, each test body on the CPU, CUDA exact and (where fast mode has its
# own arithmetic for the stage) CUDA fast.
svgf_add_device_tests(svgf_stage_tests
  SOURCES sanitize_test.cpp svgf_demodulate_test.cpp svgf_reproject_test.cpp svgf_variance_test.cpp
          svgf_atrous_test.cpp svgf_gradient_test.cpp wavelet_test.cpp jbf_test.cpp bmfr_test.cpp
          taa_test.cpp
  LIBS svgf_cpu svgf_pipeline svgf_io svgf_metrics)
# Sanitized, their compile was the build's largest after the CPU kernels (176 CPU-s at -O1);
# they run in 14.6 s at -O0 against 13.0 s at -O1.
svgf_sanitized_at_o0(svgf_stage_tests)
# The CUDA backend's host-side code that needs no device (runs in CI).
if(TARGET svgf_cuda)
  svgf_add_tests(svgf_cuda_host_tests SOURCES cuda_host_staging_test.cpp LIBS svgf_cuda)
endif()
