// Physics: MuJoCo's check and settling of sampled scenes, through the real builder
// and SceneGenerator with small inline configurations.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/physics/physics_model.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "physics_scenes.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::buildFromYaml;
using test::findPlacement;
using test::kCubeOnTable;

/// A sampled scene and the configuration its placements' names point into.
struct Sampled : SceneResult {
  std::shared_ptr<const SceneConfig> config;
};

Sampled sampleOne(const std::string& yaml, PhysicsMode mode, std::uint64_t seed = 1) {
  const SceneGenerator generator(buildFromYaml(yaml));
  SampleRequest request;
  request.physics = mode;
  Sampled out;
  static_cast<SceneResult&>(out) = generator.sampleScene(generator.prepare(request), seed, 0);
  out.config = generator.configPtr();
  return out;
}

const PhysicsOutcome& outcomeOf(const SceneResult& scene, const std::string& name) {
  for (std::size_t i = 0; i < scene.placements.size(); ++i) {
    if (scene.placements[i].name == name) {
      return scene.physics.at(i);
    }
  }
  throw std::invalid_argument("no placement " + name);
}

TEST(Physics, CubeOnTableIsStableAndSettlesWithinAMillimetre) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const Sampled scene = sampleOne(kCubeOnTable, PhysicsMode::Settle, seed);
    ASSERT_TRUE(scene.success) << scene.message;
    ASSERT_TRUE(scene.simulated);
    EXPECT_TRUE(scene.stable);
    const PhysicsOutcome& o = outcomeOf(scene, "cube");
    EXPECT_LT(o.moved, 0.001);
    EXPECT_LT(o.turned, 0.01);
    EXPECT_FALSE(o.fallen);
    // Sampled 1 cm above the table top (0.8): it lands on it.
    EXPECT_NEAR(o.sampledPosition.z(), 0.8 + 0.01 + 0.021, 1e-12);
    EXPECT_NEAR(scene.placements[0].position.z(), 0.8 + 0.021, 0.001);
  }
}

TEST(Physics, SettleGivesSettledPosesAndKeepsTheSampledOnes) {
  const Sampled sampled = sampleOne(kCubeOnTable, PhysicsMode::None);
  const Sampled settled = sampleOne(kCubeOnTable, PhysicsMode::Settle);
  const Sampled checked = sampleOne(kCubeOnTable, PhysicsMode::Check);
  ASSERT_TRUE(sampled.success && settled.success && checked.success);
  const ObjectPlacement& s = sampled.placements[0];
  const PhysicsOutcome& o = settled.physics[0];
  // The sampled pose is kept bit for bit; the answer's pose is the settled one.
  EXPECT_EQ(o.sampledPosition, s.position);
  EXPECT_EQ(o.sampledOrientation.coeffs(), s.orientation.coeffs());
  EXPECT_NE(settled.placements[0].position, s.position);
  EXPECT_GT(s.position.z() - settled.placements[0].position.z(), 0.009);
  // Check reports the same numbers but answers the sampled poses.
  EXPECT_EQ(checked.placements[0].position, s.position);
  EXPECT_EQ(checked.physics[0].moved, o.moved);
  EXPECT_EQ(checked.physics[0].turned, o.turned);
}

TEST(Physics, BoxBalancedOnASphereIsUnstable) {
  const Sampled scene = sampleOne(R"(
ground_z: 0
objects:
  ball: {shape: sphere, radius: 0.05}
  box: {shape: box, size: [0.1, 0.1, 0.05]}
samplers:
  - name: BallSampler
    objects: [ball]
    rotation: 0
    ensure_object_boundary_in_range: false
  - name: BoxSampler
    objects: [box]
    x_range: [0.005, 0.005]
    rotation: 0
    ensure_object_boundary_in_range: false
    ensure_valid_placement: false
    sample_args: {reference: ball, on_top: true}
)",
                                  PhysicsMode::Check);
  ASSERT_TRUE(scene.success) << scene.message;
  ASSERT_TRUE(scene.simulated);
  EXPECT_FALSE(scene.stable);
  const PhysicsOutcome& box = outcomeOf(scene, "box");
  EXPECT_TRUE(box.moved > 0.01 || box.turned > 0.17) << box.moved << " " << box.turned;
}

