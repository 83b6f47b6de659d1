svgf_add_tests(svgf_app_tests SOURCES app_test.cpp app_process_test.cpp app_info_compare_test.cpp
  app_import_test.cpp app_html_report_test.cpp app_browser_test.cpp app_pipeline_test.cpp LIBS svgf_app svgf_io)
# app_process_test.cpp runs the svgf binary itself (exit status, file size limits, signals).
add_dependencies(svgf_app_tests svgf)
svgf_sanitized_at_o0(svgf_app_tests)
target_compile_definitions(svgf_app_tests PRIVATE SVGF_BINARY="$<TARGET_FILE:svgf>")
# app_browser_test.cpp renders report.html in headless Chromium: hidden from discovery
# ([.browser]), run as this one entry, Skipped where no browser is installed.
add_test(NAME svgf_app_tests:browser COMMAND svgf_app_tests "[browser]")
set_tests_properties(svgf_app_tests:browser PROPERTIES
  SKIP_REGULAR_EXPRESSION "SKIPPED: no browser" TIMEOUT 300)
