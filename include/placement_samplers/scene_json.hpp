#pragma once

#include <string>

#include "placement_samplers/placement.hpp"

namespace placement_samplers {

/// One scene as one line of JSON (no newline): scene, seed, success, message and placements
/// with name, sampler, position [x, y, z] in [m], orientation [x, y, z, w] and attempts.
/// Numbers are printed with 17 significant digits, so they read back bit for bit.
std::string sceneToJson(const SceneResult& scene);

/// @p text as a JSON string literal, quotes included.
std::string jsonString(const std::string& text);

}  // namespace placement_samplers
