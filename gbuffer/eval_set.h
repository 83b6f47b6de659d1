#pragma once
// The evaluation set (issue 13): every built-in scene rendered at a realistic size and length,
// on demand, into a cache outside the source tree; never committed. Each sequence folder holds
// frame_NNNN.exr, eval.json (the parameters and the SHA-256 of every frame written so far,
// rewritten after each frame) and, once complete, manifest.json (an ordinary sequence for
// `svgf denoise`). A run renders only the frames missing or failing their SHA-256; parameters
// that differ from eval.json's mean the whole sequence is rendered again (docs/gbuffer.md).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gbuffer/renderer.h"
#include "gbuffer/scene.h"

namespace svgf::gbuffer {

// The set's parameters, in one place: its defaults are the evaluation set.
struct EvalParams {
  int width = 640;
  int height = 360;
  int frames = 48;          // each scene's story spread over them (scene_timeline.h)
  int spp = 1;
  int reference_spp = 256;  // its noise: docs/gbuffer.md, "Evaluation set"
  uint64_t seed = 1;
  bool split = true;        // direct and indirect too, for SVGF's split variant
};

// Every built-in scene, in scene_library() order.
std::vector<std::string> eval_scene_names();

// $XDG_CACHE_HOME/svgf/eval, else $HOME/.cache/svgf/eval, else ./svgf-eval-cache.
std::string default_eval_dir();

// What a sequence of `scene` with `params` is: the retimed scene and its render settings (the
// scene's gradient samples as its committed fixture has them).
struct EvalSequence {
  SceneDesc scene;  // scene_over(the library's scene, params.frames)
  RenderSettings settings;
  std::string dir;  // <root>/<scene name>
};
EvalSequence eval_sequence(const std::string& root, const std::string& scene_name,
                           const EvalParams& params);

// What a folder holds against what is wanted, found by reading eval.json and hashing every
// frame file; nothing is rendered. `notes` say why frames are rendered again (stderr lines).
struct EvalPlan {
  std::vector<int> to_render;        // frame numbers, ascending
  int kept = 0;                      // frames whose SHA-256 matches eval.json
  bool restart = false;              // parameters differ or no usable eval.json: all frames
  std::vector<std::string> notes;
};
EvalPlan plan_eval_sequence(const EvalSequence& seq, const EvalParams& params);

// Renders the plan's frames: each written under a temporary name and renamed (a frame file is
// never half written), then its SHA-256 recorded in eval.json; when all frames are there,
// manifest.json. A restart first deletes the folder's sequence files (frames, eval.json,
// manifest.json), and stale temporary files are removed. `on_frame` is called after each frame
// written. Holds an exclusive lock on <dir>/.lock meanwhile: a second run on the same folder
// fails at once. An exception (Ctrl-C through counters->cancel) keeps every frame written.
void render_eval_sequence(const Renderer& renderer, const EvalSequence& seq,
                          const EvalParams& params, const EvalPlan& plan,
                          RenderCounters* counters = nullptr,
                          const std::function<void(int frame)>& on_frame = {});

}  // namespace svgf::gbuffer
