#pragma once
// SVGF behind the Denoiser interface, written once over a backend (kernels_cpu/cpu_backend.h
// says what a backend provides; kernels_cpu/svgf_cpu.cpp and kernels_cuda/svgf_cuda.cu
// instantiate it). The history ping-pongs between two slots: a frame reads slot `slot_` and
// writes the other (the color history has one, overwritten in place: color_history_slots).
// A frame split into direct and indirect (SvgfParams::split) filters direct with the history
// below and indirect with a second one, allocated on the first split frame.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/denoiser.h"
#include "core/frame_inputs.h"
#include "methods/svgf/params.h"
#include "methods/svgf/pipeline.h"
#include "methods/svgf/stages.h"

namespace svgf {

template <class Backend>
class SvgfDenoiser final : public DenoiserOver<SvgfDenoiser<Backend>, Backend> {
 public:
  SvgfDenoiser(const SvgfParams& params, const EngineConfig& config)
      : params_(params), mode_(config.mode), keep_scratch_(config.keep_scratch),
        backend_(config) {
    params_.validate();
    if constexpr (kGuideHistory) {
      backend_.keep_previous_mesh_ids_only();
      backend_.keep_motion_in_lent_planes();
    }
    backend_.set_method_planes(
        3 * color_history_slots() + 2 * (2 + 1) + (scratch_in_history() ? 4 : 2 * 4) +
        (keep_scratch_ ? 3 + (accumulates_color() ? 4 : 1) : 0) +
        (packs_guides() ? 4 * packed_guide_slots() : 0) + (kGuideHistory && keep_scratch_ ? 3 : 0) +
        (gradient_mode() && (keep_scratch_ || params_.split != SplitMode::Off) ? 1 : 0) +
        (kGuideHistory && !motion_in_history() ? 2 : 0) + (params_.taa ? 3 * 3 : 0));
    // The frame reads the input color in the demodulation and the reprojection only, both done
    // before the remodulation (or TAA) writes the first output pixel (run_svgf_frame): the
    // output may take the color's planes on a backend that copies its inputs.
    backend_.set_output_over_color();
  }

  void reset() override { has_history_ = false; }
  const FrameReport& last_report() const override { return report_.of(backend_.engine()); }
  std::string description() const override { return "svgf " + backend_.description(); }
  std::vector<std::string> stages() const override { return svgf_stage::all(params_.taa); }
  std::vector<std::string> debug_buffers() const override {
    return svgf_buffer::all(params_.taa, keep_scratch_);
  }

  // After a split frame the history buffers are the direct signal's, and the scratch
  // (illumination, accumulated) the indirect's, which ran last.
  Image read_buffer(std::string_view name) const override {
    namespace buf = svgf_buffer;
    if (!keep_scratch_ && (name == buf::kIllumination || name == buf::kAccumulated))
      throw std::invalid_argument(
          "svgf: debug buffer '" + std::string(name) +
          "' is frame scratch the a-trous buffers overwrite; create the denoiser with "
          "keep_scratch (EngineConfig) to read it");
    const auto pick = [&]() -> const typename Backend::Buffer* {
      if (name == buf::kIllumination) return &illumination_;
      if (name == buf::kAccumulated) return &accumulated_;
      if (name == buf::kMoments) return &moments_[0][slot_];
      if (name == buf::kHistoryLength) return &history_[0][slot_];
      if (name == buf::kColorHistory) return &color_history(0, slot_);
      if (name == buf::kTaaHistory && params_.taa) return &taa_history_[slot_];
      return nullptr;
    };
    const typename Backend::Buffer* which = pick();
    if (!which) throw unknown_buffer("svgf", name, debug_buffers());
    if (backend_.width() == 0) return Image();
    const SvgfParams& last = split_history_ ? params_.indirect() : params_;  // the last signal
    if (which == &accumulated_ && !last.feeds_back_iteration()) return accumulation();
    return backend_.read(*which);
  }

