// Strategy dense: past the random-packing limit, every returned scene still passes the check.
#include <gtest/gtest.h>

#include <cmath>
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

/// @p n spheres of radius @p r in a regular @p vertices-gon of circumradius @p size.
std::string spheresInPolygon(int n, double r, int vertices, double size) {
  std::string yaml = "objects:\n";
  std::string names;
  for (int i = 0; i < n; ++i) {
    yaml += "  s" + std::to_string(i) + ": {shape: sphere, radius: " + std::to_string(r) + "}\n";
    names += (i ? ", s" : "s") + std::to_string(i);
  }
  std::string corners;
  for (int k = 0; k < vertices; ++k) {
    const double a = 2.0 * M_PI * k / vertices;
    corners += (k ? ", [" : "[") + std::to_string(size * std::cos(a)) + ", " +
               std::to_string(size * std::sin(a)) + "]";
  }
  return yaml + "samplers:\n  - {name: S, strategy: dense, objects: [" + names +
         "], region: {shape: polygon, vertices: [" + corners + "]}}\n";
}

/// A lattice whose tests would take minutes fails at once, before any draw.
TEST(Dense, BoundsTheWorkOfALattice) {
  const SceneGenerator generator(test::buildFromYaml(spheresInPolygon(10, 0.00025, 1000, 0.35)));
  const SceneResult scene = generator.sampleScene(generator.prepare(SampleRequest()), 1, 0);
  EXPECT_FALSE(scene.success);
  EXPECT_EQ(scene.message,
            "sampler 'S': strategy dense: about 2269675 lattice sites in the region's bounding "
            "box, each tested against 1000 region and keep-out edges, exceed the limit of "
            "250000000 tests a scene (larger objects, a smaller region or fewer vertices)");
  EXPECT_TRUE(scene.placements.empty());
}

/// Laying out the sites reads the clock (the first reading starts a scene's clock, the second
/// one stops it); the same lattice without a limit places every object.
TEST(Dense, StopsLayingOutSitesWhenTimeRunsOut) {
  const SceneGenerator generator(test::buildFromYaml(spheresInPolygon(5, 0.0005, 100, 0.1)));
  SampleRequest request;
  EXPECT_TRUE(generator.sampleScene(generator.prepare(request), 1, 0).success);
  request.maxSceneSeconds = 1e-9;
  SceneResult scene = generator.sampleScene(generator.prepare(request), 1, 0);
  EXPECT_FALSE(scene.success);
  EXPECT_EQ(scene.message,
            "sampler 'S': strategy dense: stopped laying out the lattice sites: the scene ran "
            "out of time (its limit is 1e-09 s)");
  request.maxSceneSeconds = 0.0;
  request.maxSeconds = 1e-9;
  scene = generator.sampleScene(generator.prepare(request), 1, 0);
  EXPECT_EQ(scene.message,
            "sampler 'S': strategy dense: stopped laying out the lattice sites: the request ran "
            "out of time");
}

}  // namespace
}  // namespace placement_samplers
