// SceneGenerator: request validation, request fixtures, call-level reference and on_top,
// running one sub-sampler, and reproducibility across scene counts and threads.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "placement_samplers/collision/radius_checker.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/sampling/failure_summary.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::buildFromYaml;
using test::findPlacement;

// A table, a plate with a cup on it, and three objects on the table.
const std::string kScene = R"(
objects:
  table_top: {shape: box, size: [0.8, 0.8, 0.05]}
  cube: {shape: box, size: [0.042, 0.042, 0.042]}
  can: {shape: cylinder, radius: 0.033, length: 0.12}
  ball: {shape: sphere, radius: 0.03}
  plate: {shape: cylinder, radius: 0.09, length: 0.02}
  cup: {shape: cylinder, radius: 0.04, length: 0.09}
  pill: {shape: capsule, radius: 0.02, length: 0.08}
fixtures:
  - {name: table, object: table_top, position: [0, 0, 0.775]}
samplers:
  - name: PlateSampler
    objects: [plate]
    x_range: [-0.3, 0.3]
    y_range: [-0.3, 0.3]
    z_offset: 0.01
    sample_args: {reference: table, on_top: true}
  - name: CupSampler
    objects: [cup]
    x_range: [-0.02, 0.02]
    y_range: [-0.02, 0.02]
    ensure_object_boundary_in_range: false
    ensure_valid_placement: false
    sample_args: {reference: plate, on_top: true}
  - name: TableSampler
    objects: [cube, can, ball]
    x_range: [-0.35, 0.35]
    y_range: [-0.35, 0.35]
    rotation: [-0.785, 0.785]
    z_offset: 0.01
    sample_args: {reference: table, on_top: true}
hide: [pill]
)";

SceneGenerator makeGenerator(const std::string& yaml = kScene) {
  return SceneGenerator(buildFromYaml(yaml));
}

std::string requestError(const SceneGenerator& generator, const SampleRequest& request) {
  try {
    generator.prepare(request);
  } catch (const RequestError& e) {
    return e.what();
  }
  return "no RequestError";
}

RequestFixture boxFixture(const std::string& name, const Eigen::Vector3d& size,
                          const Eigen::Vector3d& position) {
  RequestFixture f;
  f.name = name;
  f.shape = Shape::box(size);
  f.position = position;
  return f;
}

TEST(SceneGenerator, SamplesTheConfiguredScene) {
  const SceneGenerator generator = makeGenerator();
  const PreparedRequest request = generator.prepare(SampleRequest());
  EXPECT_EQ(request.sampler, generator.config().root.get());
  EXPECT_TRUE(request.onTop);  // robosuite's default
  const SceneResult scene = generator.sampleScene(request, 5, 3);
  ASSERT_TRUE(scene.success) << scene.message;
  EXPECT_EQ(scene.seed, 5u);
  EXPECT_EQ(scene.index, 3u);
  EXPECT_TRUE(scene.message.empty());
  std::vector<std::string> names;
  for (const ObjectPlacement& p : scene.placements) {
    names.emplace_back(p.name);
  }
  // Sampling order, the hidden object last, no fixture.
  EXPECT_EQ(names, (std::vector<std::string>{"plate", "cup", "cube", "can", "ball", "pill"}));
  const ObjectPlacement* plate = findPlacement(scene.placements, "plate");
  const ObjectPlacement* cup = findPlacement(scene.placements, "cup");
  EXPECT_DOUBLE_EQ(cup->position.z(), plate->position.z() + plate->object->topOffset.z() -
                                          cup->object->bottomOffset.z());
  EXPECT_TRUE(findPlacement(scene.placements, "pill")->hidden);
}

TEST(SceneGenerator, UnknownSamplerListsTheConfiguredOnes) {
  const SceneGenerator generator = makeGenerator();
  SampleRequest request;
  request.sampler = "ShelfSampler";
  EXPECT_EQ(requestError(generator, request),
            "unknown sampler 'ShelfSampler' (configured: root, PlateSampler, CupSampler, "
            "TableSampler, HideSampler)");
}

TEST(SceneGenerator, UnknownReference) {
  const SceneGenerator generator = makeGenerator();
  SampleRequest request;
  request.reference = Reference::named("shelf");
  EXPECT_EQ(requestError(generator, request),
            "unknown reference 'shelf' (not a configured object or a fixture)");
  request.reference = Reference::at(Eigen::Vector3d(0, NAN, 0));
  EXPECT_EQ(requestError(generator, request), "reference_point must be finite");
  // A request fixture is a valid reference.
  request.reference = Reference::named("box");
  request.fixtures.push_back(
      boxFixture("box", Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector3d(1, 1, 0)));
  EXPECT_NO_THROW(generator.prepare(request));
}