 private:
  friend class DenoiserOver<SvgfDenoiser<Backend>, Backend>;  // calls denoise_frame
  // One frame, either path: `in` a Frame (host) or a DeviceFrame, `out` an Image or a
  // DeviceTarget; the backend's overloads move the data, the frame below is the same.
  template <class Source, class Target>
  void denoise_frame(const Source& in, Target& out) {
    report_.frame_started();
    check_frame(in, out);
    const bool split = splits(in);
    if (backend_.resize(in.width(), in.height())) allocate();
    if (split && !split_allocated_) allocate_split();
    // The history of a frame filtered the other way cannot continue (a single signal's holds
    // direct + indirect, a split frame's direct history holds direct only): start afresh.
    if (split != split_history_) has_history_ = false;
    auto& engine = backend_.engine();
    backend_.begin_frame(in, out);
    // The gradient samples land in scratch (a backend that copies them; the CPU reads them in
    // place): gradient_samples_planes. A backend that sanitizes in its own planes leaves that
    // stage to the frame, which fuses it into its first kernel where it can (run_svgf_frame).
    float* gradient_into = gradient_mode() ? gradient_samples_planes() : nullptr;
    const FrameInputs cur = backend_.inputs(in, /*position=*/false, split, gradient_into,
                                            /*defer_sanitize=*/true, normals_planes(),
                                            motion_planes());

    SvgfFrameBuffers b = signal_buffers(cur, 0, backend_.output(out));
    b.sanitize_pending = cur.sanitize_pending;
    b.sanitize = cur.sanitize;
    // The depth the reprojection compares: where the camera moved, the previous camera's.
    b.previous_depth = params_.reproject_camera_depth && has_history_
                           ? PreviousViewDepth::between(previous_camera_, in.camera, in.width(),
                                                        in.height())
                           : PreviousViewDepth();
    b.color = split ? cur.direct : cur.color;
    if (params_.taa) {
      b.remodulated = backend_.rgb(remodulated_);
      b.prev_taa = backend_.rgb(taa_history_[slot_]);
      b.next_taa = backend_.rgb(taa_history_[1 - slot_]);
    }
    if (gradient_mode()) {
      place_strata(b);
      if (has_gradient_samples(in)) b.gradient_samples = cur.gradient;
    }
    SvgfFrameBuffers indirect;
    if (split) {
      indirect = signal_buffers(cur, 1, backend_.rgb(indirect_output_));
      indirect.previous_depth = b.previous_depth;
      indirect.color = cur.indirect;
      indirect.emission = {};  // the emission is part of direct
    }
    if (packs_guides()) {
      b.packed_guides = indirect.packed_guides = backend_.plane(written_packed_guides(), 0);
      if (kGuideHistory)
        b.prev_packed_guides = indirect.prev_packed_guides =
            backend_.plane(previous_packed_guides(), 0);
    }
#if defined(__CUDACC__)
    if (mode_ == Mode::Fast) {
      run<SvgfFast>(engine, split, b, indirect);
    } else
#endif
    if constexpr (Backend::kPackedStorage) {
      run<SvgfExactPacked>(engine, split, b, indirect);
    } else {
      run<SvgfExact>(engine, split, b, indirect);
    }
    // The host path waits for the frame here and raises any fault of its kernels; the
    // device path returns (the faults show in last_report()).
    backend_.finish(in, out);

    slot_ = 1 - slot_;
    previous_camera_ = in.camera;
    has_history_ = true;
    split_history_ = split;
    report_.frame_done(engine);
  }

  // The accumulation as a debug buffer (color + variance) where the last signal (the indirect
  // one after a split frame, as for the shared variance plane) wrote its color into the color
  // history: no iteration of it fed back.
  Image accumulation() const {
    const Image color = backend_.read(color_history(split_history_ ? 1 : 0, slot_));
    const Image variance = backend_.read(accumulated_);
    Image out(color.width(), color.height(), 4);
    const size_t n = static_cast<size_t>(color.width()) * color.height();
    for (int c = 0; c < 3; ++c) std::copy_n(color.plane(c), n, out.plane(c));
    std::copy_n(variance.plane(accumulates_color() ? 3 : 0), n, out.plane(3));
    return out;
  }

  bool gradient_mode() const { return params_.antilag == Antilag::Gradient; }
  // The flavor run filters against packed guides: fast mode, and exact mode on a backend with
  // packed storage (methods/svgf/flavors.h).
  bool packs_guides() const { return mode_ == Mode::Fast || Backend::kPackedStorage; }

