#include "app/import_frame.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "app/import_derive.h"
#include "io/image_file.h"
#include "io/io_error.h"

namespace fs = std::filesystem;

namespace svgf::app {

const std::vector<std::string>& import_buffer_keys() {
  static const std::vector<std::string> keys = {
      "color", "albedo", "normal", "depth",     "depth-gradient", "position",
      "motion", "id",    "emission", "reference", "matrices"};
  return keys;
}

namespace {

// The placeholder's position, length and width (0: plain decimal); npos when there is none.
struct Placeholder {
  size_t at = std::string::npos, length = 0;
  int width = 0;
};

Placeholder find_placeholder(const std::string& pattern) {
  Placeholder p;
  const size_t at = pattern.find("{N");
  if (at == std::string::npos) return p;
  const size_t close = pattern.find('}', at);
  if (close == std::string::npos)
    throw std::invalid_argument("pattern '" + pattern + "': '{N' without '}'");
  const std::string inner = pattern.substr(at + 2, close - at - 2);
  if (!inner.empty()) {
    if (inner[0] != ':' || inner.size() < 2 || inner.size() > 2 ||
        !std::isdigit(static_cast<unsigned char>(inner[1])) || inner[1] == '0')
      throw std::invalid_argument("pattern '" + pattern +
                                  "': the placeholder is {N} or {N:W} with a width W of 1 to 9");
    p.width = inner[1] - '0';
  }
  if (pattern.find("{N", close) != std::string::npos)
    throw std::invalid_argument("pattern '" + pattern + "': more than one {N}");
  p.at = at;
  p.length = close + 1 - at;
  return p;
}

bool is_integral(float v) { return std::floor(v) == v; }

// Reads the buffers of one frame; every failure names the frame, the buffer and the file.
class BufferReader {
 public:
  BufferReader(const ImportSpec& spec, int n) : spec_(spec), n_(n) {}

  bool has(const std::string& key) const { return spec_.patterns.count(key) != 0; }
  std::string path(const std::string& key) const {
    return (fs::path(spec_.in_dir) / expand_pattern(spec_.patterns.at(key), n_)).string();
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw io::IoError(prefix(key) + path(key) + ": " + what);
  }
  std::string prefix(const std::string& key) const {
    return "frame " + std::to_string(n_) + ", buffer '" + key + "': ";
  }

