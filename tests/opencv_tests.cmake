# OpenCV cross-checks (docs/opencv-checks.md): OpenCV as the independent check on every stage.
find_package(OpenCV REQUIRED COMPONENTS core imgproc quality ximgproc)

set(svgf_opencv_sources
  opencv_atrous_test.cpp
  opencv_reprojection_test.cpp
  opencv_moments_test.cpp
  opencv_metrics_test.cpp
  opencv_pipeline_test.cpp
  opencv_gaussian_test.cpp)
# With the CUDA backend, the checks are compiled by nvcc (exact flags, as the backend's kernels):
# their CUDA variants launch each stage kernel through the generic launcher
# (kernels_cuda/cuda_launch.cuh), so no list of kernel types is kept anywhere.
if(TARGET svgf_cuda)
  set_source_files_properties(${svgf_opencv_sources} PROPERTIES LANGUAGE CUDA
    COMPILE_OPTIONS "${SVGF_CUDA_EXACT_FLAGS}")
endif()

svgf_add_tests(svgf_opencv_tests
  SOURCES ${svgf_opencv_sources}
  LIBS svgf_pipeline svgf_metrics svgf_io ${OpenCV_LIBS})

if(TARGET svgf_cuda)
  # svgf_cuda brings the CUDA runtime (static, as the backend links it) and its headers.
  target_link_libraries(svgf_opencv_tests PRIVATE svgf_cuda)
  target_compile_definitions(svgf_opencv_tests PRIVATE SVGF_HAVE_CUDA=1)
endif()

# The CUDA variants are hidden from test discovery ([.cuda]) and run here as one entry, so that a
# machine without a GPU reports this entry as Skipped rather than passing it silently.
add_test(NAME svgf_opencv_tests:cuda COMMAND svgf_opencv_tests "[cuda]")
set_tests_properties(svgf_opencv_tests:cuda PROPERTIES
  SKIP_REGULAR_EXPRESSION "SKIPPED: CUDA variant not run")
