#pragma once

#include <Eigen/Core>

#include "placement_samplers/geometry/object_model.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"

namespace placement_samplers {

/// How far @p position lies outside the region where @p sampler draws the origin of @p object
/// when its reference resolves to @p base [m]: 0 inside. The region is the sampler's x and y
/// range around @p base, shrunk by the object's horizontal radius when
/// ensure_object_boundary_in_range is on (UniformRandomSampler::effectiveRange()); the distance
/// is the horizontal one to the nearest point of it. Another region shape (`region`) is inset
/// the same way (the signed depth's shortfall); a keep-out zone counts as outside, by how far
/// the object's disk (its centre without the flag) reaches into it. The one place that says what
/// a region is.
double distanceOutsideRegion(const UniformRandomSampler& sampler, const ObjectModel& object,
                             const Eigen::Vector3d& base, const Eigen::Vector3d& position);

}  // namespace placement_samplers
