#pragma once
// A scene's story told over any number of frames. Each scene is animated over time units, and its
// default length (SceneDesc::frames, the committed fixtures' 12) shows one unit per frame; a
// sequence of N frames shows time k * frames / N at frame k, so a 48-frame sequence tells the same
// story in four times as many, smaller steps and its events (the camera cut of `cut` and the
// switch of `light-switch`, both at time 6) fall at half its length, after the history has
// settled. At the default length the scene is returned as it is: the same bits as before.
// `svgf-fixtures eval` renders its sequences so; `generate` shows one time unit per frame.
#include "gbuffer/scene.h"

namespace svgf::gbuffer {

// The scene time frame `frame` of an `frames`-frame sequence shows (frame may be -1: the
// animation before frame 0, for motion vectors).
double scene_time(const SceneDesc& scene, int frames, double frame);

// `scene` retimed to `frames` frames: its camera, poses and emissions read scene_time, its
// camera cuts move to the first frame at or after their time (dropped past the end), and its
// `frames` is `frames`. Throws std::invalid_argument unless frames >= 1.
SceneDesc scene_over(const SceneDesc& scene, int frames);

}  // namespace svgf::gbuffer
