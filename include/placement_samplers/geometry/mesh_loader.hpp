#pragma once

#include <Eigen/Core>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "placement_samplers/limits.hpp"
#include "placement_samplers/geometry/shape.hpp"

namespace placement_samplers {

/// Maps a ROS package name to its directory, or returns "" when it does not know the package.
/// The node can hand in ros::package::getPath; the core never calls ROS itself.
using PackageResolver = std::function<std::string(const std::string& package)>;

/// Finds @p package through the ROS_PACKAGE_PATH environment variable, as rospack would: for
/// each directory D listed, D itself when D/package.xml names @p package, else D/<package> when
/// it holds a package.xml, else a package.xml naming @p package at most three levels below D.
/// @return the package directory, or "" when it is not found (or the variable is unset)
std::string findPackageInRosPackagePath(const std::string& package);

/// Turns a URI into a file path: `package://pkg/rel` becomes `<resolver(pkg)>/rel`,
/// `file:///abs` becomes `/abs`, an absolute path is kept, and a relative path is taken
/// relative to @p baseDirectory (or to the current directory when @p baseDirectory is "").
/// @param resolver used for package:// URIs; empty = findPackageInRosPackagePath
/// @throw ConfigError when the scheme is not supported or the package is unknown
std::string resolveUri(const std::string& uri, const PackageResolver& resolver,
                       const std::string& baseDirectory);

/// Reads a triangle mesh (STL, COLLADA or OBJ, by the file's extension, through assimp) into the
/// mesh's own frame: node transforms and COLLADA units are applied, COLLADA's up axis is not
/// (ROS and rviz keep z up), then every vertex is multiplied by @p scale.
/// Refused before assimp sees them: files of more than limits::kMeshBytes, COLLADA documents
/// nested more than limits::kXmlDepth elements deep, other formats.
/// @param path a file path (see resolveUri)
/// @param scale per-axis scale factors, finite and positive
/// @param source how the mesh was named (its URI), kept in Mesh::source and used in messages
/// @param maxTriangles at most this many triangles (every instance of a mesh in the file counts)
/// @throw ConfigError naming @p source and the path: missing, unreadable or too large file, an
///        unsupported format, too deep nesting, a file assimp cannot parse, no triangles or too
///        many, non-finite vertices, or a bad scale
Mesh loadMeshFile(const std::string& path, const Eigen::Vector3d& scale, const std::string& source,
                  std::size_t maxTriangles = limits::kMeshTriangles);

/// Loads meshes by URI for one configuration build, each (file, scale) once, all of them
/// together within limits::kMeshTriangles triangles. Not thread-safe: one loader per build.
class MeshLoader {
 public:
  /// @param resolver maps package names to directories; empty = findPackageInRosPackagePath
  /// @param baseDirectory relative paths are taken relative to it; "" = current directory
  explicit MeshLoader(PackageResolver resolver = PackageResolver(), std::string baseDirectory = "");

  /// The mesh at @p uri scaled by @p scale, read on the first request and shared afterwards.
  /// @param baseDirectory overrides the loader's base directory for a relative @p uri (a URDF
  ///        file's meshes are relative to the URDF file); "" = the loader's
  /// @throw ConfigError as resolveUri and loadMeshFile
  std::shared_ptr<const Mesh> load(const std::string& uri, const Eigen::Vector3d& scale,
                                   const std::string& baseDirectory = "");

  /// resolveUri with this loader's resolver; @p baseDirectory "" = the loader's.
  /// @throw ConfigError as resolveUri
  std::string resolve(const std::string& uri, const std::string& baseDirectory = "") const;

  const std::string& baseDirectory() const { return baseDirectory_; }
  /// Number of distinct (file, scale) pairs read so far.
  std::size_t cachedCount() const { return cache_.size(); }
  /// Triangles of the meshes read so far.
  std::size_t triangleCount() const { return triangles_; }

 private:
  using Key = std::tuple<std::string, double, double, double>;
  PackageResolver resolver_;
  std::string baseDirectory_;
  std::map<Key, std::shared_ptr<const Mesh>> cache_;
  std::size_t triangles_ = 0;
};

}  // namespace placement_samplers
