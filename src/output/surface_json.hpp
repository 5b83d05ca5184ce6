#pragma once
// A surface region in --describe (surface_json.cpp). Private to the core.

#include <string>
#include <vector>

#include "placement_samplers/sampling/uniform_random_sampler.hpp"

namespace placement_samplers::detail {

/// [{"index", "selected" (in @p selected), "z", "area", "clearance" (null: unbounded),
/// "vertices", "holes"}, ...] [m], [m^2].
void appendSurfaces(std::string& out, const std::vector<SupportSurface>& surfaces,
                    const std::vector<std::size_t>& selected);

/// {"shape": "surface", "of", "select", "min_area", "normal_tolerance", "margin",
/// "surfaces_frame" ("world", "object" or null), "surfaces" (null for a request's fixture)}.
void appendSurfaceRegion(std::string& out, const UniformRandomSampler& sampler);

}  // namespace placement_samplers::detail