  // The previous frame's depth and normal, on a backend with packed storage (the packed
  // flavors; issue 14 item 5): the packed guides that frame wrote, kept in two slots (the
  // reprojection's taps read depth + normal as one 16-byte load), and the backend keeps only
  // its mesh ids (keep_previous_mesh_ids_only: 7 planes fewer there, 4 more here). The frame's
  // own normals are then read by the stages up to its first pixel kernel only (the sanitize
  // rule, A-SVGF's stages, the packing and the reprojection of the pixel's own), so they are
  // uploaded into a-trous buffer 1 (normals_planes), which that kernel writes the accumulation
  // into pixel by pixel, after the pixel's own normal is read and packed (run_svgf_signal,
  // methods/svgf/pipeline.h): 3 planes fewer in all. A split frame's second signal reads them
  // after the first one's accumulation, and the debug buffers' layout (keep_scratch) is the
  // one the sharing is tested against: planes of their own there.
  static constexpr bool kGuideHistory = Backend::kPackedStorage;
  int packed_guide_slots() const { return kGuideHistory ? 2 : 1; }
  // The packed guides this frame writes (the next frame's previous guides where there are two
  // slots), and those the previous frame wrote (two slots only), whose planes the scratch in the
  // history reuses: the a-trous buffer 0 in the previous slot, the gradient samples and the
  // stratum image in the written one before the first kernel writes it (scratch_in_history).
  typename Backend::Buffer& written_packed_guides() {
    return packed_guides_[packed_guide_slots() == 2 ? 1 - slot_ : 0];
  }
  typename Backend::Buffer& previous_packed_guides() { return packed_guides_[slot_]; }
  float* normals_planes() {
    if constexpr (kGuideHistory) {
      return normals_.empty() ? backend_.plane(signal_[1], 0) : backend_.plane(normals_, 0);
    } else {
      return nullptr;
    }
  }

  // The frame's motion, on a backend with packed storage (which copies the inputs; issue 14
  // item 5): the reprojection reads a pixel's own motion only, before it writes that pixel's
  // moments, and nothing reads the motion after the first pixel kernel but TAA. So it is
  // uploaded into the next moments (motion_in_history): set 0's, or, from a split frame on, the
  // indirect signal's, which only the second signal's reprojection writes, after the first
  // one's has read the motion. 2 planes fewer. With TAA, and with keep_scratch (the layout the
  // shared one is tested against), planes of their own.
  bool motion_in_history() const { return kGuideHistory && !keep_scratch_ && !params_.taa; }
  float* motion_planes() {
    if constexpr (kGuideHistory) {
      if (!motion_in_history()) return backend_.plane(motion_, 0);
      return backend_.plane(moments_[split_allocated_ ? 1 : 0][1 - slot_], 0);
    } else {
      return nullptr;
    }
  }

  // A frame has gradient samples when it carries the group and at least one stratum holds one
  // (the first frame and the frame after a cut have none); else the statistics anti-lag runs.
  // Read on the host (the frame is there on every backend); a frame with samples stops at the
  // first stratum's.
  // A device frame's are never read on the host: its view is empty on a frame without any.
  static bool has_gradient_samples(const DeviceFrame& f) { return !f.gradient.empty(); }
  static bool has_gradient_samples(const Frame& f) {
    if (f.gradient.empty()) return false;
    const float* mask = f.gradient.plane(2);
    const size_t n = f.gradient.pixel_count();
    for (size_t i = 0; i < n; ++i)
      if (mask[i] > 0.5f) return true;
    return false;
  }

  // The stratum image's planes in whole planes of the frame's size (a stratum plane is a
  // ninth of one, so one usually holds them all).
  int stratum_buffer_planes() const {
    const size_t floats = kGradientStratumPlanes * stratum_count();
    return static_cast<int>((floats + pixels() - 1) / pixels());
  }
  // Whether the stratum planes but lambda fit one plane of the frame's size (all but tiny frames:
  // a stratum plane is about a ninth of one).
  bool stratum_workspace_fits_plane() const {
    return (kGradientStratumPlanes - 1) * stratum_count() <= pixels();
  }
  size_t pixels() const { return static_cast<size_t>(backend_.width()) * backend_.height(); }
  size_t stratum_count() const {
    return static_cast<size_t>(strata_along(backend_.width())) * strata_along(backend_.height());
  }

