// Writes the fuzz targets' seed corpus (tests/fuzz/corpus) with the project's own writers, so the
// seeds are files the readers must accept (or, for the RGB-only file, refuse by name); one frame
// carries the optional `gradient` group, so that the frame fuzzer reaches its reader:
//   svgf_fuzz_seeds tests/fuzz/corpus
// Small on purpose: libFuzzer mutates them, and a small input runs many times a second.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>

#include "io/exr_frame.h"
#include "io/sequence.h"

namespace {

using namespace svgf;
namespace fs = std::filesystem;

Image crop(const Image& im, int x0, int y0, int w, int h) {
  if (im.empty()) return Image();
  Image out(w, h, im.channels());
  for (int c = 0; c < im.channels(); ++c)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) out.at(x, y, c) = im.at(x0 + x, y0 + y, c);
  return out;
}

// A w x h window of a rendered fixture frame, every channel it has.
Frame crop(const Frame& f, int x0, int y0, int w, int h) {
  Frame out;
  out.index = f.index;
  out.camera = f.camera;
  out.color = crop(f.color, x0, y0, w, h);
  out.albedo = crop(f.albedo, x0, y0, w, h);
  out.normal = crop(f.normal, x0, y0, w, h);
  out.position = crop(f.position, x0, y0, w, h);
  out.depth = crop(f.depth, x0, y0, w, h);
  out.depth_gradient = crop(f.depth_gradient, x0, y0, w, h);
  out.motion = crop(f.motion, x0, y0, w, h);
  out.emission = crop(f.emission, x0, y0, w, h);
  out.reference = crop(f.reference, x0, y0, w, h);
  out.direct = crop(f.direct, x0, y0, w, h);
  out.indirect = crop(f.indirect, x0, y0, w, h);
  out.gradient = crop(f.gradient, x0, y0, w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      out.mesh_id.push_back(f.mesh_id[static_cast<size_t>(y0 + y) * f.width() + x0 + x]);
  return out;
}

// Every value a channel converter meets: signed zero, a subnormal, infinity, NaN, a value
// beyond HALF's range, and ordinary ones.
void fill_special(Image& im) {
  const float values[] = {-0.f, std::numeric_limits<float>::denorm_min(),
                          std::numeric_limits<float>::infinity(), std::nanf(""), 1e6f, 0.5f, -3.f};
  size_t k = 0;
  for (float& v : im.data()) v = values[k++ % std::size(values)];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: svgf_fuzz_seeds CORPUS_DIR\n");
    return 2;
  }
  const fs::path corpus = argv[1];
  const fs::path frames = corpus / "exr_frame", manifests = corpus / "manifest";
  fs::create_directories(frames);
  fs::create_directories(manifests);

  // A rendered frame: a 4x4 window across the cut scene's geometry, stored as the fixtures are.
  const std::string fixture = std::string(SVGF_SOURCE_DIR) + "/fixtures/cut";
  const Frame rendered = io::Sequence(fixture).read(6);
  io::FrameStorage fixture_storage;
  fixture_storage.color = fixture_storage.reference = fixture_storage.position =
      io::PixelStorage::Half;
  io::write_frame((frames / "fixture_cut_4x4.exr").string(), crop(rendered, 62, 62, 4, 4),
                  fixture_storage);

  // A-SVGF's gradient samples: a 6x6 window (2x2 strata) of the light-switch fixture as its
  // light goes off (frame 6), so that the samples' two luminances differ.
  const std::string light_switch = std::string(SVGF_SOURCE_DIR) + "/fixtures/light-switch";
  const Frame gradient = crop(io::Sequence(light_switch).read(6), 24, 24, 6, 6);
  int samples = 0, changed = 0;
  for (size_t i = 0; i < gradient.gradient.pixel_count(); ++i) {
    if (gradient.gradient.plane(2)[i] != 1.f) continue;
    ++samples;
    changed += gradient.gradient.plane(0)[i] != gradient.gradient.plane(1)[i];
  }
  if (samples < 2 || changed < 1) {
    std::fprintf(stderr, "svgf_fuzz_seeds: the light-switch window holds %d samples, %d changed\n",
                 samples, changed);
    return 1;
  }
  io::write_frame((frames / "gradient_light_switch_6x6.exr").string(), gradient, fixture_storage);

  // Only the required channels, all FLOAT, holding special values.
  Frame required;
  required.allocate(3, 2);
  required.position = Image();
  required.index = 7;
  for (Image* im : {&required.color, &required.albedo, &required.normal, &required.depth,
                    &required.depth_gradient, &required.motion})
    fill_special(*im);
  required.mesh_id = {0u, 1u, 2u, 0xffffffffu, 1u << 24, 42u};
  io::FrameStorage all_float;
  all_float.albedo = all_float.normal = io::PixelStorage::Float;
  io::write_frame((frames / "required_float_3x2.exr").string(), required, all_float);

  // One pixel with every optional group, all HALF.
  Frame split;
  split.allocate(1, 1);
  for (Image* im : {&split.emission, &split.reference, &split.direct, &split.indirect})
    *im = Image(1, 1, 3, 0.25f);
  split.color = Image(1, 1, 3, 0.5f);
  io::FrameStorage all_half{io::PixelStorage::Half, io::PixelStorage::Half,
                            io::PixelStorage::Half, io::PixelStorage::Half,
                            io::PixelStorage::Half, io::PixelStorage::Half,
                            io::PixelStorage::Half};
  io::write_frame((frames / "split_half_1x1.exr").string(), split, all_half);

  // An OpenEXR file that is not a frame (R, G, B only): the reader must refuse it by name.
  io::write_rgb_exr((frames / "rgb_only_4x4.exr").string(), crop(rendered.color, 62, 62, 4, 4));

  // Manifests: the fixture's own (twelve frames and a camera cut) and a small written one.
  fs::copy_file(fs::path(fixture) / "manifest.json", manifests / "fixture_cut.json",
                fs::copy_options::overwrite_existing);
  io::Manifest small;
  small.scene = "synthetic";
  small.width = 4;
  small.height = 4;
  small.reference_spp = 64;
  small.seed = 0xfedcba9876543210ull;  // above 2^63: unsigned in JSON
  small.generator = "svgf_fuzz_seeds";
  small.frames = {{"frame_0000.exr", std::string(64, 'a')}, {"frame_0001.exr", std::string(64, '0')}};
  small.camera_cuts = {1};
  const fs::path small_dir = manifests / "small.tmp";
  fs::create_directories(small_dir);
  io::write_manifest(small_dir.string(), small);
  fs::rename(small_dir / "manifest.json", manifests / "small.json");
  fs::remove(small_dir);
  return 0;
}
