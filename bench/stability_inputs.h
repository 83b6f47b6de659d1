#pragma once
// The stability suite's inputs (bench/stability.h): committed fixtures, sequences it renders
// (with references and gradient samples, cached when asked), and a method run over a sequence.
#include <string>
#include <vector>

#include "bench/run_config.h"
#include "core/frame.h"

namespace svgf::bench {

struct StabilitySequence {
  std::string description;  // one line for the page
  std::vector<Frame> frames;
  std::vector<int> cuts;  // frames where the history resets
  bool is_cut(int k) const;
  std::vector<Image> references() const;
  std::vector<std::vector<uint32_t>> mesh_ids() const;
};

// fixtures_root/name, every frame; the direct and indirect channels dropped.
StabilitySequence fixture_sequence(const std::string& fixtures_root, const std::string& name);

// Whether this build can render (the Embree renderer was linked).
bool stability_can_render();
// Frames 0..frames-1 of `scene`, 1 spp with gradient samples and a reference of
// `reference_spp`, rendered on `threads` threads (0: all). With a cache folder, a sequence
// rendered before with the same settings is read back (stored as FLOAT: the same bits).
StabilitySequence rendered_sequence(const std::string& scene, int width, int height, int frames,
                                    int reference_spp, int threads, const std::string& cache_dir,
                                    bool quiet);

// The method over the sequence in order, its history reset at every cut; one output a frame.
std::vector<Image> denoise_sequence(const RunConfig& config, const StabilitySequence& sequence);

}  // namespace svgf::bench
