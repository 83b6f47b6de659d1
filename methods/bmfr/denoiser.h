#pragma once
// BMFR (Koskela et al. 2019) behind the Denoiser interface, written once over a backend
// (kernels_cpu/cpu_backend.h says what a backend provides). A frame's data flow:
//   sanitize      the backend's: bad input repaired and counted (core/sanitize.h)
//   accumulate    color -> demodulated illumination, blended with its reprojected history
//                 -> noisy (the next frame's history too), history length, reprojection
//   regression    per 32x32 block (the grid moves every frame): features and noisy ->
//                 the block's weights, by a Householder QR (regression.h)
//   weighted_sum  each pixel's features x its block's weights -> filtered (a block without a
//                 fit: noisy, the pixels counted in the report as fallback_pixels)
//   post          filtered blended with the reprojected accumulated output -> accumulated
//                 (history); x albedo + emission -> output
//   taa           (--bmfr-taa) the output blended with the previous TAA output, clamped to
//                 its neighbourhood (core/taa.h) -> output and the TAA history
// The histories ping-pong between two slots: a frame reads slot `slot_` and writes the other.
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/arith.h"
#include "core/denoiser.h"
#include "core/frame_inputs.h"
#include "core/taa.h"
#include "methods/bmfr/accumulate.h"
#include "methods/bmfr/blocks.h"
#include "methods/bmfr/params.h"
#include "methods/bmfr/post.h"
#include "methods/bmfr/regression.h"
#include "methods/bmfr/weighted_sum.h"

namespace svgf {

namespace bmfr_stage {
inline constexpr const char* kAccumulate = "accumulate";
inline constexpr const char* kRegression = "regression";
inline constexpr const char* kWeightedSum = "weighted_sum";
inline constexpr const char* kPost = "post";
inline constexpr const char* kTaa = "taa";
}  // namespace bmfr_stage

namespace bmfr_buffer {
inline constexpr const char* kNoisy = "noisy";              // pre-accumulated illumination
inline constexpr const char* kLength = "history_length";    // samples in the history
inline constexpr const char* kFiltered = "filtered";        // the regression's output
inline constexpr const char* kAccumulated = "accumulated";  // post-accumulated illumination
inline constexpr const char* kRank = "block_rank";          // columns kept, per block (1 x blocks)
inline constexpr const char* kCondition = "block_condition";  // max / min |R_ii|, per block
}  // namespace bmfr_buffer

struct BmfrFrameBuffers {
  FrameInputs in;  // with world positions
  ConstRgbView prev_position, prev_normal, prev_noisy, prev_accumulated;
  const float* prev_length = nullptr;
  RgbView position, normal, noisy, accumulated;
  float* length = nullptr;
  BmfrReprojectionView reprojection;
  RgbView filtered;
  BmfrBlockData blocks;
  // With TAA: post writes `remodulated`, TAA reads it and the previous TAA output `prev_taa`
  // and writes `taa` and `output`. Without: post writes `output`.
  RgbView remodulated;
  ConstRgbView prev_taa;
  RgbView taa;
  RgbView output;
};

template <class Arith, class Engine>
void run_bmfr_frame(Engine& engine, const BmfrFrameBuffers& b, const BmfrParams& p, int frame,
                    bool has_history) {
  namespace stage = bmfr_stage;
  const GuideView& g = b.in.guides;
  const int w = g.width, h = g.height;

  BmfrAccumulate acc;
  acc.guides = g;
  acc.position = b.in.position;
  acc.color = b.in.color;
  acc.albedo = b.in.albedo;
  acc.emission = b.in.emission;
  acc.prev_position = b.prev_position;
  acc.prev_normal = b.prev_normal;
  acc.prev_noisy = b.prev_noisy;
  acc.prev_length = b.prev_length;
  acc.position_out = b.position;
  acc.normal_out = b.normal;
  acc.noisy = b.noisy;
  acc.length = b.length;
  acc.reprojection = b.reprojection;
  acc.has_history = has_history;
  acc.alpha = p.pre_alpha;
  acc.position_limit_sq = p.position_limit_sq;
  acc.normal_limit_sq = p.normal_limit_sq;
  acc.albedo_epsilon = p.albedo_epsilon;
  engine.run(stage::kAccumulate, acc, w, h);

  const BmfrGrid grid = BmfrGrid::of(w, h, frame);
  BmfrFit<Arith> fit;
  fit.grid = grid;
  fit.guides = g;
  fit.position = b.in.position;
  fit.noisy = b.noisy;
  fit.length = b.length;
  fit.out = b.blocks;
  fit.frame = frame;
  fit.strategy = p.rank_strategy;
  fit.noise_amount = p.noise_amount;
  fit.skip_threshold = p.skip_threshold;
  engine.run_blocks(stage::kRegression, fit, grid.blocks());

  engine.run_tallying(stage::kWeightedSum,
             BmfrWeightedSum<Arith>{grid, g, b.in.position, b.noisy, b.blocks, b.filtered}, w, h);

  BmfrPostAccumulate post;
  post.width = w;
  post.height = h;
  post.filtered = b.filtered;
  post.reprojection = b.reprojection;
  post.length = b.length;
  post.prev_accumulated = b.prev_accumulated;
  post.accumulated = b.accumulated;
  post.albedo = b.in.albedo;
  post.emission = b.in.emission;
  post.output = p.taa ? b.remodulated : b.output;
  post.has_history = has_history;
  post.alpha = p.post_alpha;
  post.albedo_epsilon = p.albedo_epsilon;
  engine.run(stage::kPost, post, w, h);

  if (!p.taa) return;
  TemporalAntiAliasing taa;
  taa.guides = g;
  taa.current = b.remodulated;
  taa.history = b.prev_taa;
  taa.history_out = b.taa;
  taa.output = b.output;
  taa.has_history = has_history;
  taa.alpha = p.taa_alpha;
  engine.run(stage::kTaa, taa, w, h);
}

template <class Backend>
class BmfrDenoiser final : public DenoiserOver<BmfrDenoiser<Backend>, Backend> {
 public:
  BmfrDenoiser(const BmfrParams& params, const EngineConfig& config)
      : params_(params), mode_(config.mode), backend_(config) {
    params_.validate();
    backend_.set_method_planes(2 * history_planes() + frame_data_planes() + 1);  // + blocks
  }