TEST(Physics, TallThinBoxOnASmallTopTipsOver) {
  const Sampled scene = sampleOne(R"(
ground_z: 0
objects:
  post: {shape: cylinder, radius: 0.01, length: 0.2}
  stick: {shape: box, size: [0.03, 0.03, 0.3]}
fixtures:
  - {name: pillar, object: post, position: [0, 0, 0.1]}
samplers:
  - name: StickSampler
    objects: [stick]
    x_range: [0.013, 0.013]
    rotation: 0
    ensure_object_boundary_in_range: false
    ensure_valid_placement: false
    sample_args: {reference: pillar, on_top: true}
)",
                                  PhysicsMode::Settle);
  ASSERT_TRUE(scene.success) << scene.message;
  EXPECT_FALSE(scene.stable);
  const PhysicsOutcome& stick = scene.physics[0];
  EXPECT_GT(stick.turned, 0.5);
  // Its centre is beyond the pillar's edge: it ends on the ground, lying.
  EXPECT_LT(scene.placements[0].position.z(), 0.1);
  EXPECT_FALSE(stick.fallen);  // the ground holds it
}

TEST(Physics, StackedMugStaysOnItsPlate) {
  const std::string yaml = R"(
objects:
  table_top: {shape: box, size: [0.8, 0.8, 0.05]}
  plate: {shape: cylinder, radius: 0.09, length: 0.02}
  mug:
    shapes:
      - {shape: cylinder, radius: 0.04, length: 0.09}
      - {shape: box, size: [0.03, 0.01, 0.05], position: [0.05, 0, 0]}
fixtures:
  - {name: table, object: table_top, position: [0, 0, 0.775]}
samplers:
  - name: PlateSampler
    objects: [plate]
    x_range: [-0.2, 0.2]
    y_range: [-0.2, 0.2]
    z_offset: 0.01
    sample_args: {reference: table, on_top: true}
  - name: MugSampler
    objects: [mug]
    x_range: [-0.02, 0.02]
    y_range: [-0.02, 0.02]
    ensure_object_boundary_in_range: false
    ensure_valid_placement: false
    sample_args: {reference: plate, on_top: true}
)";
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const Sampled scene = sampleOne(yaml, PhysicsMode::Settle, seed);
    ASSERT_TRUE(scene.success) << scene.message;
    EXPECT_TRUE(scene.stable) << "seed " << seed;
    const ObjectPlacement* plate = findPlacement(scene.placements, "plate");
    const ObjectPlacement* mug = findPlacement(scene.placements, "mug");
    ASSERT_TRUE(plate != nullptr && mug != nullptr);
    // The mug stands on the plate's top (0.8 + 0.02) where it was put.
    EXPECT_NEAR(mug->position.z(), 0.82 + 0.045, 0.002);
    EXPECT_LT((mug->position - plate->position).head<2>().norm(), 0.03);
    // It dropped 1 cm with the plate, lifted by its z_offset: no motion of its own.
    EXPECT_LT(outcomeOf(scene, "mug").moved, 0.002);
    EXPECT_GT(outcomeOf(scene, "mug").sampledPosition.z() - mug->position.z(), 0.009);
  }
}

