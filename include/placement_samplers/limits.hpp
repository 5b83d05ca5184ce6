#pragma once

#include <cstddef>
#include <cstdint>

namespace placement_samplers {

/// Limits on what a configuration may ask of the process (docs/reliability.md, "Limits").
/// Each is checked before the work it bounds, and exceeding it is a ConfigError that names the
/// file or parameter and the limit. They keep a configuration file from killing the process
/// (stack overflow in a library, memory exhaustion) and every accepted value finite.
namespace limits {

/// Bytes of a configuration file (the CLI reads at most one byte more).
constexpr std::size_t kConfigBytes = std::size_t{1} << 20;
/// Values in a configuration tree (maps, lists and scalars), YAML aliases expanded.
constexpr std::size_t kConfigValues = 200000;
/// Nesting levels of a configuration tree (yaml-cpp itself gives up at about 500).
constexpr int kConfigDepth = 100;

/// Bytes of a URDF document (a urdf_file or a urdf_param).
constexpr std::size_t kUrdfBytes = std::size_t{8} << 20;
/// Links of a URDF document.
constexpr std::size_t kUrdfLinks = 10000;
/// Element nesting of an XML document (URDF, COLLADA) handed to a parser that recurses.
constexpr int kXmlDepth = 256;

/// Bodies of an MJCF document with its included files (a <composite> counts the bodies it
/// makes): MuJoCo's compiler takes time that grows with the square of them.
constexpr std::size_t kMjcfBodies = 10000;
/// Geoms of an MJCF document with its included files.
constexpr std::size_t kMjcfGeoms = 10000;
/// Files (meshes, height fields) an MJCF document names, and their bytes together.
constexpr std::size_t kMjcfFiles = 1000;
constexpr std::size_t kMjcfFileBytes = std::size_t{64} << 20;
/// Samples of a height field (nrow x ncol, or its file's image or grid): 16 MiB of floats.
constexpr std::uint64_t kHfieldSamples = std::uint64_t{1} << 22;

/// Bytes of a mesh file.
constexpr std::size_t kMeshBytes = std::size_t{16} << 20;
/// Triangles of all meshes of one configuration together (each instance of a mesh counts).
constexpr std::size_t kMeshTriangles = 250000;

/// Largest magnitude of a coordinate, length or offset [m]: positions, ranges, sizes, derived
/// bounds of the geometry. Sums of a few such values along references stay finite.
constexpr double kCoordinate = 1e6;
/// Largest time limit of a request [s] (about 11.6 days): now + it cannot overflow a clock.
constexpr double kRequestSeconds = 1e6;

/// Poses of one scene to validate (validateScene()): more than any configuration has objects
/// (a configuration has at most kConfigValues values, and an object takes at least three).
constexpr std::size_t kValidatedPlacements = 100000;

/// Defaults of the configurable limits of a request (SceneConfig).
constexpr std::uint32_t kDefaultFixturesPerRequest = 1000;
constexpr std::uint64_t kDefaultPlacementsPerRequest = 1000000;

}  // namespace limits
}  // namespace placement_samplers