  void reset() override { has_history_ = false; }
  const FrameReport& last_report() const override { return report_.of(backend_.engine()); }
  std::string description() const override {
    return std::string("bmfr (") + to_string(params_.rank_strategy) +
           (params_.taa ? ", taa" : "") + ") " + backend_.description();
  }
  std::vector<std::string> stages() const override {
    std::vector<std::string> s = {kSanitizeStage, bmfr_stage::kAccumulate,
                                  bmfr_stage::kRegression, bmfr_stage::kWeightedSum,
                                  bmfr_stage::kPost};
    if (params_.taa) s.push_back(bmfr_stage::kTaa);
    return s;
  }
  std::vector<std::string> debug_buffers() const override {
    return {bmfr_buffer::kNoisy, bmfr_buffer::kLength, bmfr_buffer::kFiltered,
            bmfr_buffer::kAccumulated, bmfr_buffer::kRank, bmfr_buffer::kCondition};
  }
  // Buffers of the last frame. block_rank and block_condition are 1 row of the last frame's
  // blocks (row-major over its grid, which moves every frame).
  Image read_buffer(std::string_view name) const override {
    const bool known = name == bmfr_buffer::kNoisy || name == bmfr_buffer::kLength ||
                       name == bmfr_buffer::kFiltered || name == bmfr_buffer::kAccumulated ||
                       name == bmfr_buffer::kRank || name == bmfr_buffer::kCondition;
    if (!known) throw unknown_buffer("bmfr", name, debug_buffers());
    if (backend_.width() == 0) return Image();
    const Image h = backend_.read(history_[slot_]);  // written by the last frame
    if (name == bmfr_buffer::kNoisy) return h.channels_from(kNoisy, 3);
    if (name == bmfr_buffer::kAccumulated) return h.channels_from(kAccumulated, 3);
    if (name == bmfr_buffer::kLength) return h.channels_from(kLength, 1);
    if (name == bmfr_buffer::kFiltered) return backend_.read(frame_data_).channels_from(3, 3);
    const Image all = backend_.read(blocks_);
    const int at = name == bmfr_buffer::kRank ? BmfrBlockData::kFloats - 2
                                              : BmfrBlockData::kFloats - 1;
    Image per_block(last_grid_.blocks(), 1, 1);
    for (int k = 0; k < last_grid_.blocks(); ++k)
      per_block.at(k, 0, 0) = all.plane(0)[k * BmfrBlockData::kFloats + at];
    return per_block;
  }