TEST(SceneGenerator, FixtureErrors) {
  const SceneGenerator generator = makeGenerator();
  SampleRequest request;
  request.fixtures.push_back(
      boxFixture("cube", Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector3d::Zero()));
  EXPECT_EQ(requestError(generator, request),
            "fixture 'cube': the name is already a configured object");

  request.fixtures = {boxFixture("table", Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector3d::Zero())};
  EXPECT_EQ(requestError(generator, request), "fixture 'table': the name is used twice");

  request.fixtures = {boxFixture("a", Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector3d::Zero()),
                      boxFixture("a", Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector3d::Zero())};
  EXPECT_EQ(requestError(generator, request), "fixture 'a': the name is used twice");

  request.fixtures = {boxFixture("a b", Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector3d::Zero())};
  EXPECT_EQ(requestError(generator, request), "fixture name 'a b' must match [A-Za-z0-9_-]+");

  request.fixtures = {boxFixture("a", Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector3d::Zero())};
  request.fixtures[0].orientation = Eigen::Quaterniond(2.0, 0.0, 0.0, 0.0);
  EXPECT_EQ(requestError(generator, request),
            "fixture 'a': orientation must be a finite unit quaternion");
  request.fixtures[0].orientation = Eigen::Quaterniond(0.0, 0.0, 0.0, 0.0);
  EXPECT_EQ(requestError(generator, request),
            "fixture 'a': orientation must be a finite unit quaternion");

  request.fixtures = {
      boxFixture("a", Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector3d(INFINITY, 0, 0))};
  EXPECT_EQ(requestError(generator, request), "fixture 'a': position must be finite");

  request.fixtures = {boxFixture("a", Eigen::Vector3d(0.1, -0.1, 0.1), Eigen::Vector3d::Zero())};
  EXPECT_EQ(requestError(generator, request),
            "fixture 'a': box size y must be finite and positive, got -0.1");
  RequestFixture ball;
  ball.name = "a";
  ball.shape = Shape::sphere(0.0);
  request.fixtures = {ball};
  EXPECT_EQ(requestError(generator, request),
            "fixture 'a': sphere radius must be finite and positive, got 0");

  RequestFixture bare;
  bare.name = "a";
  request.fixtures = {bare};
  EXPECT_EQ(requestError(generator, request), "fixture 'a': give an object name or a shape");

  RequestFixture unknown;
  unknown.name = "a";
  unknown.object = "shelf_board";
  request.fixtures = {unknown};
  EXPECT_EQ(requestError(generator, request), "fixture 'a': unknown object 'shelf_board'");
}

TEST(SceneGenerator, RequestFixtureFromAConfiguredObject) {
  const SceneGenerator generator = makeGenerator();
  SampleRequest request;
  RequestFixture f;
  f.name = "board";
  f.object = "table_top";
  f.position = Eigen::Vector3d(3, 0, 0);
  // Stood on its edge: its bounds are derived under that orientation.
  f.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitX()));
  request.fixtures.push_back(f);
  const PreparedRequest prepared = generator.prepare(request);
  ASSERT_EQ(prepared.fixtures.size(), 2u);  // configured first, then the request's
  EXPECT_EQ(prepared.fixtures[0].name, "table");
  EXPECT_EQ(prepared.fixtures[1].name, "board");
  EXPECT_EQ(prepared.fixtures[1].objectName, "table_top");
  EXPECT_NEAR(prepared.fixtures[1].object->topOffset.z(), 0.4, 1e-12);
}

TEST(SceneGenerator, RequestFixturesAreAvoided) {
  // A tall block in the middle of the table: nothing on the table may overlap it.
  const SceneGenerator generator = makeGenerator();
  SampleRequest request;
  request.fixtures.push_back(
      boxFixture("block", Eigen::Vector3d(0.1, 0.1, 0.5), Eigen::Vector3d(0.0, 0.0, 1.0)));
  const PreparedRequest prepared = generator.prepare(request);
  const PlacedEntry block{"block", prepared.fixtures[1].object.get(),
                          Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Quaterniond::Identity(), true};
  for (const SceneResult& scene : generator.sampleScenes(prepared, 11, 200, 1)) {
    ASSERT_TRUE(scene.success) << scene.message;
    EXPECT_EQ(findPlacement(scene.placements, "block"), nullptr);
    for (const ObjectPlacement& p : scene.placements) {
      if (p.sampler != "CupSampler" && !p.hidden) {  // the cup is unchecked by configuration
        EXPECT_FALSE(radiusOverlap(block, test::asCandidate(p))) << p.name;
      }
    }
  }
}

