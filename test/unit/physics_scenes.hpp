#pragma once
// Configurations shared by the physics tests (physics_test.cpp, physics_config_test.cpp).

#include <string>

namespace placement_samplers {
namespace test {

// A 4.2 cm cube sampled 1 cm above a table fixture, as robosuite's Lift does.
inline const std::string kCubeOnTable = R"(
objects:
  table_top: {shape: box, size: [0.8, 0.8, 0.05]}
  cube: {shape: box, size: [0.042, 0.042, 0.042], density: 900}
fixtures:
  - {name: table, object: table_top, position: [0, 0, 0.775]}
samplers:
  - name: CubeSampler
    objects: [cube]
    x_range: [-0.2, 0.2]
    y_range: [-0.2, 0.2]
    z_offset: 0.01
    sample_args: {reference: table, on_top: true}
)";

}  // namespace test
}  // namespace placement_samplers
