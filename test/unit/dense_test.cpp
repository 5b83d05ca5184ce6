// Strategy dense: past the random-packing limit, every returned scene still passes the check.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "placement_samplers/sampling/region.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

std::string cylinders(int n, const std::string& extra) {
  std::string yaml = "objects:\n  post: {shape: cylinder, radius: 0.05, length: 0.3}\n";
  std::string names;
  for (int i = 0; i < n; ++i) {
    yaml += "  c" + std::to_string(i) + ": {shape: cylinder, radius: 0.03, length: 0.1}\n";
    names += (i ? ", c" : "c") + std::to_string(i);
  }
  return yaml + "samplers:\n  - {name: S, strategy: dense, objects: [" + names +
         "], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3]" + extra + "}\n";
}

std::vector<SceneResult> run(const std::string& yaml, std::size_t count) {
  const SceneGenerator generator(test::buildFromYaml(yaml));
  return generator.sampleScenes(generator.prepare(SampleRequest()), 7, count, 2);
}

/// 80 cylinders of r = 0.03 m in 0.6 x 0.6 m (rejection and free_space jam at about 65): placed
/// in nearly every scene, inside the inset square, no two overlapping.
TEST(Dense, EightyCylindersOnASmallTable) {
  std::size_t placed = 0;
  const std::vector<SceneResult> scenes = run(cylinders(80, ""), 400);
  for (const SceneResult& s : scenes) {
    placed += s.success ? 1 : 0;
    for (std::size_t i = 0; i < s.placements.size(); ++i) {
      EXPECT_LE(s.placements[i].position.head<2>().lpNorm<Eigen::Infinity>(), 0.27 + 1e-12);
      for (std::size_t j = 0; j < i; ++j) {
        EXPECT_GT((s.placements[i].position - s.placements[j].position).head<2>().norm(), 0.06);
      }
    }
  }
  EXPECT_GE(placed, 380u);  // 95 %
  // Different scenes: the lattice moves and turns.
  EXPECT_NE(scenes[0].placements[0].position, scenes[1].placements[0].position);
}

TEST(Dense, KeepsZonesAndFixtures) {
  const std::string yaml =
      cylinders(30, ", keep_out: [{shape: disk, centre: [0.1, 0.1], radius: 0.1}]") +
      "fixtures:\n  - {name: p, object: post, position: [-0.1, -0.1, 0]}\n";
  for (const SceneResult& s : run(yaml, 200)) {
    ASSERT_TRUE(s.success) << s.message;
    for (const ObjectPlacement& p : s.placements) {
      EXPECT_GE((p.position.head<2>() - Eigen::Vector2d(0.1, 0.1)).norm(), 0.13 - 1e-12);
      EXPECT_GT((p.position.head<2>() - Eigen::Vector2d(-0.1, -0.1)).norm(), 0.08);
    }
  }
}

TEST(Dense, FailsWhenTheLatticeIsFull) {
  const std::vector<SceneResult> out = run(cylinders(120, ""), 1);
  ASSERT_FALSE(out[0].success);
  EXPECT_NE(out[0].message.find("with sampler 'S': strategy dense ran out of lattice sites ("),
            std::string::npos)
      << out[0].message;
}

}  // namespace
}  // namespace placement_samplers
