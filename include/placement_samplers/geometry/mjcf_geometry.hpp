#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "placement_samplers/geometry/shape.hpp"

namespace placement_samplers {

/// What robosuite reads from an MJCF object file (MujocoXMLObject): its collision geometry and
/// its three sites, all in the frame of the top-level body.
struct MjcfObject {
  std::vector<Shape> shapes;      ///< geoms with contype or conaffinity non-zero
  Eigen::Vector3d bottomOffset;   ///< bottom_site pos [m]
  Eigen::Vector3d topOffset;      ///< top_site pos [m]
  double horizontalRadius = 0.0;  ///< x of horizontal_radius_site pos, as robosuite [m]
  std::size_t visualGeoms = 0;    ///< geoms left out (contype and conaffinity 0)
  /// What the file names but does not define and was left out because it changes no geometry
  /// (a material robosuite's arena defines), one message each.
  std::vector<std::string> warnings;
};

/// Reads the MJCF file at @p path with MuJoCo's own compiler, so that defaults and classes,
/// compiler settings (angle units, meshdir), fromto, every orientation form and includes mean
/// what they mean in MuJoCo. The top-level body is the first child of the worldbody; geoms of
/// nested bodies are placed through the body poses. Boxes, spheres, cylinders, capsules and
/// meshes (with their scale) are supported.
/// MuJoCo opens no file itself: the document, its includes, meshes and height fields are read
/// here as regular files within the limits (limits.hpp), and what changes no geometry and costs
/// memory (textures, <size>, sensors, joints, ...) is left out of what MuJoCo compiles.
/// A material the file names but does not define (robosuite's arena defines it) is a warning.
/// Refused before MuJoCo sees them: files of more than limits::kUrdfBytes bytes or nested more
/// than limits::kXmlDepth levels, anything that is not a regular file, more bodies, geoms or
/// height field samples than the limits.
/// @param maxTriangles mesh triangles allowed in all of its meshes together
/// @throw ConfigError naming the cause: unreadable or malformed file, no body, a missing site
///        (robosuite needs all three), an unsupported geom type, a missing mesh, too large
MjcfObject loadMjcfObject(const std::string& path, std::size_t maxTriangles);

/// loadMjcfObject for MJCF text (the node's `mjcf_param`): relative paths of meshes and
/// includes are relative to the working directory, so they need absolute paths.
/// @throw ConfigError as loadMjcfObject, and for text larger than limits::kUrdfBytes
MjcfObject loadMjcfText(const std::string& text, std::size_t maxTriangles);

}  // namespace placement_samplers
