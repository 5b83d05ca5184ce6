#pragma once

#include <istream>
#include <ostream>
#include <string>

#include "placement_samplers/sampling/scene_generator.hpp"
#include "placement_samplers/validation/scene_validator.hpp"

namespace placement_samplers {

/// sample_scenes --validate: reads scenes in the CLI's own JSON line format from @p in (each
/// line's "placements": "name", "position", "orientation"; "scene" when present) and prints one
/// verdict line per scene: {"scene", "valid", "objects": [{"name", "valid", "reasons":
/// [{"kind", "sampler", "other", "check", "distance", "message"}]}]}. Blank lines are skipped.
/// @param source the input's name in messages ("-" for stdin)
/// @return 0 when every scene is valid, 1 when some is not, 2 when a line cannot be read (the
/// message names the line and what was expected)
int validateSceneLines(const SceneGenerator& generator, const PreparedRequest& request,
                       const ValidationOptions& options, std::istream& in,
                       const std::string& source, std::ostream& out, std::ostream& err);

}  // namespace placement_samplers