  // Whether this frame is filtered as direct + indirect; std::invalid_argument for a frame that
  // carries half the split (when the split is not off) or none of it with split on.
  template <class Source>
  bool splits(const Source& f) const {
    if (params_.split == SplitMode::Off) return false;
    const bool direct = !f.direct.empty(), indirect = !f.indirect.empty();
    const std::string frame = "frame " + std::to_string(f.index) + ": ";
    if (direct != indirect)
      throw std::invalid_argument(frame + "channel '" + (direct ? "direct" : "indirect") +
                                  "' without '" + (direct ? "indirect" : "direct") +
                                  "': filtering them apart (--svgf-split) needs both");
    if (!direct && params_.split == SplitMode::On)
      throw std::invalid_argument(frame + "--svgf-split on needs the channels 'direct' and "
                                  "'indirect', and the frame has neither");
    return direct;
  }

  // One signal's buffers: history set `set` (0: color or direct, 1: indirect), the shared
  // scratch, and its output.
  SvgfFrameBuffers signal_buffers(const FrameInputs& cur, int set, RgbView output) {
    const int prev = slot_;
    const int next = 1 - slot_;
    SvgfFrameBuffers b;
    b.guides = cur.guides;
    b.prev_guides = backend_.previous_guides();
    b.color = cur.color;
    b.albedo = cur.albedo;
    b.emission = cur.emission;
    b.prev_color = backend_.rgb(color_history(set, prev));
    b.prev_moment1 = backend_.plane(moments_[set][prev], 0);
    b.prev_moment2 = backend_.plane(moments_[set][prev], 1);
    b.prev_history = backend_.plane(history_[set][prev], 0);
    b.next_color = backend_.rgb(color_history(set, next));
    b.color_history_in_place = color_history_slots() == 1;
    b.next_moment1 = backend_.plane(moments_[set][next], 0);
    b.next_moment2 = backend_.plane(moments_[set][next], 1);
    b.next_history = backend_.plane(history_[set][next], 0);
    b.illumination = illumination_planes();
    b.illumination_read_back = keep_scratch_;
    // The accumulation's variance (none with the scratch in the history: the variance stage
    // derives it from the moments); its color only where an iteration is fed back or the color
    // history has one slot (otherwise the pipeline accumulates into the color history,
    // methods/svgf/pipeline.h).
    auto& acc = keep_scratch_ ? accumulated_ : signal_[1];
    if (accumulates_color())
      b.accumulated = {backend_.rgb(acc),
                       scratch_in_history() ? nullptr : backend_.plane(acc, 3)};
    else
      b.accumulated = {RgbView(), backend_.plane(acc, 0)};
    // The a-trous ping-pong; with the scratch in the history, buffer 0 is the previous frame's
    // packed guides, which nothing reads after the reprojection.
    b.signal[0] = scratch_in_history() ? backend_.plane(previous_packed_guides(), 0)
                                       : backend_.plane(signal_[0], 0);
    b.signal[1] = backend_.plane(signal_[1], 0);
    b.output = output;
    return b;
  }

  template <class Flavor, class Engine>
  void run(Engine& engine, bool split, const SvgfFrameBuffers& b,
           const SvgfFrameBuffers& indirect) {
    run_svgf_frame<Flavor>(engine, b, params_, has_history_, split ? &indirect : nullptr);
  }

  // Whether a signal needs the accumulation's color planes: an iteration is fed back, or the
  // color history has one slot (which the reprojection is still reading while it accumulates).
  bool accumulates_color() const {
    return params_.feeds_back_iteration() || params_.indirect().feeds_back_iteration() ||
           color_history_slots() == 1;
  }

  // The color history's slots (issue 14 item 5). The previous frame's color history is read by
  // the reprojection alone; the next one is written after it, by the fed-back iteration or,
  // without one, by the variance stage from the accumulation (run_svgf_signal,
  // methods/svgf/pipeline.h): one slot, overwritten in place, 3 planes fewer (6 split). With
  // keep_scratch, two: the reprojection writes the accumulation's color into the next slot
  // when no iteration is fed back, the layout the shared one is tested against, bit for bit.
  int color_history_slots() const { return keep_scratch_ ? 2 : 1; }
  typename Backend::Buffer& color_history(int set, int slot) {
    return color_history_[set][keep_scratch_ ? slot : 0];
  }
  const typename Backend::Buffer& color_history(int set, int slot) const {
    return color_history_[set][keep_scratch_ ? slot : 0];
  }