TEST(SceneGenerator, FailingSceneReportsWhy) {
  // A block covering the whole table top: the plate cannot be placed.
  const SceneGenerator generator = makeGenerator();
  SampleRequest request;
  request.fixtures.push_back(
      boxFixture("block", Eigen::Vector3d(2.0, 2.0, 0.5), Eigen::Vector3d(0.0, 0.0, 1.0)));
  request.maxAttempts = 25;
  const SceneResult scene = generator.sampleScene(generator.prepare(request), 1, 0);
  EXPECT_FALSE(scene.success);
  EXPECT_EQ(scene.message,
            "could not place object 'plate' with sampler 'PlateSampler' in 25 attempts: 25 of them "
            "overlapped fixture 'block'");
  EXPECT_TRUE(scene.placements.empty());
}

TEST(SceneGenerator, CallLevelReferenceAndOnTop) {
  // A sampler without sample_args takes the call's reference and on_top. Unchecked: with
  // on_top false the ball sits inside the table top.
  const SceneGenerator generator = makeGenerator(R"(
objects:
  table_top: {shape: box, size: [0.8, 0.8, 0.05]}
  ball: {shape: sphere, radius: 0.03}
fixtures:
  - {name: table, object: table_top, position: [1, 2, 0.775]}
samplers:
  - {name: S, objects: [ball], x_range: [-0.1, 0.1], y_range: [-0.1, 0.1], z_offset: 0.01, reference_pos: [9, 9, 9], ensure_valid_placement: false}
)");
  SampleRequest request;
  request.reference = Reference::named("table");
  for (bool onTop : {true, false}) {
    request.onTop = onTop;
    const SceneResult scene = generator.sampleScene(generator.prepare(request), 3, 0);
    ASSERT_TRUE(scene.success) << scene.message;
    const ObjectPlacement& ball = scene.placements.at(0);
    EXPECT_LE(std::abs(ball.position.x() - 1.0), 0.07 + 1e-12);
    EXPECT_LE(std::abs(ball.position.y() - 2.0), 0.07 + 1e-12);
    if (onTop) {
      EXPECT_DOUBLE_EQ(ball.position.z(), 0.01 + (0.775 + 0.025) + 0.03);
    } else {
      EXPECT_DOUBLE_EQ(ball.position.z(), 0.01 + 0.775);
    }
  }
  // A point: no top offset.
  request.reference = Reference::at(Eigen::Vector3d(-1, -1, 0.5));
  request.onTop = true;
  const ObjectPlacement ball =
      generator.sampleScene(generator.prepare(request), 3, 0).placements.at(0);
  EXPECT_LE(std::abs(ball.position.x() + 1.0), 0.07 + 1e-12);
  EXPECT_DOUBLE_EQ(ball.position.z(), 0.01 + 0.5 + 0.03);
  // Nothing given: the sampler's reference_pos.
  const ObjectPlacement own =
      generator.sampleScene(generator.prepare(SampleRequest()), 3, 0).placements.at(0);
  EXPECT_LE(std::abs(own.position.x() - 9.0), 0.07 + 1e-12);
}

TEST(SceneGenerator, CallLevelReferenceDoesNotOverrideSampleArgs) {
  const SceneGenerator generator = makeGenerator();
  SampleRequest request;
  request.reference = Reference::at(Eigen::Vector3d(50, 50, 0));
  const SceneResult scene = generator.sampleScene(generator.prepare(request), 4, 0);
  ASSERT_TRUE(scene.success) << scene.message;
  // Everything has its own reference (the table, the plate, hiding): none near the point.
  for (const ObjectPlacement& p : scene.placements) {
    EXPECT_LT(std::abs(p.position.x()), 25.0) << p.name;
  }
}

TEST(SceneGenerator, RunsOneSubSamplerByName) {
  const SceneGenerator generator = makeGenerator();
  SampleRequest request;
  request.sampler = "TableSampler";
  const PreparedRequest prepared = generator.prepare(request);
  EXPECT_EQ(prepared.sampler->name(), "TableSampler");
  // It keeps the sample_args its parent gives it.
  EXPECT_EQ(prepared.reference.kind, Reference::Kind::Name);
  EXPECT_EQ(prepared.reference.name, "table");
  const SceneResult scene = generator.sampleScene(prepared, 6, 0);
  ASSERT_TRUE(scene.success) << scene.message;
  ASSERT_EQ(scene.placements.size(), 3u);
  for (const ObjectPlacement& p : scene.placements) {
    EXPECT_EQ(p.sampler, "TableSampler");
    EXPECT_DOUBLE_EQ(p.position.z(), 0.01 + (0.775 + 0.025) - p.object->bottomOffset.z());
  }
}

