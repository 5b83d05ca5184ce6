// resting: stable: poses drawn by probability, each placed with its own numbers (height, boundary
// shrink, overlap radius), outputs and validation; errors.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "placement_samplers/geometry/resting_poses.hpp"
#include "placement_samplers/output/scene_json.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "placement_samplers/validation/scene_validator.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::buildFromYaml;

const std::string kObjects = R"(
objects:
  table: {shape: box, size: [1.0, 0.8, 0.05]}
  brick: {shape: box, size: [0.12, 0.07, 0.04]}
  brick2: {shape: box, size: [0.12, 0.07, 0.04]}
  brick3: {shape: box, size: [0.12, 0.07, 0.04]}
  ball: {shape: sphere, radius: 0.03}
fixtures:
  - {name: t1, object: table, position: [0, 0, 0.775]}
)";

struct Scenes {
  std::shared_ptr<const SceneGenerator> generator;
  PreparedRequest request;
  std::vector<SceneResult> results;
};

Scenes scenes(const std::string& yaml, std::size_t count, unsigned threads = 1) {
  Scenes s;
  s.generator = std::make_shared<const SceneGenerator>(buildFromYaml(kObjects + yaml));
  s.request = s.generator->prepare(SampleRequest());
  s.results = s.generator->sampleScenes(s.request, 11, count, threads);
  return s;
}

std::string buildError(const std::string& yaml) {
  return test::configError([&] { buildFromYaml(kObjects + yaml); });
}

const std::string kOnTable =
    "samplers:\n  - {name: S, objects: [brick], region: {shape: surface, of: t1}, resting: "
    "stable}\n";

TEST(RestingSampler, PosesAreDrawnByTheirProbabilities) {
  const Scenes s = scenes(kOnTable, 6000);
  const std::vector<RestingPose> poses =
      restingPoses({Shape::box(Eigen::Vector3d(0.12, 0.07, 0.04))});
  ASSERT_EQ(poses.size(), 6u);
  std::map<int, int> counts;
  for (const SceneResult& scene : s.results) {
    ASSERT_TRUE(scene.success) << scene.message;
    ++counts[scene.placements[0].restPose];
  }
  // Chi-square with 5 degrees of freedom, p = 0.001: 20.5.
  double chi2 = 0.0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const double expected = poses[k].probability * 6000.0;
    const double n = counts[static_cast<int>(k)];
    chi2 += (n - expected) * (n - expected) / expected;
  }
  EXPECT_LT(chi2, 20.5);
}

TEST(RestingSampler, EachPoseStandsOnTheSurfaceWithItsOwnNumbers) {
  const Scenes s = scenes(kOnTable, 600);
  const std::vector<RestingPose> poses =
      restingPoses({Shape::box(Eigen::Vector3d(0.12, 0.07, 0.04))});
  for (const SceneResult& scene : s.results) {
    const ObjectPlacement& p = scene.placements[0];
    ASSERT_GE(p.restPose, 0);
    const RestingPose& pose = poses[static_cast<std::size_t>(p.restPose)];
    // The bottom touches the table top (z 0.8) exactly.
    EXPECT_NEAR(p.position.z() + pose.bounds.bottomZ, 0.8, 1e-12);
    EXPECT_NEAR(p.object->bottomOffset.z(), pose.bounds.bottomZ, 0);
    // The orientation is the pose turned about z: the face's normal points down.
    const Eigen::Vector3d down = p.orientation * pose.normal;
    EXPECT_NEAR(down.z(), -1.0, 1e-9);
    // The boundary shrink by the pose's radius.
    EXPECT_LE(std::abs(p.position.x()), 0.5 - pose.bounds.horizontalRadius + 1e-12);
    EXPECT_LE(std::abs(p.position.y()), 0.4 - pose.bounds.horizontalRadius + 1e-12);
  }
}

