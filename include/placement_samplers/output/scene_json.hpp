#pragma once

#include <string>
#include <string_view>

#include "placement_samplers/sampling/placement.hpp"
#include "placement_samplers/sampling/scene_config.hpp"

namespace placement_samplers {

/// One scene as one line of JSON (no newline): scene, seed, success, message and placements
/// with name, sampler, position [x, y, z] in [m], orientation [x, y, z, w] and attempts.
/// Numbers are printed in the shortest form that reads back as the same double.
std::string sceneToJson(const SceneResult& scene);

/// sceneToJson(), appended to @p out.
void appendSceneJson(std::string& out, const SceneResult& scene);

/// The built configuration as one JSON object: what robosuite's samplers need to sample the
/// same scenes (README, "robosuite semantics"). "objects": name -> horizontal_radius,
/// bottom_offset, top_offset [m] and init_orientation [x, y, z, w], as derived or overridden,
/// bottom_gap and top_gap [m] (ObjectModel::bottomGap, topGap: what physics counts as clearance);
/// "fixtures": name, position, orientation and the same values under the fixture's
/// orientation; "hidden": the hidden objects; "sampler": the root composite as a tree of
/// {"type": "sequential", "name", "samplers": [{"sampler", "sample_args"}]} and
/// {"type": "uniform", "name", "objects", "x_range", "y_range", "rotation" (null, an angle or
/// [min, max] [rad]), "rotation_axis", "ensure_object_boundary_in_range",
/// "ensure_valid_placement", "reference_pos", "z_offset", "max_attempts", "region" and
/// "keep_out" when set (shapes as configured; a surface region with the surfaces found, each
/// with its "index", "z", "area", "clearance" and "vertices"), "hides"}; sample_args
/// hold "reference" (a name or [x, y, z]) and "on_top" when set.
std::string configToJson(const SceneConfig& config);

/// @p text as a JSON string literal, quotes included, appended to @p out. Bytes that are not
/// valid UTF-8 become U+FFFD (the replacement character), so the literal is always valid JSON.
void appendJsonString(std::string& out, std::string_view text);

}  // namespace placement_samplers
