#pragma once
// Where an a-trous iteration's result can go besides the next iteration's buffer, for the fused
// pipeline (CUDA, both modes): the remodulated output (RemodulateSink, methods/svgf/remodulate.h), and a
// copy into the color history.
#include "core/sink.h"
#include "core/views.h"
#include "methods/svgf/remodulate.h"

namespace svgf {

// Stores a result's color alone: the feedback tap's copy out of packed storage.
struct ColorOnlySink {
  RgbView out;
  SVGF_HD void store(int i, ColorVar v) const { out.store(i, v.color); }
};

// Stores into `out` and copies the color into the history: the feedback tap's iteration.
template <class Out>
struct FeedbackTee {
  Out out;
  RgbView color_history;
  SVGF_HD void store(int i, ColorVar v) const {
    out.store(i, v);
    color_history.store(i, v.color);
  }
  // Its target's inputs (core/sink.h).
  SVGF_HD auto inputs(int i) const { return sink_inputs(out, i); }
  template <class In>
  SVGF_HD void store(const In& in, int i, ColorVar v) const {
    store_with(out, in, i, v);
    color_history.store(i, v.color);
  }
};

}  // namespace svgf