// Near a table's edge, lifted 1 cm: it stays (released in contact; dropped, MuJoCo 2.2.2's
// convex contacts kicked it off the table).
TEST(Physics, ClearanceNearATableEdgeIsNoFall) {
  const Sampled scene = sampleOne(R"(
objects:
  table_top: {shape: box, size: [0.9, 0.9, 0.04]}
  plate: {shape: cylinder, radius: 0.1, length: 0.02}
fixtures:
  - {name: table, object: table_top, position: [0, 0, 0.78]}
samplers:
  - name: S
    objects: [plate]
    x_range: [0.33, 0.33]
    ensure_object_boundary_in_range: false
    z_offset: 0.01
    sample_args: {reference: table, on_top: true}
)",
                                  PhysicsMode::Settle);
  ASSERT_TRUE(scene.success);
  EXPECT_TRUE(scene.stable);
  EXPECT_NEAR(scene.placements[0].position.x(), 0.33, 0.001);
}

TEST(Physics, ObjectWithNoSupportFalls) {
  // Nothing at all to land on.
  const Sampled alone = sampleOne(R"(
objects:
  cube: {shape: box, size: [0.05, 0.05, 0.05]}
samplers:
  - {name: S, objects: [cube], reference_pos: [0, 0, 1], ensure_object_boundary_in_range: false}
)",
                                  PhysicsMode::Check);
  ASSERT_TRUE(alone.success);
  EXPECT_FALSE(alone.stable);
  EXPECT_TRUE(alone.physics[0].fallen);
  EXPECT_GT(alone.physics[0].moved, 1.0);  // about g / 2 in one second
  // A table, but the cube is put beside it: it falls past the table's bottom.
  const Sampled beside = sampleOne(R"(
objects:
  table_top: {shape: box, size: [0.8, 0.8, 0.05]}
  cube: {shape: box, size: [0.05, 0.05, 0.05]}
fixtures:
  - {name: table, object: table_top, position: [0, 0, 0.775]}
samplers:
  - name: S
    objects: [cube]
    reference_pos: [1.0, 0, 0.8]
    ensure_object_boundary_in_range: false
)",
                                   PhysicsMode::Check);
  ASSERT_TRUE(beside.success);
  EXPECT_FALSE(beside.stable);
  EXPECT_TRUE(beside.physics[0].fallen);
}

// A pile that moves: two objects turned about x on the ground, three turned about y dropped
// onto them from 25 cm, one hidden.
const std::string kPile = R"(
ground_z: 0.8
physics_seconds: 0.5
objects:
  a: {shape: cylinder, radius: 0.03, length: 0.1}
  b: {shape: box, size: [0.05, 0.04, 0.12]}
  c: {shape: sphere, radius: 0.03}
  d: {shape: capsule, radius: 0.02, length: 0.06, density: 900}
  e: {shape: box, size: [0.04, 0.04, 0.04]}
  f: {shape: box, size: [0.06, 0.06, 0.02]}
samplers:
  - name: Low
    objects: [a, b]
    x_range: [-0.08, 0.08]
    y_range: [-0.08, 0.08]
    rotation_axis: x
    reference_pos: [0, 0, 0.8]
    z_offset: 0.03
  - name: High
    objects: [c, d, e]
    x_range: [-0.08, 0.08]
    y_range: [-0.08, 0.08]
    rotation_axis: y
    reference_pos: [0, 0, 0.8]
    z_offset: 0.25
hide: [f]
)";

TEST(Physics, SameSeedGivesTheSameSettledPosesOnAnyThreadCount) {
  const SceneGenerator generator(buildFromYaml(kPile));
  SampleRequest request;
  request.physics = PhysicsMode::Settle;
  const PreparedRequest prepared = generator.prepare(request);
  const std::vector<SceneResult> one = generator.sampleScenes(prepared, 7, 12, 1);
  const std::vector<SceneResult> two = generator.sampleScenes(prepared, 7, 12, 2);
  // A second request: its own model, compiled again.
  const std::vector<SceneResult> again =
      generator.sampleSceneRange(generator.prepare(request), 7, 6, 6, 2);
  bool anyMoved = false;
  for (std::size_t s = 0; s < one.size(); ++s) {
    ASSERT_TRUE(one[s].simulated);
    test::expectSamePlacements(one[s].placements, two[s].placements);
    EXPECT_EQ(one[s].stable, two[s].stable);
    for (std::size_t i = 0; i < one[s].physics.size(); ++i) {
      EXPECT_EQ(one[s].physics[i].moved, two[s].physics[i].moved);
      EXPECT_EQ(one[s].physics[i].turned, two[s].physics[i].turned);
      anyMoved = anyMoved || one[s].physics[i].moved > 0.01;
    }
    if (s >= 6) {
      test::expectSamePlacements(one[s].placements, again[s - 6].placements);
    }
  }
  EXPECT_TRUE(anyMoved);  // the pile really moves, so equality means something
}