TEST(RestingSampler, TheRadiusTestUsesEachPosesRadius) {
  const Scenes s = scenes(
      "samplers:\n  - {name: S, objects: [brick, brick2, brick3], x_range: [-0.2, 0.2], "
      "y_range: [-0.2, 0.2], reference_pos: [0, 0, 0.8], resting: stable}\n",
      400);
  std::size_t close = 0;
  for (const SceneResult& scene : s.results) {
    ASSERT_TRUE(scene.success) << scene.message;
    for (std::size_t i = 0; i < 3; ++i) {
      for (std::size_t j = i + 1; j < 3; ++j) {
        const ObjectPlacement& a = scene.placements[i];
        const ObjectPlacement& b = scene.placements[j];
        const double d = (a.position - b.position).head<2>().norm();
        const double reach = a.object->horizontalRadius + b.object->horizontalRadius;
        EXPECT_GT(d, reach - 1e-12);
        close += d < reach + 0.01 ? 1 : 0;
      }
    }
  }
  EXPECT_GT(close, 0u);  // the disks do come near each other
}

TEST(RestingSampler, SameScenesOnOneAndTwoThreadsAndUprightAsBefore) {
  const Scenes one = scenes(kOnTable, 100, 1);
  const Scenes two = scenes(kOnTable, 100, 2);
  for (std::size_t i = 0; i < one.results.size(); ++i) {
    test::expectSamePlacements(one.results[i].placements, two.results[i].placements);
  }
  // Without resting: stable, no placement has a resting pose.
  const Scenes upright =
      scenes("samplers:\n  - {name: S, objects: [brick], region: {shape: surface, of: t1}}\n", 20);
  for (const SceneResult& scene : upright.results) {
    EXPECT_EQ(scene.placements[0].restPose, ObjectPlacement::kUpright);
  }
}

TEST(RestingSampler, ABallHasNoRestingPoseAndIsPlacedAsConfigured) {
  const Scenes s = scenes(
      "samplers:\n  - {name: S, objects: [ball], region: {shape: surface, of: t1}, resting: "
      "stable}\n",
      20);
  for (const SceneResult& scene : s.results) {
    EXPECT_EQ(scene.placements[0].restPose, ObjectPlacement::kUpright);
    EXPECT_NEAR(scene.placements[0].position.z(), 0.83, 1e-12);
  }
}

TEST(RestingSampler, TheValidatorTakesAnyRestingPose) {
  const Scenes s = scenes(kOnTable, 20);
  for (const SceneResult& scene : s.results) {
    const ObjectPlacement& p = scene.placements[0];
    std::vector<GivenPose> poses{GivenPose{"brick", p.position, p.orientation}};
    EXPECT_TRUE(validateScene(*s.generator, s.request, poses).valid);
    // Tilted out of every resting pose.
    poses[0].orientation =
        Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX())) * p.orientation;
    SceneVerdict verdict = validateScene(*s.generator, s.request, poses);
    ASSERT_FALSE(verdict.objects[0].reasons.empty());
    EXPECT_EQ(verdict.objects[0].reasons[0].kind, Violation::Kind::RestPose);
    EXPECT_EQ(verdict.objects[0].reasons[0].message,
              "object 'brick' is in none of its 6 resting poses (each turned about z only) of "
              "sampler 'S'");
    // In its pose, 1 cm high: HEIGHT against that pose's bottom.
    poses[0].orientation = p.orientation;
    poses[0].position.z() += 0.01;
    verdict = validateScene(*s.generator, s.request, poses);
    ASSERT_EQ(verdict.objects[0].reasons.size(), 1u);
    EXPECT_EQ(verdict.objects[0].reasons[0].kind, Violation::Kind::Height);
    EXPECT_NEAR(verdict.objects[0].reasons[0].distance, 0.01, 1e-9);
  }
}

