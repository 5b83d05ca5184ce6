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
};

/// Reads the MJCF file at @p path with MuJoCo's own compiler, so that defaults and classes,
/// compiler settings (angle units, meshdir), fromto, every orientation form and includes mean
/// what they mean in MuJoCo. The top-level body is the first child of the worldbody; geoms of
/// nested bodies are placed through the body poses. Boxes, spheres, cylinders, capsules and
/// meshes (with their scale) are supported.
/// Refused before MuJoCo sees them: files of more than limits::kUrdfBytes bytes or nested more
/// than limits::kXmlDepth levels.
/// @param maxTriangles mesh triangles allowed in all of its meshes together
/// @throw ConfigError naming the cause: unreadable or malformed file, no body, a missing site
///        (robosuite needs all three), an unsupported geom type, a missing mesh, too large
MjcfObject loadMjcfObject(const std::string& path, std::size_t maxTriangles);

/// loadMjcfObject for MJCF text (the node's `mjcf_param`): the document is given to MuJoCo
/// through its virtual file system, so meshes and includes need absolute paths.
/// @throw ConfigError as loadMjcfObject, and for text larger than limits::kUrdfBytes
MjcfObject loadMjcfText(const std::string& text, std::size_t maxTriangles);

}  // namespace placement_samplers