  // The frame's scratch (issue 14 item 5). The illumination lives from the demodulation to the
  // end of the reprojection, the accumulation from the reprojection to the end of the variance
  // stage, and the gradient samples (in the illumination's planes) until the gradient stages
  // have read them; the a-trous buffer 0 is first written by the variance stage, buffer 1 by
  // the first a-trous iteration (run_svgf_frame, methods/svgf/pipeline.h). So, unless the
  // caller keeps the scratch to read it back, the illumination takes a-trous buffer 0's first
  // three planes and the accumulation (1 or 4 planes) buffer 1's: 4 planes fewer (5 with
  // A-SVGF's stratum image, allocate()). A split frame's two signals run these stages one after
  // the other, so they share them too. On a backend with packed storage the scratch goes
  // further, into the history (scratch_in_history below).
  RgbView illumination_planes() {
    if (keep_scratch_) return backend_.rgb(illumination_);
    if (scratch_in_history()) return RgbView();  // never stored (the first kernel's registers)
    return backend_.rgb(signal_[0]);
  }

  // The scratch in the history (issue 14 item 5): on a backend with packed storage, without
  // keep_scratch and until a split frame comes, the frame's scratch lives in planes of the
  // history that are dead while it lives, and a-trous buffer 0 is not allocated (4 planes fewer):
  // - the gradient samples and A-SVGF's stratum planes but lambda: in the next packed-guide
  //   slot (three planes, then the fourth), which the first pixel kernel writes only after the
  //   gradient stages have read them;
  // - lambda, which that kernel reads at other pixels than its own: in a-trous buffer 1's
  //   fourth plane, free in that kernel since the accumulation has no variance plane (the
  //   variance stage derives it from the moments, methods/svgf/variance.h); the frame's normals
  //   and then the accumulated color in its first three, as before;
  // - the a-trous ping-pong: buffer 0 in the previous packed-guide slot, which nothing reads
  //   after the first kernel (buffer 1 is then free too).
  // A split frame's second signal reads the previous guides and lambda after the first signal's
  // a-trous: from the first split frame on, a-trous buffer 0 and the stratum image have their
  // own planes again (allocate_split); keep_scratch keeps every buffer apart, the layout the
  // shared one is tested against (tests/svgf_packed_exact_test.cpp).
  bool scratch_in_history() const { return kGuideHistory && !keep_scratch_ && !split_allocated_; }

  // Where the gradient samples land: the next packed-guide slot (scratch_in_history) or the
  // illumination's planes, both written only after the gradient stages have read them
  // (run_svgf_frame, methods/svgf/pipeline.h).
  float* gradient_samples_planes() {
    return scratch_in_history() ? backend_.plane(written_packed_guides(), 0)
                                : illumination_planes().r;
  }

  // A-SVGF's stratum image: planes of its own, a-trous buffer 0's fourth plane (strata_shared_),
  // or the next packed-guide slot's fourth plane with lambda in a-trous buffer 1's
  // (scratch_in_history, where the planes but lambda fit one plane).
  void place_strata(SvgfFrameBuffers& b) {
    if (!strata_.empty()) {
      b.strata = backend_.plane(strata_, 0);
    } else if (strata_shared_) {
      b.strata = backend_.plane(signal_[0], 3);
    } else {
      b.strata = backend_.plane(written_packed_guides(), 3);
      b.lambda = backend_.plane(signal_[1], 3);
    }
  }

