# OpenCV cross-checks (docs/opencv-checks.md): OpenCV as the independent check on every stage,
# each check on the CPU and on CUDA exact (tests/test_device.h).
# SVGF_BUILD_OPENCV_TESTS=OFF: the sanitized build leaves them out (docs/sanitizers.md).
if(NOT SVGF_BUILD_OPENCV_TESTS)
  return()
endif()
find_package(OpenCV REQUIRED COMPONENTS core imgproc quality ximgproc)

svgf_add_device_tests(svgf_opencv_tests
  SOURCES opencv_atrous_test.cpp opencv_reprojection_test.cpp opencv_moments_test.cpp
          opencv_pipeline_test.cpp opencv_gaussian_test.cpp opencv_wavelet_test.cpp
          opencv_jbf_test.cpp
  HOST_SOURCES opencv_metrics_test.cpp
  LIBS svgf_pipeline svgf_metrics svgf_io ${OpenCV_LIBS})
