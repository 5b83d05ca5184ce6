#pragma once
// The MJCF document of an object as MuJoCo compiles it: read, bounded and reduced to what
// gives geometry and sites. Private to the core (mjcf_geometry.cpp).

#include <string>
#include <utility>
#include <vector>

#include "geometry/mujoco_compile.hpp"

namespace placement_samplers::detail {

/// What MuJoCo compiles: every file it may read, in its virtual file system.
struct MjcfDocument {
  MujocoVfsPtr vfs;  ///< the rewritten document and each file it names
  std::string file;  ///< the name to compile (the document's directory + its name in vfs)
  std::vector<std::string> warnings;  ///< what was left out and why (missing materials, ...)
  /// Each file's name in vfs and its path: MuJoCo's messages name the former.
  std::vector<std::pair<std::string, std::string>> renamed;

  /// @p message with each file's name in vfs (and the path MuJoCo put before it) replaced by
  /// the file's path.
  std::string originalNames(std::string message) const;
};

/// Prepares the MJCF document @p text for MuJoCo's compiler, so that MuJoCo opens no file
/// itself and allocates no more than the limits allow:
/// - its <include> files are read (regular files, all together at most limits::kUrdfBytes
///   with the document) and merged in, as MuJoCo does (relative to the document's directory);
/// - the meshes and height fields it names are read here (regular files of at most
///   limits::kMeshBytes, limits::kMjcfFileBytes together), found as MuJoCo finds them
///   (compiler meshdir and strippath), and handed to MuJoCo in its virtual file system;
/// - what changes no geometry and costs memory or time is left out: textures, skins, joints,
///   <size>, <visual>, <statistic>, <custom>, <keyframe>, <tendon>, <actuator>, <sensor>,
///   <equality>, <contact>, and the compiler's fusestatic;
/// - materials that the file names but does not define (robosuite's arena defines them) are
///   defined as plain ones, with a warning each; a material's texture is dropped, with a
///   warning when the file does not define it;
/// - bodies (a <composite> counts those it makes), geoms and height field samples are counted
///   against limits::kMjcfBodies, kMjcfGeoms and kHfieldSamples.
/// The document keeps its line numbers, so MuJoCo's messages point into the file.
/// @param path the document's file; "" when it came as text (relative paths are then relative
///        to the working directory)
/// @throw ConfigError naming the element, the file and the limit
MjcfDocument prepareMjcf(const std::string& text, const std::string& path);

}  // namespace placement_samplers::detail
