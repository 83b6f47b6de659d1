svgf_add_device_tests(svgf_pipeline_tests DENOISERS_ONLY
  SOURCES svgf_pipeline_test.cpp svgf_asvgf_test.cpp svgf_split_test.cpp bad_input_test.cpp gaussian_test.cpp svgf_params_test.cpp gaussian_params_test.cpp
  LIBS svgf_pipeline svgf_metrics svgf_io)
