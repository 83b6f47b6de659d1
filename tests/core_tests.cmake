svgf_add_tests(svgf_core_tests
  SOURCES det_math_test.cpp demodulate_test.cpp reproject_test.cpp variance_test.cpp
          atrous_test.cpp cpu_rows_test.cpp
  LIBS svgf_cpu)
