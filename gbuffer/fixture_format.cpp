#include "gbuffer/fixture_format.h"

#include <Imath/half.h>

#include <cmath>
#include <cstring>
#include <sstream>

namespace svgf::gbuffer {

std::string generator_tag() { return "svgf-fixtures " + std::to_string(kGeneratorVersion); }

io::FrameStorage fixture_storage() {
  io::FrameStorage s;
  s.color = io::PixelStorage::Half;
  s.reference = io::PixelStorage::Half;
  s.albedo = io::PixelStorage::Half;
  s.normal = io::PixelStorage::Half;
  s.position = io::PixelStorage::Half;
  s.depth = io::PixelStorage::Float;
  s.motion = io::PixelStorage::Float;
  return s;
}

float quantize(float v, io::PixelStorage storage) {
  if (storage == io::PixelStorage::Float) return v;
  return static_cast<float>(Imath::half(v));
}

RenderSettings settings_from_manifest(const io::Manifest& m) {
  RenderSettings s;
  s.width = m.width;
  s.height = m.height;
  s.spp = m.spp;
  s.reference_spp = m.reference_spp;
  s.seed = m.seed;
  return s;
}

namespace {

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

class Comparer {
 public:
  Comparer(const CompareOptions& o, std::vector<ChannelDiff>& out) : opt_(o), out_(out) {}

  void image(const Image& stored, const Image& rendered, const char* const* names,
             io::PixelStorage storage) {
    if (stored.empty()) return;
    if (rendered.empty() || rendered.channels() != stored.channels() ||
        rendered.width() != stored.width() || rendered.height() != stored.height()) {
      ChannelDiff d;
      d.channel = std::string(names[0]) + " (missing or wrongly sized in the render)";
      d.count = stored.pixel_count();
      out_.push_back(d);
      return;
    }
    for (int c = 0; c < stored.channels(); ++c) {
      ChannelDiff d;
      d.channel = names[c];
      const float* a = stored.plane(c);
      const float* b = rendered.plane(c);
      for (size_t i = 0; i < stored.pixel_count(); ++i) {
        const float q = quantize(b[i], storage);
        if (same_bits(a[i], q)) continue;
        const double diff = std::fabs(static_cast<double>(a[i]) - q);
        if (opt_.tolerance > 0.f && diff <= opt_.tolerance * std::fmax(1.0, std::fabs(a[i])))
          continue;
        note(d, i, stored.width(), a[i], q);
      }
      if (d.count) out_.push_back(d);
    }
  }

  void ids(const Frame& stored, const Frame& rendered) {
    ChannelDiff d;
    d.channel = io::channel::kMeshId;
    if (rendered.mesh_id.size() != stored.mesh_id.size()) {
      d.count = stored.mesh_id.size();
      out_.push_back(d);
      return;
    }
    for (size_t i = 0; i < stored.mesh_id.size(); ++i)
      if (stored.mesh_id[i] != rendered.mesh_id[i])
        note(d, i, stored.width(), stored.mesh_id[i], rendered.mesh_id[i]);
    if (d.count) out_.push_back(d);
  }

  void camera(const Camera& a, const Camera& b) {
    ChannelDiff d;
    d.channel = "camera";
    for (int k = 0; k < 16; ++k) {
      if (!same_bits(a.world_to_view[k], b.world_to_view[k])) ++d.count;
      if (!same_bits(a.view_to_clip[k], b.view_to_clip[k])) ++d.count;
    }
    if (d.count) out_.push_back(d);
  }

 private:
  static void note(ChannelDiff& d, size_t i, int width, double stored, double rendered) {
    ++d.count;
    const double diff = std::fabs(stored - rendered);
    d.max_abs = std::isnan(diff) ? INFINITY : std::fmax(d.max_abs, diff);
    if (d.pixels.size() < kListedPixels) {
      const auto w = static_cast<size_t>(width);
      d.pixels.push_back({static_cast<int>(i % w), static_cast<int>(i / w), stored, rendered});
    }
  }
  static constexpr size_t kListedPixels = 4;
  const CompareOptions& opt_;
  std::vector<ChannelDiff>& out_;
};

}  // namespace

std::vector<ChannelDiff> compare_frames(const Frame& stored, const Frame& rendered,
                                        const io::FrameStorage& st, const CompareOptions& opt) {
  namespace ch = io::channel;
  std::vector<ChannelDiff> out;
  if (stored.width() != rendered.width() || stored.height() != rendered.height()) {
    ChannelDiff d;
    d.channel = "size";
    d.count = 1;
    out.push_back(d);
    return out;
  }
  Comparer c(opt, out);
  c.image(stored.color, rendered.color, ch::kColor, st.color);
  c.image(stored.albedo, rendered.albedo, ch::kAlbedo, st.albedo);
  c.image(stored.emission, rendered.emission, ch::kEmission, st.color);
  c.image(stored.normal, rendered.normal, ch::kNormal, st.normal);
  c.image(stored.position, rendered.position, ch::kPosition, st.position);
  c.image(stored.depth, rendered.depth, &ch::kDepth, st.depth);
  c.image(stored.depth_gradient, rendered.depth_gradient, ch::kDepthGradient, st.depth);
  c.image(stored.motion, rendered.motion, ch::kMotion, st.motion);
  c.ids(stored, rendered);
  if (opt.reference) c.image(stored.reference, rendered.reference, ch::kReference, st.reference);
  c.image(stored.direct, rendered.direct, ch::kDirect, st.color);
  c.image(stored.indirect, rendered.indirect, ch::kIndirect, st.color);
  c.image(stored.gradient, rendered.gradient, ch::kGradient, io::PixelStorage::Float);
  c.camera(stored.camera, rendered.camera);
  return out;
}

std::string describe(const ChannelDiff& d) {
  std::ostringstream s;
  s.precision(9);
  s << "channel " << d.channel << ": " << d.count << " value" << (d.count == 1 ? "" : "s")
    << " differ";
  if (d.max_abs > 0.0) s << ", max |diff| " << d.max_abs;
  for (size_t k = 0; k < d.pixels.size(); ++k) {
    const PixelDiff& p = d.pixels[k];
    s << (k ? "; " : ": ") << "(" << p.x << ", " << p.y << ") file " << p.stored << " render "
      << p.rendered;
  }
  if (d.count > d.pixels.size()) s << "; ...";
  return s.str();
}

}  // namespace svgf::gbuffer
