#pragma once

#include <optional>
#include <string>

#include "placement_samplers/collision/collision_checker.hpp"
#include "placement_samplers/sampling/placement_sampler.hpp"
#include "placement_samplers/sampling/region.hpp"

namespace placement_samplers {

/// Area of a region shape [m^2] (a polygon's enclosed area, an annulus without its hole).
double regionArea(const RegionShape& shape);

/// Finds a uniform sampler below @p root that can never place its objects: with
/// ensure_object_boundary_in_range each object's disk (its horizontal radius) lies inside the
/// region, and robosuite's radius test needs the disks of objects at overlapping heights to be
/// disjoint, so their areas cannot add up to more than the region's, whatever the packing.
/// Only objects that would all test against each other are counted (the radius test is
/// one-sided in z); keep-out zones, fixtures and other samplers' objects are left out, so the
/// answer is never "hopeless" for a request that could succeed.
/// @return the reason with the numbers, or nothing when no sampler is provably overfull
///   (always nothing for CollisionMode::Fcl, whose shapes are not disks)
std::optional<std::string> findOverfullSampler(const PlacementSampler& root,
                                               const Reference& reference, bool onTop,
                                               CollisionMode mode);

}  // namespace placement_samplers
