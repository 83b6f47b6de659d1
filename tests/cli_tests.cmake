# The tools' shared command-line parts: the progress bar.
svgf_add_tests(svgf_cli_tests SOURCES cli_progress_test.cpp LIBS svgf_cli)
