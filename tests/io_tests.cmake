svgf_add_tests(svgf_io_tests SOURCES io_test.cpp io_staged_folder_test.cpp LIBS svgf_io)
svgf_sanitized_at_o0(svgf_io_tests)