TEST(SceneGenerator, SubSamplerWhoseReferenceIsNotPlacedFails) {
  // Alone, CupSampler has no plate to stand on: the scene fails and says why.
  const SceneGenerator generator = makeGenerator();
  SampleRequest request;
  request.sampler = "CupSampler";
  const SceneResult scene = generator.sampleScene(generator.prepare(request), 7, 0);
  EXPECT_FALSE(scene.success);
  EXPECT_EQ(scene.message,
            "sampler 'CupSampler': reference 'plate' is neither a fixture nor an object placed "
            "before this sampler");
}

TEST(SceneGenerator, SubSamplerInsideACompositeKeepsInheritedArgs) {
  // Run alone, a sampler inside a composite must see what the full run gives it: here the
  // composite's reference (the table), not the call's default.
  const SceneGenerator generator = makeGenerator(R"(
objects:
  table_top: {shape: box, size: [0.8, 0.8, 0.05]}
  ball: {shape: sphere, radius: 0.03}
fixtures:
  - {name: table, object: table_top, position: [1, 2, 0.775]}
samplers:
  - name: OnTable
    type: sequential
    sample_args: {reference: table, on_top: true}
    samplers:
      - {name: BallSampler, objects: [ball], x_range: [-0.1, 0.1], y_range: [-0.1, 0.1]}
)");
  SampleRequest request;
  const SceneResult full = generator.sampleScene(generator.prepare(request), 8, 0);
  request.sampler = "BallSampler";
  const SceneResult alone = generator.sampleScene(generator.prepare(request), 8, 0);
  ASSERT_TRUE(full.success && alone.success);
  test::expectSamePlacements(full.placements, alone.placements);
  EXPECT_LE(std::abs(alone.placements.at(0).position.x() - 1.0), 0.07 + 1e-12);
}

TEST(SceneGenerator, RequestMaxAttemptsOverridesConfiguration) {
  const SceneGenerator generator = makeGenerator();
  SampleRequest request;
  request.maxAttempts = 3;
  request.fixtures.push_back(
      boxFixture("block", Eigen::Vector3d(2.0, 2.0, 0.5), Eigen::Vector3d(0.0, 0.0, 1.0)));
  const SceneResult scene = generator.sampleScene(generator.prepare(request), 1, 0);
  EXPECT_FALSE(scene.success);
  EXPECT_NE(scene.message.find(" in 3 attempts"), std::string::npos) << scene.message;
}

TEST(SceneGenerator, TimeLimit) {
  const SceneGenerator generator = makeGenerator();
  SampleRequest request;
  request.maxSeconds = -1.0;
  EXPECT_EQ(requestError(generator, request),
            "the time limit must be a non-negative number of seconds");
  request.maxSeconds = NAN;
  EXPECT_EQ(requestError(generator, request),
            "the time limit must be a non-negative number of seconds");
  // A blocked scene, a huge attempt limit and a time limit already passed when sampling starts.
  request.maxSeconds = 1e-9;
  request.maxAttempts = 100000000;
  request.fixtures.push_back(
      boxFixture("block", Eigen::Vector3d(2.0, 2.0, 0.5), Eigen::Vector3d(0.0, 0.0, 1.0)));
  const PreparedRequest prepared = generator.prepare(request);
  // A scene under way stops at its first time check (every 1024 attempts).
  const SceneResult one = generator.sampleScene(prepared, 1, 0);
  EXPECT_FALSE(one.success);
  EXPECT_EQ(one.message,
            "stopped placing object 'plate' with sampler 'PlateSampler' after 1023 attempts: the "
            "request ran out of time");
  // Scenes not started yet are reported, not sampled.
  const std::vector<SceneResult> scenes = generator.sampleScenes(prepared, 1, 3, 1);
  ASSERT_EQ(scenes.size(), 3u);
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    EXPECT_FALSE(scenes[i].success);
    EXPECT_EQ(scenes[i].seed, 1u);
    EXPECT_EQ(scenes[i].index, i);
    EXPECT_EQ(scenes[i].message, "not sampled: the request ran out of time");
  }
}

