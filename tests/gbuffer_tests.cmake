# Embree fixture renderer: conventions, motion vectors, determinism, committed fixtures.
if(SVGF_BUILD_GBUFFER AND TARGET svgf_gbuffer)
  svgf_add_tests(svgf_gbuffer_tests SOURCES gbuffer_test.cpp gbuffer_gradient_test.cpp gbuffer_eval_test.cpp
                 svgf_convergence_test.cpp svgf_lighting_change_test.cpp
                 LIBS svgf_gbuffer svgf_io svgf_pipeline svgf_metrics)
endif()
