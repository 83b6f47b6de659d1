#pragma once
// SVGF's stage views as each flavor stores them (methods/svgf/flavors.h), on a StageRunner:
// a stage test written once over the flavor runs exact mode on planes and fast mode on packed
// pixels, as the pipeline does (methods/svgf/pipeline.h: filter_guides, signal_buffer).
#include "methods/svgf/flavors.h"
#include "test_device.h"

namespace svgf::test {

inline GuideView filter_guides(SvgfExact, StageRunner& r, const Frame& f) { return r.guides(f); }
inline IllumVarView signal(SvgfExact, StageRunner& r, Image& im) { return r.illum_var(im); }
inline ConstIllumVarView signal(SvgfExact, StageRunner& r, const Image& im) {
  return r.illum_var(im);
}
#if defined(__CUDACC__)
inline PackedGuides filter_guides(SvgfFast, StageRunner& r, const Frame& f) {
  return r.packed_guides(f);
}
inline PackedIllumVar<Packed4> signal(SvgfFast, StageRunner& r, Image& im) {
  return r.packed(im);
}
inline PackedIllumVar<const Packed4> signal(SvgfFast, StageRunner& r, const Image& im) {
  return r.packed(im);
}
#endif

// Runs body(flavor) with the device's flavor: SvgfExact, or SvgfFast on CUDA fast.
template <class Body>
void with_flavor(const TestDevice& d, const Body& body) {
  if (!d.fast()) {
    body(SvgfExact{});
    return;
  }
#if defined(__CUDACC__)
  body(SvgfFast{});
#else
  FAIL("fast mode in a binary not compiled by nvcc");
#endif
}

}  // namespace svgf::test
