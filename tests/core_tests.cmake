svgf_add_tests(svgf_core_tests
  SOURCES det_math_test.cpp svgf_demodulate_test.cpp svgf_reproject_test.cpp
          svgf_variance_test.cpp svgf_atrous_test.cpp svgf_cpu_rows_test.cpp
  LIBS svgf_cpu)