TEST(Physics, HiddenObjectsAreNotSimulated) {
  const Sampled scene = sampleOne(kPile, PhysicsMode::Settle);
  ASSERT_TRUE(scene.success);
  const ObjectPlacement* f = findPlacement(scene.placements, "f");
  ASSERT_NE(f, nullptr);
  EXPECT_TRUE(f->hidden);
  const PhysicsOutcome& o = outcomeOf(scene, "f");
  EXPECT_EQ(o.moved, 0.0);
  EXPECT_EQ(o.turned, 0.0);
  EXPECT_FALSE(o.fallen);
  EXPECT_EQ(o.sampledPosition, f->position);
}

TEST(Physics, RetryDrawsAgainReproduciblyAndBounded) {
  // A stick stood on a pillar's top (r = 3 cm) anywhere within 4.5 cm of its axis: it stands
  // when its centre is over the top (about a third of the draws), else it falls off.
  const std::string yaml = R"(
ground_z: 0
physics_retry: true
physics_max_draws: 4
objects:
  post: {shape: cylinder, radius: 0.03, length: 0.2}
  stick: {shape: box, size: [0.02, 0.02, 0.1]}
fixtures:
  - {name: pillar, object: post, position: [0, 0, 0.1]}
samplers:
  - name: StickSampler
    objects: [stick]
    x_range: [-0.045, 0.045]
    y_range: [-0.045, 0.045]
    ensure_object_boundary_in_range: false
    ensure_valid_placement: false
    sample_args: {reference: pillar, on_top: true}
)";
  const SceneGenerator generator(buildFromYaml(yaml));
  SampleRequest request;
  request.physics = PhysicsMode::Check;
  const PreparedRequest prepared = generator.prepare(request);
  const std::vector<SceneResult> one = generator.sampleScenes(prepared, 3, 20, 1);
  const std::vector<SceneResult> two = generator.sampleScenes(prepared, 3, 20, 2);
  const SceneGenerator plain(buildFromYaml(yaml));
  std::size_t failed = 0;
  std::size_t redrawn = 0;
  for (std::size_t s = 0; s < one.size(); ++s) {
    test::expectSamePlacements(one[s].placements, two[s].placements);
    EXPECT_EQ(one[s].success, two[s].success);
    EXPECT_EQ(one[s].message, two[s].message);
    if (one[s].success) {
      EXPECT_TRUE(one[s].stable);  // with retry, a placed scene is a stable one
    } else {
      ++failed;
      EXPECT_EQ(one[s].message.rfind(
                    "physics: no stable scene in 4 draws; in the last, 'stick' moved", 0),
                0u)
          << one[s].message;
    }
    // A redrawn scene is not the first draw: the stream went on.
    const SceneResult first = plain.sampleScene(plain.prepare(SampleRequest()), 3, s);
    redrawn += one[s].placements[0].position != first.placements[0].position ? 1 : 0;
  }
  EXPECT_GT(redrawn, 0u);
  EXPECT_LT(failed, one.size());
}

