svgf_add_tests(svgf_app_tests SOURCES app_test.cpp LIBS svgf_app svgf_io)