  void allocate() {
    split_allocated_ = false;
    signal_[0] = {};  // a split frame's, at the size before
    strata_ = {};
    try {
      for (int s = 0; s < 2; ++s) {
        if (s < color_history_slots())
          backend_.allocate(color_history_[0][s], 3, "color history");
        backend_.allocate(moments_[0][s], 2, "moments");
        backend_.allocate(history_[0][s], 1, "history length");
        if (s == 1 || !scratch_in_history()) backend_.allocate(signal_[s], 4, "a-trous buffers");
      }
      if (keep_scratch_) {
        backend_.allocate(illumination_, 3, "illumination");
        backend_.allocate(accumulated_, accumulates_color() ? 4 : 1, "accumulation");
      }
      if (packs_guides())
        for (int s = 0; s < packed_guide_slots(); ++s)
          backend_.allocate(packed_guides_[s], 4, "packed guides");
      normals_ = {};  // a split frame's, at the size before
      if (kGuideHistory && keep_scratch_) backend_.allocate(normals_, 3, "frame normals");
      motion_ = {};
      if (kGuideHistory && !motion_in_history()) backend_.allocate(motion_, 2, "frame motion");
      if (params_.taa) {
        backend_.allocate(remodulated_, 3, "remodulated color");
        for (auto& t : taa_history_) backend_.allocate(t, 3, "TAA history");
      }
      // A-SVGF's stratum image lives from the gradient stages to the end of the reprojection
      // (its lambda): with the scratch in the history where its planes but lambda fit one plane
      // (scratch_in_history), else in a-trous buffer 0's fourth plane where it fits one, beside
      // the gradient samples and the illumination; from a split frame on in planes of its own
      // (its indirect signal reads lambda after the direct signal's variance stage has written
      // buffer 0).
      const bool in_history = scratch_in_history() && stratum_workspace_fits_plane();
      strata_shared_ = gradient_mode() && !keep_scratch_ && !scratch_in_history() &&
                       stratum_buffer_planes() == 1;
      if (gradient_mode() && !strata_shared_ && !in_history)
        backend_.allocate(strata_, stratum_buffer_planes(), "gradient strata");
    } catch (...) {
      release();  // nothing half-made stays; a later frame may try again
      throw;
    }
    has_history_ = false;
  }

  // The indirect signal's history and output, on the first split frame at this size.
  void allocate_split() {
    try {
      for (int s = 0; s < 2; ++s) {
        if (s < color_history_slots())
          backend_.allocate(color_history_[1][s], 3, "indirect color history");
        backend_.allocate(moments_[1][s], 2, "indirect moments");
        backend_.allocate(history_[1][s], 1, "indirect history length");
      }
      backend_.allocate(indirect_output_, 3, "indirect output");
      if (kGuideHistory && normals_.empty()) backend_.allocate(normals_, 3, "frame normals");
      if (signal_[0].empty()) backend_.allocate(signal_[0], 4, "a-trous buffers");
      if (gradient_mode() && strata_.empty())
        backend_.allocate(strata_, stratum_buffer_planes(), "gradient strata");
      strata_shared_ = false;
    } catch (...) {
      release();
      throw;
    }
    split_allocated_ = true;
    has_history_ = false;
  }

  void release() {
    for (int s = 0; s < 2; ++s) {
      for (int set = 0; set < 2; ++set) {
        color_history_[set][s] = {};
        moments_[set][s] = {};
        history_[set][s] = {};
      }
      signal_[s] = {};
      taa_history_[s] = {};
    }
    remodulated_ = {};
    indirect_output_ = {};
    split_allocated_ = false;
    illumination_ = {};
    accumulated_ = {};
    packed_guides_[0] = {};
    packed_guides_[1] = {};
    normals_ = {};
    motion_ = {};
    strata_ = {};
    strata_shared_ = false;
    backend_.release();
  }

  SvgfParams params_;
  Mode mode_;
  bool keep_scratch_;
  bool strata_shared_ = false;  // the stratum image in a-trous buffer 0's fourth plane
  Backend backend_;
  int slot_ = 0;  // history slot the next frame reads
  bool has_history_ = false;
  Camera previous_camera_;  // the camera of the frame the history comes from
  bool split_history_ = false;    // the history is a split frame's
  bool split_allocated_ = false;  // the indirect history exists at this size
  // History per signal ([0]: color or direct, [1]: indirect) and slot.
  typename Backend::Buffer color_history_[2][2], moments_[2][2], history_[2][2];
  typename Backend::Buffer illumination_, accumulated_, signal_[2], packed_guides_[2], strata_;
  typename Backend::Buffer normals_;  // the frame's normals where a-trous buffer 1 cannot take them
  typename Backend::Buffer motion_;   // the frame's motion where the next moments cannot take it
  typename Backend::Buffer indirect_output_;
  typename Backend::Buffer remodulated_, taa_history_[2];  // only with TAA
  LastReport report_;
};

}  // namespace svgf
