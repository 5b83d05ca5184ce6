#pragma once

#include <string>
#include <string_view>

#include "placement_samplers/placement.hpp"

namespace placement_samplers {

/// One scene as one line of JSON (no newline): scene, seed, success, message and placements
/// with name, sampler, position [x, y, z] in [m], orientation [x, y, z, w] and attempts.
/// Numbers are printed in the shortest form that reads back as the same double.
std::string sceneToJson(const SceneResult& scene);

/// sceneToJson(), appended to @p out.
void appendSceneJson(std::string& out, const SceneResult& scene);

/// @p text as a JSON string literal, quotes included.
std::string jsonString(const std::string& text);

/// jsonString(), appended to @p out.
void appendJsonString(std::string& out, std::string_view text);

}  // namespace placement_samplers