TEST(SceneGenerator, SceneTimeLimit) {
  const SceneGenerator generator = makeGenerator();
  SampleRequest request;
  for (const double bad : {-1.0, double(NAN), 2e6}) {
    request.maxSceneSeconds = bad;
    EXPECT_EQ(
        requestError(generator, request)
            .rfind("the time limit of a scene must be a number of seconds in [0, 1e+06], got ", 0),
        0u);
  }
  // A blocked scene and a huge attempt limit: each scene stops on its own (its clock starts at
  // its first time check, after 1023 attempts, and stops it at the second), and the next one
  // is still sampled.
  request.maxSceneSeconds = 1e-9;
  request.maxAttempts = 100000000;
  request.fixtures.push_back(
      boxFixture("block", Eigen::Vector3d(2.0, 2.0, 0.5), Eigen::Vector3d(0.0, 0.0, 1.0)));
  const std::vector<SceneResult> scenes =
      generator.sampleScenes(generator.prepare(request), 1, 3, 1);
  ASSERT_EQ(scenes.size(), 3u);
  for (const SceneResult& scene : scenes) {
    EXPECT_FALSE(scene.success);
    EXPECT_EQ(scene.message,
              "stopped placing object 'plate' with sampler 'PlateSampler' after 2047 attempts: "
              "the scene ran out of time (its limit is 1e-09 s)");
  }
}

TEST(SceneGenerator, SceneIndependentOfCountAndThreads) {
  const SceneGenerator generator = makeGenerator();
  const PreparedRequest prepared = generator.prepare(SampleRequest());
  const std::uint64_t seed = 123456789;
  const std::vector<SceneResult> one = generator.sampleScenes(prepared, seed, 40, 1);
  const std::vector<SceneResult> two = generator.sampleScenes(prepared, seed, 40, 2);
  const std::vector<SceneResult> fewer = generator.sampleScenes(prepared, seed, 7, 2);
  ASSERT_EQ(one.size(), 40u);
  ASSERT_EQ(two.size(), 40u);
  ASSERT_EQ(fewer.size(), 7u);
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].index, i);
    EXPECT_EQ(two[i].index, i);
    EXPECT_EQ(one[i].success, two[i].success);
    test::expectSamePlacements(one[i].placements, two[i].placements);
    if (i < fewer.size()) {
      test::expectSamePlacements(one[i].placements, fewer[i].placements);
    }
  }
  test::expectSamePlacements(one[17].placements,
                             generator.sampleScene(prepared, seed, 17).placements);
  // Scenes of one request differ from each other.
  EXPECT_TRUE(test::anyPositionDiffers(one[0].placements, one[1].placements));
}

TEST(SceneGenerator, DifferentSeedsDiffer) {
  const SceneGenerator generator = makeGenerator();
  const PreparedRequest prepared = generator.prepare(SampleRequest());
  const SceneResult a = generator.sampleScene(prepared, 1, 0);
  const SceneResult b = generator.sampleScene(prepared, 2, 0);
  EXPECT_TRUE(test::anyPositionDiffers(a.placements, b.placements));
  test::expectSamePlacements(a.placements, generator.sampleScene(prepared, 1, 0).placements);
}

TEST(SceneGenerator, ZeroScenes) {
  const SceneGenerator generator = makeGenerator();
  EXPECT_TRUE(generator.sampleScenes(generator.prepare(SampleRequest()), 1, 0, 2).empty());
}

// One line for a batch: the first failure (with its index when there are several scenes) and
// the count; nothing when all were placed.
TEST(FailureSummary, FirstFailureAndCount) {
  auto scene = [](std::uint64_t index, bool success, const std::string& message) {
    SceneResult r;
    r.index = index;
    r.success = success;
    r.message = message;
    return r;
  };
  FailureSummary none;
  none.add(scene(0, true, ""));
  EXPECT_EQ(none.failed(), 0u);
  EXPECT_EQ(none.message(1), "");

  FailureSummary one;
  one.add(scene(7, false, "could not place 'a'"));
  EXPECT_EQ(one.message(1), "could not place 'a'");
  EXPECT_EQ(one.message(3), "scene 7: could not place 'a'");

  FailureSummary several;
  several.add(scene(4, true, ""));
  several.add(scene(5, false, "first"));
  several.add(scene(6, false, "second"));
  EXPECT_EQ(several.failed(), 2u);
  EXPECT_EQ(several.message(10), "scene 5: first (2 of 10 scenes failed)");
}

}  // namespace
}  // namespace placement_samplers