  // The first `channels` channels of the key's file; `finite`: every value must be finite.
  Image read(const std::string& key, int channels, bool finite) {
    Image im;
    try {
      im = io::read_image(path(key));
    } catch (const io::IoError& e) {
      throw io::IoError(prefix(key) + e.what());
    }
    if (width_ == 0) {
      width_ = im.width();
      height_ = im.height();
    } else if (im.width() != width_ || im.height() != height_) {
      fail(key, "is " + std::to_string(im.width()) + "x" + std::to_string(im.height()) +
                    ", the color is " + std::to_string(width_) + "x" + std::to_string(height_));
    }
    if (im.channels() < channels)
      fail(key, "has " + std::to_string(im.channels()) + " channel" +
                    (im.channels() == 1 ? "" : "s") + ", needs " + std::to_string(channels));
    if (im.channels() > channels) im = im.channels_from(0, channels);
    if (finite)
      for (int c = 0; c < channels; ++c)
        for (size_t i = 0; i < im.pixel_count(); ++i)
          if (!std::isfinite(im.plane(c)[i]))
            fail(key, "value " + std::to_string(im.plane(c)[i]) + " at pixel (" +
                          std::to_string(i % width_) + ", " + std::to_string(i / width_) +
                          "), channel " + std::to_string(c) + " (this buffer must be finite)");
    return im;
  }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  const ImportSpec& spec_;
  int n_;
  int width_ = 0, height_ = 0;
};

std::string pixel(size_t i, int w) {
  return "(" + std::to_string(i % static_cast<size_t>(w)) + ", " +
         std::to_string(i / static_cast<size_t>(w)) + ")";
}

}  // namespace

bool has_placeholder(const std::string& pattern) {
  return find_placeholder(pattern).at != std::string::npos;
}

std::string expand_pattern(const std::string& pattern, int frame) {
  const Placeholder p = find_placeholder(pattern);
  if (p.at == std::string::npos) return pattern;
  std::string number = std::to_string(frame);
  if (static_cast<int>(number.size()) < p.width)
    number.insert(0, static_cast<size_t>(p.width) - number.size(), '0');
  return pattern.substr(0, p.at) + number + pattern.substr(p.at + p.length);
}

void ImportNotes::warn(const std::string& text) {
  if (seen_.insert(text).second) warnings.push_back(text);
}

Frame import_frame(const ImportSpec& spec, int n, int expected_width, int expected_height,
                   const io::SceneMatrices* previous, io::SceneMatrices* matrices_out,
                   ImportNotes& notes) {
  BufferReader r(spec, n);
  Frame f;
  f.index = n;
  f.color = r.read("color", 3, false);  // non-finite samples are repaired by svgf denoise
  const int w = r.width(), h = r.height();
  if (expected_width > 0 && (w != expected_width || h != expected_height))
    r.fail("color", "is " + std::to_string(w) + "x" + std::to_string(h) + ", earlier frames are " +
                        std::to_string(expected_width) + "x" + std::to_string(expected_height));
  notes.sources["color"] = "file";
  f.normal = r.read("normal", 3, true);
  notes.sources["normal"] = "file";
  if (r.has("albedo")) {
    f.albedo = r.read("albedo", 3, true);
    notes.sources["albedo"] = "file";
  } else {
    f.albedo = Image(w, h, 3, 1.f);
    notes.sources["albedo"] = "absent: 1";
    notes.warn("no albedo: albedo 1 everywhere, so the filters see texture as noise and blur it "
               "(give the renderer's albedo with --albedo where it has one)");
  }
  if (r.has("position")) {
    f.position = r.read("position", 3, true);
    notes.sources["position"] = "file";
  }
  io::SceneMatrices matrices;
  const bool has_matrices = r.has("matrices");
  if (has_matrices) {
    try {
      matrices = io::read_games202_matrices(r.path("matrices"));
    } catch (const io::IoError& e) {
      throw io::IoError(r.prefix("matrices") + e.what());
    }
    if (matrices_out) *matrices_out = matrices;
    notes.sources["matrices"] = "file";
  }

  // Mesh ids: from the id buffer (object ids from 0, negative: background), else every pixel
  // with depth > 0 (or, without depth, with a non-zero normal) is object 1.
  const size_t count = static_cast<size_t>(w) * h;
  f.mesh_id.assign(count, 0u);
  const bool has_id = r.has("id");
  if (has_id) {
    const Image id = r.read("id", 1, true);
    for (size_t i = 0; i < count; ++i) {
      const float v = id.plane(0)[i];
      if (!is_integral(v) || v >= 16777216.f)
        r.fail("id", "value " + std::to_string(v) + " at pixel " + pixel(i, w) +
                         " is not an integer id below 2^24");
      if (v < 0) continue;
      if (has_matrices && static_cast<size_t>(v) >= matrices.object_to_world.size())
        r.fail("id", "id " + std::to_string(static_cast<long>(v)) + " at pixel " + pixel(i, w) +
                         " but " + r.path("matrices") + " holds " +
                         std::to_string(matrices.object_to_world.size()) + " objects");
      f.mesh_id[i] = static_cast<uint32_t>(v) + 1u;
    }
    notes.sources["id"] = "file (mesh id = id + 1, negative ids background)";
  }

  if (r.has("depth")) {
    f.depth = r.read("depth", 1, true);
    notes.sources["depth"] = "file";
  } else if (has_matrices && !f.position.empty()) {
    // Without ids, a pixel is a surface where its normal is not 0 (position 0 is a point too).
    std::vector<uint32_t> surface(count, 0u);
    for (size_t i = 0; i < count; ++i)
      surface[i] = f.normal.plane(0)[i] != 0.f || f.normal.plane(1)[i] != 0.f ||
                   f.normal.plane(2)[i] != 0.f;
    f.depth = depth_from_position(f.position, has_id ? f.mesh_id : surface, matrices.world_to_camera);
    notes.sources["depth"] = "derived: |z| of the position in camera space";
  }
  if (!has_id) {
    for (size_t i = 0; i < count; ++i) {
      const float d = f.depth.empty() ? 0.f : f.depth.plane(0)[i];
      if (d < 0.f)
        r.fail("depth", "depth " + std::to_string(d) + " at pixel " + pixel(i, w) +
                            " (linear view depth is > 0 on surfaces, 0 on background)");
      const bool normal_set = f.normal.plane(0)[i] != 0.f || f.normal.plane(1)[i] != 0.f ||
                              f.normal.plane(2)[i] != 0.f;
      f.mesh_id[i] = (f.depth.empty() ? normal_set : d > 0.f) ? 1u : 0u;
    }
    notes.sources["id"] = f.depth.empty() ? "absent: 1 where the normal is not 0"
                                          : "absent: 1 where depth > 0";
  }
  if (f.depth.empty()) {
    f.depth = Image(w, h, 1);
    for (size_t i = 0; i < count; ++i) f.depth.plane(0)[i] = f.mesh_id[i] ? 1.f : 0.f;
    notes.sources["depth"] = "absent: 1 where the normal is not 0";
    notes.warn("no depth: depth 1 on every pixel with a non-zero normal (a plane facing the "
               "camera) and 0 (background, left unfiltered) where the normal is 0, so depth "
               "does not stop the filters at edges (give --depth, or --position with --matrices)");
  }
  if (has_id)
    for (size_t i = 0; i < count; ++i) {
      if (f.mesh_id[i] == 0) {  // background, as the frame format has it
        f.depth.plane(0)[i] = 0.f;
        for (int c = 0; c < 3; ++c) f.normal.plane(c)[i] = 0.f;
        if (!f.position.empty())
          for (int c = 0; c < 3; ++c) f.position.plane(c)[i] = 0.f;
      } else if (!(f.depth.plane(0)[i] > 0.f)) {
        r.fail(r.has("depth") ? "depth" : "position",
               "depth " + std::to_string(f.depth.plane(0)[i]) + " at pixel " + pixel(i, w) +
                   ", whose id says it is a surface (depth 0 means background: the filters "
                   "would leave it unfiltered)");
      }
    }

  if (r.has("depth-gradient")) {
    f.depth_gradient = r.read("depth-gradient", 2, true);
    notes.sources["depth-gradient"] = "file";
  } else {
    f.depth_gradient = depth_gradient_from_depth(f.depth, f.mesh_id);
    notes.sources["depth-gradient"] = "derived from depth (differences, docs/import.md)";
  }

  if (r.has("motion")) {
    f.motion = r.read("motion", 2, true);
    notes.sources["motion"] = "file";
  } else if (has_matrices) {
    notes.sources["motion"] = has_id ? "derived from the object and camera matrices"
                                     : "derived from the camera matrices (no id: a static scene)";
    if (previous) {
      try {
        const Image position =
            f.position.empty() ? position_from_depth(f.depth, f.mesh_id, matrices) : f.position;
        f.motion = motion_from_matrices(position, f.mesh_id, has_id, matrices, *previous);
      } catch (const std::invalid_argument& e) {
        throw io::IoError(r.prefix("matrices") + r.path("matrices") + ": " + e.what());
      }
    } else {
      f.motion = Image(w, h, 2);  // the first frame: no history to point at
    }
  } else {
    f.motion = Image(w, h, 2);
    notes.sources["motion"] = "absent: 0";
    if (spec.frame_count > 1)
      notes.warn("no motion and no matrices: motion 0, right only for a static camera and scene "
               "(give --motion, or --matrices to derive it)");
  }

  if (r.has("emission")) {
    f.emission = r.read("emission", 3, true);
    notes.sources["emission"] = "file";
  }
  if (r.has("reference")) {
    f.reference = r.read("reference", 3, false);
    notes.sources["reference"] = "file";
  }
  if (has_matrices) {
    try {
      f.camera = camera_from_matrices(matrices, w, h);
    } catch (const std::invalid_argument& e) {
      throw io::IoError(r.prefix("matrices") + r.path("matrices") + ": " + e.what());
    }
  }
  return f;
}

}  // namespace svgf::app
