svgf_add_tests(svgf_pipeline_tests SOURCES svgf_pipeline_test.cpp gaussian_test.cpp
               svgf_planted_bug_test.cpp gaussian_planted_bug_test.cpp
               LIBS svgf_pipeline svgf_metrics)
