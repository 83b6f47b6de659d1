#pragma once
// BMFR's blocks (paper Sec. 4.2): the image is cut into 32x32 blocks, each fitted on its own.
// The grid moves every frame by one of 16 offsets (the authors' BLOCK_OFFSETS, in [-16, 16]),
// so the seams between blocks move and the post-accumulation averages them away. The grid's
// origin is offset - 16: the blocks along the image's edges stick out, and their rows outside
// the image repeat the image mirrored (as the authors' workset does), so every block has 1024
// rows.
#include "core/block_reduce.h"
#include "core/hd.h"

namespace svgf {

namespace bmfr {
constexpr int kBlockSize = 32;
static_assert(kBlockSize * kBlockSize == block::kRows, "a BMFR block is one block of rows");
constexpr int kOffsetCount = 16;
}  // namespace bmfr

struct BmfrGrid {
  int width = 0, height = 0;  // the image
  int origin_x = 0, origin_y = 0;  // image coordinates of block (0, 0)'s first pixel
  int blocks_x = 0, blocks_y = 0;

  // The grid of frame `frame` (frames count from 0 for the denoiser's lifetime).
  SVGF_HD static BmfrGrid of(int width, int height, int frame) {
    constexpr int kOffsets[bmfr::kOffsetCount][2] = {
        {-14, -14}, {4, -6}, {-8, 14}, {8, 0},    {-10, -8}, {2, 12},  {12, -12}, {-10, 0},
        {12, 14},   {-8, -16}, {6, 6}, {-2, -2}, {6, -14}, {-16, 12}, {14, -4},  {-6, 4}};
    const int k = frame % bmfr::kOffsetCount;
    BmfrGrid g;
    g.width = width;
    g.height = height;
    g.origin_x = kOffsets[k][0] - bmfr::kBlockSize / 2;
    g.origin_y = kOffsets[k][1] - bmfr::kBlockSize / 2;
    g.blocks_x = (width - 1 - g.origin_x) / bmfr::kBlockSize + 1;
    g.blocks_y = (height - 1 - g.origin_y) / bmfr::kBlockSize + 1;
    return g;
  }
  SVGF_HD int blocks() const { return blocks_x * blocks_y; }
  // The block image pixel (x, y) belongs to.
  SVGF_HD int block_of(int x, int y) const {
    return ((y - origin_y) / bmfr::kBlockSize) * blocks_x + (x - origin_x) / bmfr::kBlockSize;
  }
  // The image pixel (linear index) of row r of block b: rows go along x, then y, inside the
  // block; outside the image, mirrored back in.
  SVGF_HD int pixel_of(int b, int r) const {
    const int x = origin_x + (b % blocks_x) * bmfr::kBlockSize + r % bmfr::kBlockSize;
    const int y = origin_y + (b / blocks_x) * bmfr::kBlockSize + r / bmfr::kBlockSize;
    return mirror(y, height) * width + mirror(x, width);
  }
  // True when row r of block b lies inside the image (not a mirrored copy).
  SVGF_HD bool row_inside(int b, int r) const {
    const int x = origin_x + (b % blocks_x) * bmfr::kBlockSize + r % bmfr::kBlockSize;
    const int y = origin_y + (b / blocks_x) * bmfr::kBlockSize + r / bmfr::kBlockSize;
    return x >= 0 && y >= 0 && x < width && y < height;
  }

  // Reflection about the edges (edge pixels not repeated: -1 -> 0, -2 -> 1, n -> n - 1), for
  // any distance outside (an image smaller than a block reflects more than once).
  SVGF_HD static int mirror(int i, int n) {
    const int period = 2 * n;
    int m = i % period;
    if (m < 0) m += period;
    return m < n ? m : period - 1 - m;
  }
};

}  // namespace svgf
