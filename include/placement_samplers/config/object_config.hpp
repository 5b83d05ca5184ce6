#pragma once

#include <functional>
#include <string>
#include <vector>

#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/geometry/mesh_loader.hpp"
#include "placement_samplers/geometry/object_model.hpp"

namespace placement_samplers {

/// Where a build finds what the configuration names but does not contain: URDF parameters,
/// ROS packages and relative paths. The defaults suit the CLI.
struct BuildOptions {
  /// The URDF text of parameter @p name (`urdf_param`); may throw to say it is missing (its
  /// message is kept). Empty = `urdf_param` is refused (the CLI has no parameter server).
  std::function<std::string(const std::string& name)> urdfParam;
  /// The MJCF text of parameter @p name (`mjcf_param`), as urdfParam.
  std::function<std::string(const std::string& name)> mjcfParam;
  /// Directory of a ROS package (`package://` URIs); empty = findPackageInRosPackagePath.
  PackageResolver packageResolver;
  /// Relative paths of `urdf_file` and `mesh` are taken relative to it (the configuration
  /// file's directory); "" = the current directory.
  std::string baseDirectory;
};

/// Builds the object @p name from its configuration entry, one of
/// - a primitive: `shape: box | cylinder | sphere | capsule` with its sizes [m];
/// - a mesh: `shape: mesh, mesh: URI, scale: [sx, sy, sz]` (scale optional, default 1);
/// - a URDF: `urdf_file: URI` or `urdf_param: NAME`, with an optional `link: NAME` (see
///   urdfCollisionShapes), a relative mesh path in a URDF file being relative to the file;
/// plus optional overrides (horizontal_radius, bottom_offset, top_offset) and init_orientation
/// [x, y, z, w], on every kind. URIs are package://, file:// or paths (see resolveUri).
/// @param options the URDF parameters; @p meshes must resolve URIs as @p options says
/// @param meshes loads each mesh file once per build
/// @param warnings receives what was accepted but left out (an MJCF file's missing material)
/// @throw ConfigError naming the parameter, the object, the file or parameter, and the cause
ObjectModel parseObject(const std::string& name, const ConfigNode& node,
                        const BuildOptions& options, MeshLoader& meshes,
                        std::vector<std::string>* warnings = nullptr);

/// parseObject with default BuildOptions (no urdf_param, ROS_PACKAGE_PATH, current directory).
/// @throw ConfigError as above
ObjectModel parseObject(const std::string& name, const ConfigNode& node);

/// A vector [x, y, z] [m] within +-limits::kCoordinate (positions, offsets, references).
/// @param what how the message calls the numbers ("coordinates", "values")
/// @throw ConfigError naming @p node otherwise
Eigen::Vector3d parseBoundedVector(const ConfigNode& node, const char* what);

/// A unit quaternion from [x, y, z, w] (isUnitQuaternion()), normalized.
/// @throw ConfigError naming @p node otherwise
Eigen::Quaterniond parseQuaternion(const ConfigNode& node);

}  // namespace placement_samplers
