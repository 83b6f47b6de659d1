#include "kernels_cuda/host_staging.h"

#include <algorithm>
#include <cstring>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace svgf::cuda {

namespace {
// Large enough that a piece costs far more than scheduling it (~0.1 ms at 10 GB/s), small
// enough that a 1080p plane (8 MB) spreads over 8 threads.
constexpr size_t kPieceBytes = size_t(1) << 20;
}  // namespace

struct HostStaging::Arena {
  tbb::task_arena arena;
  explicit Arena(int threads) : arena(threads > 0 ? threads : tbb::task_arena::automatic) {}
};

HostStaging::HostStaging(int threads) : arena_(std::make_unique<Arena>(threads)) {}
HostStaging::~HostStaging() = default;

void HostStaging::run() {
  // Piece k of the whole list: copies in order, each cut into kPieceBytes pieces.
  std::vector<size_t> first_piece(copies_.size() + 1, 0);
  for (size_t i = 0; i < copies_.size(); ++i)
    first_piece[i + 1] = first_piece[i] + (copies_[i].bytes + kPieceBytes - 1) / kPieceBytes;
  const size_t pieces = first_piece.back();
  arena_->arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pieces), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t p = r.begin(); p != r.end(); ++p) {
        const size_t i =
            static_cast<size_t>(std::upper_bound(first_piece.begin(), first_piece.end(), p) -
                                first_piece.begin()) - 1;
        const HostCopy& c = copies_[i];
        const size_t offset = (p - first_piece[i]) * kPieceBytes;
        const size_t bytes = std::min(kPieceBytes, c.bytes - offset);
        std::memcpy(static_cast<char*>(c.dst) + offset, static_cast<const char*>(c.src) + offset,
                    bytes);
      }
    });
  });
  copies_.clear();
}

}  // namespace svgf::cuda