// robosuite's sites need not lie on the geometry (its milk's bottom_site is 2.4 cm below the
// mesh): test/data/mjcf/gap_object.xml's bottom_site is 2.5 cm below its mesh and its top_site
// 1 cm above. Sampled by the sites, the carton and the lid on it land that much lower: a
// landing, counted as clearance like z_offset, not a motion.
TEST(Physics, SitesOffTheGeometryCountAsClearance) {
  const std::string yaml = "ground_z: 0.8\nobjects:\n  carton: {mjcf_file: " +
                           std::string(PLACEMENT_SAMPLERS_SOURCE_DIR) +
                           "/test/data/mjcf/gap_object.xml}\n" + R"(
  lid: {shape: box, size: [0.04, 0.04, 0.01]}
samplers:
  - name: CartonSampler
    objects: [carton]
    x_range: [-0.2, 0.2]
    y_range: [-0.2, 0.2]
    reference_pos: [0, 0, 0.8]
    z_offset: 0.01
  - name: LidSampler
    objects: [lid]
    x_range: [0, 0]
    y_range: [0, 0]
    ensure_object_boundary_in_range: false
    ensure_valid_placement: false
    sample_args: {reference: carton, on_top: true}
)";
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const Sampled scene = sampleOne(yaml, PhysicsMode::Settle, seed);
    ASSERT_TRUE(scene.success) << scene.message;
    ASSERT_TRUE(scene.simulated);
    EXPECT_TRUE(scene.stable);
    const ObjectModel& carton = *scene.placements[0].object;
    EXPECT_NEAR(carton.bottomGap, 0.025, 1e-6);
    EXPECT_NEAR(carton.topGap, 0.01, 1e-6);
    for (const char* name : {"carton", "lid"}) {
      const PhysicsOutcome& o = outcomeOf(scene, name);
      EXPECT_LT(o.moved, 0.001) << name;
      EXPECT_FALSE(o.fallen) << name;
    }
    // Sampled with its bottom_site 1 cm above the table (z 0.895), it rests on its mesh (0.86);
    // the lid rests on the mesh's top (0.92 + 0.005).
    EXPECT_NEAR(outcomeOf(scene, "carton").sampledPosition.z(), 0.8 + 0.01 + 0.085, 1e-12);
    EXPECT_NEAR(findPlacement(scene.placements, "carton")->position.z(), 0.86, 0.001);
    EXPECT_NEAR(findPlacement(scene.placements, "lid")->position.z(), 0.925, 0.001);
  }
}

// The other way round: a geometry reaching 2 cm below its bottom offset starts 2 cm in the
// ground; that is no clearance, and MuJoCo's push up counts.
TEST(Physics, GeometryBelowItsBottomOffsetIsNoClearance) {
  const Sampled scene = sampleOne(R"(
ground_z: 0.8
objects:
  block: {shape: box, size: [0.05, 0.05, 0.1], bottom_offset: [0, 0, -0.03]}
samplers:
  - name: S
    objects: [block]
    reference_pos: [0, 0, 0.8]
    z_offset: 0.01
    ensure_object_boundary_in_range: false
)",
                                  PhysicsMode::Check);
  ASSERT_TRUE(scene.success) << scene.message;
  EXPECT_NEAR(scene.placements[0].object->bottomGap, -0.02, 1e-12);
  EXPECT_FALSE(scene.stable);
  EXPECT_NEAR(scene.physics[0].moved, 0.02, 0.002);
}

TEST(Physics, FailedScenesAreNotSimulated) {
  const Sampled scene = sampleOne(R"(
ground_z: 0
max_attempts: 3
objects:
  big: {shape: box, size: [0.5, 0.5, 0.1]}
  other: {shape: box, size: [0.5, 0.5, 0.1]}
samplers:
  - {name: S, objects: [big, other], ensure_object_boundary_in_range: false}
)",
                                  PhysicsMode::Check);
  EXPECT_FALSE(scene.success);
  EXPECT_FALSE(scene.simulated);
  EXPECT_FALSE(scene.stable);
  EXPECT_TRUE(scene.physics.empty());
}

}  // namespace
}  // namespace placement_samplers
