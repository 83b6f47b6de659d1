#pragma once
// What the fixture renderer's tests share: one Renderer per test binary (its Embree device is
// made once, not once per test file).
#include "gbuffer/renderer.h"

namespace svgf::test {

inline const gbuffer::Renderer& renderer() {
  static const gbuffer::Renderer r;
  return r;
}

}  // namespace svgf::test
