#pragma once
// Sinks: where a kernel stores a pixel's result (anything with store(i, value): a buffer view,
// or a sink that computes on the way, such as a remodulation). A sink may read inputs of its
// own for pixel i (the remodulation reads albedo and emission): it then has inputs(i) and
// store(inputs, i, value). A kernel that works long before it stores fetches them first,
// `const auto in = sink_inputs(sink, i)`, and stores with `store_with(sink, in, i, value)`, so
// the sink's loads overlap the kernel's work instead of waiting at the end of the thread.
#include <type_traits>
#include <utility>

#include "core/hd.h"

namespace svgf {

struct NoSinkInputs {};

template <class Sink, class = void>
struct SinkHasInputs : std::false_type {};
template <class Sink>
struct SinkHasInputs<Sink, std::void_t<decltype(std::declval<const Sink&>().inputs(0))>>
    : std::true_type {};

template <class Sink>
SVGF_HD auto sink_inputs(const Sink& sink, int i) {
  if constexpr (SinkHasInputs<Sink>::value) return sink.inputs(i);
  else return NoSinkInputs{};
}
template <class Sink, class In, class V>
SVGF_HD void store_with(const Sink& sink, const In& in, int i, const V& v) {
  if constexpr (SinkHasInputs<Sink>::value) sink.store(in, i, v);
  else sink.store(i, v);
}

}  // namespace svgf
