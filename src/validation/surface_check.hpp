#pragma once

// Internal to the core library: the validator's test of a pose on a surface region. Not
// installed.

#include <Eigen/Core>

#include "placement_samplers/sampling/sample_context.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/validation/scene_validator.hpp"

namespace placement_samplers {
namespace detail {

/// A surface region's checks of @p candidate, @p object's pose (@p object: in its resting pose
/// under resting: stable): on a selected surface of the region's target that the object fits
/// under, keep-out zones kept (OUTSIDE_REGION, with the distance), and at that surface's height
/// (HEIGHT); a target not in @p context is REFERENCE_MISSING. The target becomes the
/// candidate's support, which the radius test skips. @p base is the sampler's base [m];
/// @p surfaces the request's fixtures' surfaces.
void checkOnSurface(ObjectVerdict& verdict, const UniformRandomSampler& sampler,
                    const ObjectModel& object, const Eigen::Vector3d& base, Candidate& candidate,
                    const SampleContext& context, const RequestSurfaces* surfaces,
                    const ValidationOptions& options);

}  // namespace detail
}  // namespace placement_samplers
