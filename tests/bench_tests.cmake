# The benchmark's cost model against the kernels, and its runs of any method read back through
# the results model (built with svgf-bench's library).
if(TARGET svgf_bench_lib)
  svgf_add_tests(svgf_bench_tests SOURCES bench_stage_cost_test.cpp bench_methods_test.cpp bench_targets_test.cpp
                 bench_workload_test.cpp bench_stability_test.cpp bench_pareto_test.cpp
                 LIBS svgf_bench_lib)
  # A tiny evaluation set rendered in the test (seconds): needs the renderer.
  if(TARGET svgf_gbuffer)
    svgf_add_tests(svgf_bench_eval_tests SOURCES bench_eval_quality_test.cpp
                   LIBS svgf_bench_lib svgf_gbuffer)
  endif()
endif()
