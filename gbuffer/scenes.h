#pragma once
// The built-in scenes (scenes.cpp): cornell-static, cornell-moving, camera-pan, textured, thin, cut,
// moving-shadow, light-switch.
#include <string>
#include <vector>

#include "gbuffer/scene.h"

namespace svgf::gbuffer {

const std::vector<SceneDesc>& scene_library();
// Throws std::invalid_argument listing the known names when `name` is unknown.
const SceneDesc& find_scene(const std::string& name);

}  // namespace svgf::gbuffer
