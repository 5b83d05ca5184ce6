#pragma once
// Reads region shapes and keep-out zones of a uniform sampler (region_config.cpp). Private to
// the core.

#include <vector>

#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/sampling/region.hpp"

namespace placement_samplers::detail {

/// A map {shape: rectangle | rotated_rectangle | disk | annulus | polygon, ...}; every problem
/// of the shape fails at the parameter it is about.
RegionShape parseRegionShape(const ConfigNode& node);

/// A list of shapes, each with an optional `frame: sampler | world`.
std::vector<KeepOutZone> parseKeepOut(const ConfigNode& node);

}  // namespace placement_samplers::detail
