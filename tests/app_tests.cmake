svgf_add_tests(svgf_app_tests SOURCES app_test.cpp app_process_test.cpp app_info_compare_test.cpp
  app_import_test.cpp LIBS svgf_app svgf_io)
# app_process_test.cpp runs the svgf binary itself (exit status, file size limits, signals).
add_dependencies(svgf_app_tests svgf)
target_compile_definitions(svgf_app_tests PRIVATE SVGF_BINARY="$<TARGET_FILE:svgf>")
