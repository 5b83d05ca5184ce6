#pragma once

// Internal to the core library: FCL geometry of the project's shapes. Not installed.

#include "collision/fcl_compat.hpp"
#include "placement_samplers/geometry/shape.hpp"

namespace placement_samplers {
namespace fcl_compat {

/// FCL geometry of @p shape, its local box computed. Meshes are built once per Mesh for the
/// whole process (an OBBRSS BVH, shared by every checker and thread: FCL only reads it).
/// @throw std::invalid_argument for a mesh without triangles; std::runtime_error when FCL
/// cannot build its BVH
GeometryPtr makeGeometry(const Shape& shape);

}  // namespace fcl_compat
}  // namespace placement_samplers
