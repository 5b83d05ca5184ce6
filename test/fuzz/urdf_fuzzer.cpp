// libFuzzer target: URDF text -> collision shapes -> derived bounds. Meshes resolve into an empty
// directory, so mesh references exercise the error paths without reading the machine's files.
#include <cstddef>
#include <cstdint>
#include <string>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/geometry/mesh_loader.hpp"
#include "placement_samplers/geometry/object_model.hpp"
#include "placement_samplers/geometry/urdf_geometry.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace placement_samplers;
  const std::string text(reinterpret_cast<const char*>(data), size);
  MeshLoader meshes([](const std::string&) { return std::string("/nonexistent"); }, "/nonexistent");
  for (const char* link : {"", "base_link"}) {
    try {
      std::vector<Shape> shapes = urdfCollisionShapes(text, link, meshes, "");
      makeObject("fuzz", std::move(shapes), Eigen::Quaterniond::Identity());
    } catch (const ConfigError&) {
    } catch (const std::invalid_argument&) {
    }
  }
  return 0;
}
