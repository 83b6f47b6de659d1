#include "gbuffer/scene_timeline.h"

#include <stdexcept>
#include <string>

namespace svgf::gbuffer {

namespace {

// Multiply first: at 12 of 48 frames every time is exact (k * 12 / 48 = k / 4).
double time_at(int story_frames, int frames, double frame) {
  return frame * static_cast<double>(story_frames) / static_cast<double>(frames);
}

}  // namespace

double scene_time(const SceneDesc& scene, int frames, double frame) {
  return time_at(scene.frames, frames, frame);
}

SceneDesc scene_over(const SceneDesc& scene, int frames) {
  if (frames < 1)
    throw std::invalid_argument(scene.name + ": a sequence of " + std::to_string(frames) +
                                " frames");
  if (frames == scene.frames) return scene;
  SceneDesc s = scene;
  auto time = [story = scene.frames, frames](double k) { return time_at(story, frames, k); };
  if (scene.camera) s.camera = [f = scene.camera, time](double k) { return f(time(k)); };
  for (Object& o : s.objects) {
    if (o.pose) o.pose = [f = o.pose, time](double k) { return f(time(k)); };
    if (o.emission_scale)
      o.emission_scale = [f = o.emission_scale, time](double k) { return f(time(k)); };
  }
  // The same comparison the scenes make (time < cut: the old shot), on the same times.
  s.camera_cuts.clear();
  for (int cut : scene.camera_cuts) {
    int k = 0;
    while (k < frames && time(k) < cut) ++k;
    if (k < frames) s.camera_cuts.push_back(k);
  }
  s.frames = frames;
  return s;
}

}  // namespace svgf::gbuffer