TEST(RestingSampler, DescribeListsThePosesAndTheJsonTheirIndex) {
  const Scenes s = scenes(kOnTable, 1);
  const std::string json = configToJson(s.generator->config());
  EXPECT_NE(json.find("\"resting\": \"stable\", \"min_probability\": 0.02, \"allow_rolling\": "
                      "false, \"resting_poses\": {\"brick\": [{\"index\": 0, \"orientation\": "),
            std::string::npos)
      << json;
  const std::string line = sceneToJson(s.results[0]);
  EXPECT_NE(line.find("\"rest_pose\": " + std::to_string(s.results[0].placements[0].restPose)),
            std::string::npos);
}

TEST(RestingSampler, EveryPoseStaysPutUnderPhysics) {
  // A brick, a mug with a handle and a bottle in their resting poses on the table, simulated
  // for 2 s: none moves 1 cm or turns 0.1 rad.
  const std::string yaml = kObjects + R"(
  mug:
    shapes:
      - {shape: cylinder, radius: 0.04, length: 0.1}
      - {shape: box, size: [0.03, 0.015, 0.07], position: [0.05, 0, 0]}
  bottle: {shape: cylinder, radius: 0.035, length: 0.22}
physics_seconds: 2.0
samplers:
  - {name: S, objects: [brick, mug, bottle], region: {shape: surface, of: t1}, resting: stable}
)";
  std::string text = yaml;
  // The extra objects belong under objects: (kObjects ends with the fixtures).
  const std::size_t fixtures = text.find("fixtures:");
  const std::size_t extra = text.find("  mug:");
  const std::size_t end = text.find("physics_seconds:");
  const std::string objects = text.substr(extra, end - extra);
  text.erase(extra, end - extra);
  text.insert(fixtures, objects);
  const SceneGenerator generator(buildFromYaml(text));
  SampleRequest request;
  request.physics = PhysicsMode::Check;
  const PreparedRequest prepared = generator.prepare(request);
  std::map<std::string, std::set<int>> posesSeen;
  for (const SceneResult& scene : generator.sampleScenes(prepared, 5, 60, 2)) {
    ASSERT_TRUE(scene.success) << scene.message;
    ASSERT_TRUE(scene.simulated);
    ASSERT_EQ(scene.physics.size(), scene.placements.size());
    for (std::size_t i = 0; i < scene.placements.size(); ++i) {
      posesSeen[std::string(scene.placements[i].name)].insert(scene.placements[i].restPose);
      EXPECT_LT(scene.physics[i].moved, 0.01) << scene.placements[i].name;
      EXPECT_LT(scene.physics[i].turned, 0.1) << scene.placements[i].name;
      EXPECT_FALSE(scene.physics[i].fallen);
    }
  }
  EXPECT_GE(posesSeen["brick"].size(), 4u);
  EXPECT_GE(posesSeen["mug"].size(), 3u);
}

TEST(RestingSampler, ConfigurationErrors) {
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [brick], x_range: [0, 1], y_range: [0, "
                       "1], resting: lying}\n"),
            "samplers[0].resting: expected upright (the objects as configured, robosuite's) or "
            "stable (every pose they rest in), got 'lying'");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [brick], x_range: [0, 1], y_range: [0, "
                       "1], min_probability: 0.1}\n"),
            "samplers[0].min_probability: min_probability applies to resting: stable only");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [brick], x_range: [0, 1], y_range: [0, "
                       "1], resting: stable, rotation_axis: x}\n"),
            "samplers[0]: sampler 'S': resting: stable turns each object about z after its "
            "resting pose: rotation_axis must be z");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [brick], x_range: [0, 1], y_range: [0, "
                       "1], resting: stable, min_probability: 1}\n"),
            "samplers[0].min_probability: expected a probability in [0, 1)");
  // No pose has room in a 5 cm range: the brick's smallest radius is 0.04 m.
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [brick], x_range: [0, 0.05], y_range: "
                       "[0, 1], resting: stable}\n")
                .rfind("samplers[0].x_range: sampler 'S': x_range [0, 0.05] leaves no room for "
                       "object 'brick'",
                       0),
            0u);
}

}  // namespace
}  // namespace placement_samplers
