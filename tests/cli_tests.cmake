# The tools' shared command-line parts: the CLI11 conventions and the progress bar.
svgf_add_tests(svgf_cli_tests SOURCES cli_command_line_test.cpp cli_progress_test.cpp LIBS svgf_cli)
svgf_sanitized_at_o0(svgf_cli_tests)
