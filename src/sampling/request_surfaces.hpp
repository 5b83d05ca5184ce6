#pragma once
// The surfaces of request fixtures that surface regions stand on (request_surfaces.cpp).
// Private to the core.

#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers::detail {

/// Finds, once per request, the surfaces of each request fixture that a surface region of the
/// request's sampler names, into request.surfaces.
/// @throw RequestError when a region's `of` is no fixture or earlier object, when the fixture
///        has no surface, or when an object fits on none of the selected ones
void prepareRequestSurfaces(PreparedRequest& request);

}  // namespace placement_samplers::detail
