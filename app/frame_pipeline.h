#pragma once
// svgf denoise's frame loop as a bounded pipeline: reading frame N+1, denoising frame N and
// writing frame N-1 overlap (docs/cli.md). Three stages, each serial and in frame order, so each
// behaves as in a plain loop: the denoiser, which keeps history, sees the frames one at a time
// in order, and the outputs and the report are written in order.
//
// Errors travel with their item: what the first or second stage throws is kept with the item and
// handed to the last stage in order, which throws it. So only the last stage ever throws, after
// every earlier item was finished whole, and the run fails at the same item, with the same
// outputs written before it, as the plain loop; after a failed item none is read or processed.
#include <atomic>
#include <exception>
#include <limits>
#include <utility>
#include <vector>

#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include "kernels_cpu/ieee_guard.h"

namespace svgf::app {

// The pipeline's stages, in order; a failure names the one that threw.
enum class FrameStep { Read, Denoise, Write };
inline const char* to_string(FrameStep step) {
  return step == FrameStep::Read ? "read" : step == FrameStep::Denoise ? "denoise" : "write";
}

// What the first or second stage threw, handed to the last with its item.
struct StageFailure {
  FrameStep step = FrameStep::Read;
  std::exception_ptr error;  // null: none
};

// Runs items 0..count-1 through read(index, Item&), process(Item&) and
// finish(Item&, const StageFailure&), at most `in_flight` items at once (>= 1; 1 is the plain
// loop: each item finished before the next is read). process is skipped for an item whose read
// failed and for any item after a failed one; finish gets the failure and must throw (it is
// rethrown if finish returns). Each call
// runs with the IEEE float environment (kernels_cpu/ieee_guard.h: TBB's threads need not have
// the caller's) and isolated, so that waiting inside one stage never runs another stage's work
// on the same thread (a stage's time is its own).
template <class Item, class Read, class Process, class Finish>
void run_frame_pipeline(int count, int in_flight, Read read, Process process, Finish finish) {
  struct Slot {
    int index = -1;
    Item item;
    StageFailure failure;
  };
  if (in_flight < 1) in_flight = 1;
  // One slot per item in flight, owned here: item k uses slot k % in_flight, free again by then
  // (TBB reads item k + in_flight only after item k left the last stage). Nothing leaks when a
  // throw cancels the pipeline with items between stages.
  std::vector<Slot> slots(static_cast<size_t>(in_flight));
  const auto guarded = [](auto&& body) {
    tbb::this_task_arena::isolate([&] {
      cpu::ScopedIeeeFloat ieee;
      body();
    });
  };
  // The first item that failed: none after it is read or processed (its failure ends the run).
  constexpr int kNone = std::numeric_limits<int>::max();
  std::atomic<int> first_failed{kNone};
  const auto fail = [&](Slot& slot, FrameStep step) {
    slot.failure = {step, std::current_exception()};
    int seen = first_failed.load();
    while (slot.index < seen && !first_failed.compare_exchange_weak(seen, slot.index)) {
    }
  };
  int next = 0;  // the first stage's alone (serial)
  tbb::parallel_pipeline(
      static_cast<size_t>(in_flight),
      tbb::make_filter<void, Slot*>(
          tbb::filter_mode::serial_in_order,
          [&](tbb::flow_control& fc) -> Slot* {
            if (first_failed.load() != kNone || next >= count) {
              fc.stop();
              return nullptr;
            }
            Slot* slot = &slots[static_cast<size_t>(next % in_flight)];
            slot->index = next++;
            try {
              guarded([&] { read(slot->index, slot->item); });
            } catch (...) {
              fail(*slot, FrameStep::Read);
            }
            return slot;
          }) &
          tbb::make_filter<Slot*, Slot*>(
              tbb::filter_mode::serial_in_order,
              [&](Slot* slot) {
                if (slot->failure.error || slot->index > first_failed.load()) return slot;
                try {
                  guarded([&] { process(slot->item); });
                } catch (...) {
                  fail(*slot, FrameStep::Denoise);
                }
                return slot;
              }) &
          tbb::make_filter<Slot*, void>(tbb::filter_mode::serial_in_order, [&](Slot* slot) {
            // An item after a failed one never gets here: the failed one's finish threw.
            const StageFailure failure = std::exchange(slot->failure, {});
            Item item = std::exchange(slot->item, Item{});  // the slot's memory freed with it
            guarded([&] { finish(item, failure); });
            if (failure.error) std::rethrow_exception(failure.error);
          }));
}

}  // namespace svgf::app
