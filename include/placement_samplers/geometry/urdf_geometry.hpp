#pragma once

#include <string>
#include <vector>

#include "placement_samplers/limits.hpp"
#include "placement_samplers/geometry/mesh_loader.hpp"
#include "placement_samplers/geometry/shape.hpp"

namespace placement_samplers {

/// The collision geometry of a URDF model, as shapes in one frame.
///
/// Without @p link, the whole model: every link's collision elements, each link placed through
/// the origins of the joints from the root link at zero joint values, in the root link's frame.
/// With @p link, that link's collision elements alone, in the link's own frame.
/// Boxes, cylinders (axis z, full length) and spheres map to primitives; meshes are read with
/// @p meshes, scaled by their `scale`, a relative mesh path being taken relative to
/// @p meshBaseDirectory (the URDF file's directory).
///
/// @param urdfXml the URDF document
/// @param link a link name, or "" for the whole model
/// @param meshes loads (and caches) the meshes
/// @param meshBaseDirectory directory for relative mesh paths; "" = the loader's
/// Refused before urdfdom parses them: documents of more than limits::kUrdfBytes bytes or
/// nested more than limits::kXmlDepth elements deep; after parsing, more than
/// limits::kUrdfLinks links. The link tree is walked without recursion.
/// @throw ConfigError saying what is wrong (not prefixed with the object or file: the caller
///        knows them): a limit exceeded, a malformed document (with urdfdom's reason), a link
///        that does not exist,
///        no collision geometry, a missing, unreadable or empty mesh, non-finite or non-positive
///        sizes or scales, naming the link and the collision element
std::vector<Shape> urdfCollisionShapes(const std::string& urdfXml, const std::string& link,
                                       MeshLoader& meshes,
                                       const std::string& meshBaseDirectory = "");

/// Reads a whole text file (a URDF), a regular file of at most @p maxBytes bytes.
/// @throw ConfigError when it does not exist, is not a regular file, cannot be read or is larger
std::string readTextFile(const std::string& path, std::size_t maxBytes = limits::kUrdfBytes);

}  // namespace placement_samplers
