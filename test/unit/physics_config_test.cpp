// Physics settings: configuration keys and their errors, densities, and physics
// none leaving sampling untouched. The simulated scenes are in physics_test.cpp.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "placement_samplers/output/scene_json.hpp"
#include "placement_samplers/physics/physics_model.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "physics_scenes.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::buildFromYaml;
using test::configError;
using test::kCubeOnTable;

TEST(PhysicsConfig, MassFollowsTheDensity) {
  const Shape cube = Shape::box(Eigen::Vector3d(0.1, 0.1, 0.1));
  const ObjectModel object = makeObject("cube", {cube}, Eigen::Quaterniond::Identity());
  PhysicsSettings settings;
  const PhysicsModel model(
      {}, {PhysicsBody{&object, 0.0, 500.0}, PhysicsBody{&object, 0.0, 2000.0}}, settings);
  EXPECT_NEAR(model.mass(0), 0.5, 1e-9);
  EXPECT_NEAR(model.mass(1), 2.0, 1e-9);
  // The configuration's density, and an object's own.
  const std::shared_ptr<SceneConfig> config = buildFromYaml(kCubeOnTable);
  EXPECT_EQ(config->physics.density, 500.0);
  EXPECT_EQ(config->findObject("cube")->density, 900.0);
  EXPECT_EQ(config->findObject("table_top")->density, 0.0);
}

TEST(PhysicsConfig, NoneLeavesResultsUntouched) {
  const std::string withKeys = "physics: none\nphysics_seconds: 2\ndensity: 800\n" + kCubeOnTable;
  const SceneGenerator plain(buildFromYaml(kCubeOnTable));
  const SceneGenerator keyed(buildFromYaml(withKeys));
  const std::vector<SceneResult> a = plain.sampleScenes(plain.prepare(SampleRequest()), 5, 50, 2);
  const std::vector<SceneResult> b = keyed.sampleScenes(keyed.prepare(SampleRequest()), 5, 50, 2);
  for (std::size_t s = 0; s < a.size(); ++s) {
    test::expectSamePlacements(a[s].placements, b[s].placements);
    EXPECT_FALSE(b[s].simulated);
    EXPECT_FALSE(b[s].stable);
    EXPECT_TRUE(b[s].physics.empty());
    EXPECT_EQ(b[s].physicsMode, PhysicsMode::None);
  }
  // A request's mode wins over the configuration's.
  const SceneGenerator checking(buildFromYaml("physics: check\n" + kCubeOnTable));
  SampleRequest none;
  none.physics = PhysicsMode::None;
  EXPECT_FALSE(checking.sampleScene(checking.prepare(none), 5, 0).simulated);
  EXPECT_TRUE(checking.sampleScene(checking.prepare(SampleRequest()), 5, 0).simulated);
}

TEST(PhysicsConfig, BadParametersAreConfigurationErrors) {
  const std::string objects = "objects: {cube: {shape: box, size: [0.1, 0.1, 0.1]}}\n";
  const auto error = [&](const std::string& line) {
    return configError([&] { buildFromYaml(line + "\n" + objects); });
  };
  EXPECT_EQ(error("physics_seconds: -1"),
            "physics_seconds: expected a positive duration [s] of at most 60, got -1");
  EXPECT_EQ(error("physics_seconds: 0"),
            "physics_seconds: expected a positive duration [s] of at most 60, got 0");
  EXPECT_EQ(error("physics_seconds: 1000"),
            "physics_seconds: expected a positive duration [s] of at most 60, got 1000");
  EXPECT_EQ(error("physics_position_tolerance: .nan"),
            "physics_position_tolerance: expected a finite number, got a number (nan)");
  EXPECT_EQ(error("physics_rotation_tolerance: .inf"),
            "physics_rotation_tolerance: expected a finite number, got a number (inf)");
  EXPECT_EQ(
      error("physics_rotation_tolerance: 4"),
      "physics_rotation_tolerance: expected a positive angle [rad] of at most 3.14159, got 4");
  EXPECT_EQ(error("physics_timestep: 0.00001"),
            "physics_timestep: expected a time step [s] of at least 0.0001, got 1e-05");
  EXPECT_EQ(error("physics_timestep: 0.05\nphysics_seconds: 0.01"),
            "physics_timestep: expected a time step [s] no longer than physics_seconds (0.01), "
            "got 0.05");
  EXPECT_EQ(error("physics: wobble"), "physics: expected none, check or settle, got 'wobble'");
  EXPECT_EQ(error("physics_max_draws: 0"),
            "physics_max_draws: expected an integer in [1, 1000], got an integer (0)");
  EXPECT_EQ(error("density: -5"), "density: expected a density [kg/m^3] in [1, 100000], got -5");
  EXPECT_EQ(error("physics_max_memory_mb: 8"),
            "physics_max_memory_mb: expected an integer in [16, 1048576], got an integer (8)");
  EXPECT_EQ(error("ground_z: .nan"), "ground_z: expected a finite number, got a number (nan)");
  EXPECT_EQ(configError([] {
              buildFromYaml("objects: {cube: {shape: box, size: [0.1, 0.1, 0.1], density: 0}}");
            }),
            "objects.cube.density: expected a density [kg/m^3] in [1, 100000], got 0");
}

TEST(PhysicsConfig, DescribeShowsOnlyWhatIsSet) {
  const std::string plain = configToJson(*buildFromYaml(kCubeOnTable));
  EXPECT_EQ(plain.find("\"physics\""), std::string::npos);
  EXPECT_NE(plain.find("\"density\": 900"), std::string::npos);  // the cube's own
  const std::string set = configToJson(*buildFromYaml(
      "ground_z: 0.8\nphysics: settle\nphysics_retry: true\ndensity: 500\n" + kCubeOnTable));
  EXPECT_NE(set.find(", \"physics\": {\"physics\": \"settle\", \"physics_retry\": true, "
                     "\"ground_z\": 0.8}}"),
            std::string::npos)
      << set;
}

}  // namespace
}  // namespace placement_samplers
