# The benchmark's cost model against the kernels (built with svgf-bench's cost library).
if(TARGET svgf_bench_cost)
  svgf_add_tests(svgf_bench_tests SOURCES bench_stage_cost_test.cpp LIBS svgf_bench_cost)
endif()
