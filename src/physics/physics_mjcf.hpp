#pragma once
// The MJCF text of a PhysicsModel. Private to the core.

#include <string>
#include <vector>

#include "physics/physics_buffers.hpp"
#include "placement_samplers/physics/physics_model.hpp"

namespace placement_samplers::detail {

/// Name of free body @p index in the generated model.
std::string physicsBodyName(std::size_t index);

/// The MJCF document of a scene: `<option timestep>`, @p buffers,
/// each distinct mesh once as an asset (its vertices: MuJoCo builds the convex hull), the
/// ground plane, the fixtures' shapes as geoms of the world body at their poses, and one body
/// with a free joint per entry of @p bodies, its geoms carrying the body's density.
std::string physicsMjcf(const std::vector<PhysicsFixture>& fixtures,
                        const std::vector<PhysicsBody>& bodies, const PhysicsSettings& settings,
                        const PhysicsBuffers& buffers);

}  // namespace placement_samplers::detail