 private:
  friend class DenoiserOver<BmfrDenoiser<Backend>, Backend>;  // calls denoise_frame
  // One frame, either path: a Frame into an Image, or a DeviceFrame into a DeviceTarget (the
  // backend's overloads move the data; the frame is the same).
  template <class Source, class Target>
  void denoise_frame(const Source& in, Target& out) {
    report_.frame_started();
    check_frame(in, out);
    if (in.position.empty())
      throw std::invalid_argument("frame " + std::to_string(in.index) +
                                  ": bmfr needs the 'position' channel (world positions)");
    if (backend_.resize(in.width(), in.height())) allocate(in.width(), in.height());
    auto& engine = backend_.engine();
    backend_.begin_frame(in, out);
    const int prev = slot_, next = 1 - slot_;
    BmfrFrameBuffers b;
    b.in = backend_.inputs(in, /*position=*/true);
    b.prev_position = backend_.rgb(history_[prev], kPosition);
    b.prev_normal = backend_.rgb(history_[prev], kNormal);
    b.prev_noisy = backend_.rgb(history_[prev], kNoisy);
    b.prev_accumulated = backend_.rgb(history_[prev], kAccumulated);
    b.prev_length = backend_.plane(history_[prev], kLength);
    b.position = backend_.rgb(history_[next], kPosition);
    b.normal = backend_.rgb(history_[next], kNormal);
    b.noisy = backend_.rgb(history_[next], kNoisy);
    b.accumulated = backend_.rgb(history_[next], kAccumulated);
    b.length = backend_.plane(history_[next], kLength);
    b.reprojection = {backend_.plane(frame_data_, 0), backend_.plane(frame_data_, 1),
                      backend_.plane(frame_data_, 2)};
    b.filtered = backend_.rgb(frame_data_, 3);
    if (params_.taa) {
      b.remodulated = backend_.rgb(frame_data_, kRemodulated);
      b.prev_taa = backend_.rgb(history_[prev], kTaa);
      b.taa = backend_.rgb(history_[next], kTaa);
    }
    b.blocks.data = backend_.plane(blocks_, 0);
    b.output = backend_.output(out);
#if defined(__CUDACC__)
    if (mode_ == Mode::Fast)
      run_bmfr_frame<FastArith>(engine, b, params_, frame_, has_history_);
    else
#endif
      run_bmfr_frame<ExactArith>(engine, b, params_, frame_, has_history_);
    backend_.finish(in, out);  // the host path waits here, the device path does not
    last_grid_ = BmfrGrid::of(in.width(), in.height(), frame_);
    slot_ = next;
    has_history_ = true;
    ++frame_;
    report_.frame_done(engine);
  }

  // The planes of a history slot (the TAA output only with TAA), and of the frame's data.
  enum : int { kPosition = 0, kNormal = 3, kNoisy = 6, kAccumulated = 9, kLength = 12, kTaa = 13 };
  enum : int { kRemodulated = 6 };
  int history_planes() const { return params_.taa ? kTaa + 3 : kTaa; }
  int frame_data_planes() const { return params_.taa ? kRemodulated + 3 : kRemodulated; }

  void allocate(int w, int h) {
    for (int s = 0; s < 2; ++s) backend_.allocate(history_[s], history_planes(), "bmfr history");
    backend_.allocate(frame_data_, frame_data_planes(),
                      "bmfr reprojection, filtered and remodulated color");
    // The most blocks any frame's grid has (an offset of -16 adds a column and a row).
    const long long blocks = static_cast<long long>(w / bmfr::kBlockSize + 2) *
                             (h / bmfr::kBlockSize + 2);
    const long long pixels = static_cast<long long>(w) * h;
    const int planes =
        static_cast<int>((blocks * BmfrBlockData::kFloats + pixels - 1) / pixels);
    backend_.allocate(blocks_, planes, "bmfr block weights");
    has_history_ = false;
  }

  BmfrParams params_;
  Mode mode_;
  Backend backend_;
  typename Backend::Buffer history_[2], frame_data_, blocks_;
  int slot_ = 0;   // history_[slot_] is what the next frame reads
  int frame_ = 0;  // frames since construction: picks the grid's offset and the noise
  BmfrGrid last_grid_;
  bool has_history_ = false;
  LastReport report_;
};

}  // namespace svgf
