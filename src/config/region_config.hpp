#pragma once
// Reads region shapes and keep-out zones of a uniform sampler (region_config.cpp). Private to
// the core.

#include <vector>

#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/sampling/region.hpp"
#include "placement_samplers/sampling/surface_region.hpp"

namespace placement_samplers::detail {

/// A map {shape: rectangle | rotated_rectangle | disk | annulus | polygon, ...}; every problem
/// of the shape fails at the parameter it is about.
RegionShape parseRegionShape(const ConfigNode& node);

/// True for a map {shape: surface, ...}.
bool isSurfaceRegion(const ConfigNode& node);

/// A map {shape: surface, of: NAME, select: all | top | [i, ...], min_area, normal_tolerance,
/// margin}; each value checked at its parameter.
SurfaceRegion parseSurfaceRegion(const ConfigNode& node);

/// A list of shapes, each with an optional `frame: sampler | world`.
std::vector<KeepOutZone> parseKeepOut(const ConfigNode& node);

}  // namespace placement_samplers::detail
