// Relations between objects (README, "Relations"): configuration errors naming the relation,
// every relation holding in every placed scene, positions uniform over the allowed set, the
// rotation draws as documented, fast failures, failure messages, --describe, the validator.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "placement_samplers/collision/make_collision_checker.hpp"
#include "placement_samplers/output/scene_json.hpp"
#include "placement_samplers/sampling/relation_links.hpp"
#include "placement_samplers/sampling/relations.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/validation/scene_validator.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::buildFromYaml;

const std::string kSource = PLACEMENT_SAMPLERS_SOURCE_DIR;

const std::string kObjects = R"(
objects:
  cube: {shape: box, size: [0.02, 0.02, 0.02]}
  can: {shape: cylinder, radius: 0.03, length: 0.1}
  plate: {shape: cylinder, radius: 0.1, length: 0.02}
  mark: {shape: box, size: [0.01, 0.01, 0.01]}
fixtures:
  - {name: post, object: mark, position: [0.5, 0.0, 0.8],
     orientation: [0.0, 0.0, 0.7071067811865476, 0.7071067811865476]}
)";

std::string buildError(const std::string& yaml) {
  return test::configError([&] { buildFromYaml(kObjects + yaml); });
}

struct Scenes {
  std::shared_ptr<const SceneGenerator> generator;
  std::vector<SceneResult> results;
};

Scenes scenes(const std::shared_ptr<SceneConfig>& config, std::size_t count, std::uint64_t seed) {
  auto generator = std::make_shared<const SceneGenerator>(config);
  auto results = generator->sampleScenes(generator->prepare(SampleRequest()), seed, count, 1);
  return Scenes{generator, std::move(results)};
}

/// The largest gap between the empirical distributions of @p a and @p b.
double ksTwoSample(std::vector<double> a, std::vector<double> b) {
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  std::size_t i = 0;
  std::size_t j = 0;
  double d = 0.0;
  while (i < a.size() && j < b.size()) {
    const double v = std::min(a[i], b[j]);
    while (i < a.size() && a[i] == v) {
      ++i;
    }
    while (j < b.size() && b[j] == v) {
      ++j;
    }
    d = std::max(d,
                 std::abs(static_cast<double>(i) / a.size() - static_cast<double>(j) / b.size()));
  }
  return d;
}

/// The two-sample KS critical distance at significance 1e-4.
double ksCritical2(std::size_t n, std::size_t m) {
  return std::sqrt(-0.5 * std::log(0.5e-4)) * std::sqrt(static_cast<double>(n + m) / (n * m));
}

TEST(Relations, ConfigurationErrorsNameTheRelation) {
  const std::string head = R"(
samplers:
  - name: S
    objects: [cube, can]
    x_range: [-0.3, 0.3]
    y_range: [-0.3, 0.3]
    relations:
)";
  EXPECT_EQ(buildError(head + "      - {next_to: nowhere, distance: [0, 0.1]}\n"),
            "samplers[0].relations[0].next_to: sampler 'S': relations[0] (next_to 'nowhere', gap "
            "[0, 0.1] m): unknown target 'nowhere': neither a configured fixture nor an object (a "
            "fixture every request gives takes request_fixture: true)");
  EXPECT_EQ(buildError(head + "      - {next_to: plate, distance: [0, 0.1]}\n"),
            "samplers[0].relations[0].next_to: sampler 'S': relations[0] (next_to 'plate', gap "
            "[0, 0.1] m): target 'plate' is an object that no earlier sampler places: it is not "
            "in the scene yet when this sampler runs");
  EXPECT_EQ(buildError(head + "      - {next_to: can, distance: [0, 0.1], objects: [cube]}\n"
                              "      - {away_from: cube, distance: 0.1, objects: [can]}\n"),
            "samplers[0].relations[0].next_to: sampler 'S': relations[0] (next_to 'can', gap "
            "[0, 0.1] m): the relations form a cycle: cube -> can -> cube");
  EXPECT_EQ(buildError(head + "      - {next_to: can, distance: [0, 0.1]}\n"),
            "samplers[0].relations[0].next_to: sampler 'S': relations[0] (next_to 'can', gap "
            "[0, 0.1] m): target 'can' is placed after object 'cube' (a sampler places its "
            "objects in their order): list it before");
  EXPECT_EQ(buildError(head + "      - {next_to: post, distance: [0, 0.1], objects: [plate]}\n"),
            "samplers[0].relations[0].objects[0]: sampler 'S': relations[0] (next_to 'post', gap "
            "[0, 0.1] m): 'plate' is not an object of this sampler");
  EXPECT_EQ(buildError(head + "      - {next_to: post, distance: [0.2, 0.1]}\n"),
            "samplers[0].relations[0].distance: expected [min, max] with min <= max, got [0.2, "
            "0.1]");
  EXPECT_EQ(buildError(head + "      - {next_to: post, distance: 0.1}\n"),
            "samplers[0].relations[0].distance: sampler 'S': expected the gap's [min, max] [m]");
  EXPECT_EQ(buildError(head + "      - {next_to: post, distance: [0, 0.1], sde: left}\n"),
            "samplers[0].relations[0]: unknown key 'sde' (expected one of: next_to, side, "
            "distance, objects, request_fixture)");
  EXPECT_EQ(buildError(head + "      - {next_to: post, face: post, distance: [0, 0.1]}\n"),
            "samplers[0].relations[0]: sampler 'S': give one of next_to, away_from, align_with, "
            "face; got next_to and face");
  EXPECT_EQ(buildError(head + "      - {next_to: post, side: up, distance: [0, 0.1]}\n"),
            "samplers[0].relations[0].side: sampler 'S': expected left, right, front, back or "
            "any, got 'up'");
  EXPECT_EQ(buildError(head + "      - {align_with: post}\n"),
            "samplers[0].relations[0]: missing required key 'tolerance'");
  EXPECT_EQ(buildError(head + "      - {align_with: post, tolerance: 0.1, period: 7}\n"),
            "samplers[0].relations[0].period: sampler 'S': expected a period in (0, 2 pi] [rad]");
  EXPECT_EQ(buildError(head + "      - {face: post}\n      - {align_with: post, tolerance: 0.1}\n"),
            "samplers[0]: sampler 'S': relations[1] (align_with 'post', tolerance 0.1 rad, period "
            "6.28319 rad) and relations[0] (face 'post', tolerance 0 rad) both set the yaw of "
            "object 'cube': give one align_with or face per object");
  EXPECT_EQ(buildError(head + "      - {face: post, request_fixture: true}\n"),
            "samplers[0].relations[0].request_fixture: sampler 'S': relations[0] (face 'post', "
            "tolerance 0 rad): 'post' is a configured fixture, not a fixture of the request");
  EXPECT_EQ(buildError(R"(
samplers:
  - {name: S, objects: [cube], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3], rotation_axis: x,
     relations: [{face: post}]}
)"),
            "samplers[0]: sampler 'S': relations[0]: face sets the turn about z: rotation_axis "
            "must be z");
  EXPECT_EQ(buildError(R"(
samplers:
  - {name: S, objects: [cube], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3], strategy: dense,
     relations: [{face: post}]}
)"),
            "samplers[0].relations: sampler 'S': relations take strategy rejection or "
            "free_space, not dense");
}

/// config/relations.yaml: every relation holds in every placed scene, by the validator, which
/// decides positions with sampling's own test.
TEST(Relations, TableSettingHoldsInEveryScene) {
  const auto config = buildSceneConfig(loadYamlFile(kSource + "/config/relations.yaml"));
  const Scenes s = scenes(config, 10000, 7);
  const PreparedRequest request = s.generator->prepare(SampleRequest());
  std::size_t placed = 0;
  for (const SceneResult& r : s.results) {
    if (!r.success) {
      continue;
    }
    ++placed;
    std::vector<GivenPose> poses;
    for (const ObjectPlacement& p : r.placements) {
      poses.push_back({std::string(p.name), p.position, p.orientation});
    }
    const SceneVerdict v = validateScene(*s.generator, request, poses);
    ASSERT_TRUE(v.valid) << "scene " << r.index << ": "
                         << (v.objects.empty() || v.objects[0].reasons.empty()
                                 ? std::string()
                                 : v.objects[0].reasons[0].message);
  }
  EXPECT_GT(placed, 9900u);
}

/// Relations on a surface region, under resting: stable, in a disk with a keep-out zone, with a
/// target of an earlier sampler and of the same sampler, in every collision mode: every placed
/// scene validates (positions by sampling's own test, angles within their slack).
TEST(Relations, HoldOnEveryRegionKindInEveryMode) {
  const auto config = buildFromYaml(R"(
objects:
  cube: {shape: box, size: [0.02, 0.02, 0.02]}
  can: {shape: cylinder, radius: 0.03, length: 0.1}
  plate: {shape: cylinder, radius: 0.1, length: 0.02}
  mark: {shape: box, size: [0.01, 0.01, 0.01]}
  slab: {shape: box, size: [1.0, 1.0, 0.1]}
  brick: {shape: box, size: [0.08, 0.04, 0.02]}
fixtures:
  - {name: post, object: mark, position: [0.5, 0.0, 0.8],
     orientation: [0.0, 0.0, 0.7071067811865476, 0.7071067811865476]}
  - {name: board, object: slab, position: [0.0, 2.0, 0.05]}
samplers:
  - {name: P, objects: [plate], region: {shape: surface, of: board},
     relations: [{away_from: post, distance: 1.0}, {face: post, tolerance: 0.3}]}
  - {name: R, objects: [brick, cube], resting: stable, x_range: [-0.6, 0.6], y_range: [1.4, 2.6],
     z_offset: 0.2, relations: [{next_to: plate, side: front, distance: [0.0, 0.1]},
                                {away_from: brick, distance: 0.02, objects: [cube]}]}
  - {name: S, objects: [can], region: {shape: disk, center: [0, 2], radius: 0.45},
     keep_out: [{shape: disk, center: [0, 2.1], radius: 0.05, frame: world}], z_offset: 0.2,
     relations: [{away_from: plate, distance: 0.05}, {align_with: post, tolerance: 0.2}]}
)");
  for (const CollisionMode mode :
       {CollisionMode::Radius, CollisionMode::Fcl, CollisionMode::RadiusAndFcl}) {
    auto generator = std::make_shared<const SceneGenerator>(config);
    SampleRequest request;
    request.collisionCheck = mode;
    const PreparedRequest prepared = generator->prepare(request);
    const std::vector<SceneResult> results = generator->sampleScenes(prepared, 9, 1000, 1);
    std::size_t placed = 0;
    for (const SceneResult& r : results) {
      if (!r.success) {
        continue;
      }
      ++placed;
      std::vector<GivenPose> poses;
      for (const ObjectPlacement& p : r.placements) {
        poses.push_back({std::string(p.name), p.position, p.orientation});
      }
      const SceneVerdict v = validateScene(*generator, prepared, poses);
      ASSERT_TRUE(v.valid) << collisionModeName(mode) << " scene " << r.index;
    }
    EXPECT_GT(placed, 900u) << collisionModeName(mode) << ": " << results[0].message;
  }
}

/// In the fcl modes the gap is the shapes' exact distance: a stick next to a disc may lie along
/// it, closer than its horizontal disk allows; every placed scene validates and rviz's lines
/// agree.
TEST(Relations, FclModesMeasureTheShapesExactGap) {
  const auto config = buildFromYaml(R"(
objects:
  plate: {shape: cylinder, radius: 0.1, length: 0.02}
  stick: {shape: box, size: [0.3, 0.02, 0.02]}
fixtures:
  - {name: disc, object: plate, position: [0.0, 0.0, 0.8]}
samplers:
  - {name: S, objects: [stick], x_range: [-0.4, 0.4], y_range: [-0.4, 0.4],
     reference_pos: [0, 0, 0.8], relations: [{next_to: disc, distance: [0.0, 0.02]}]}
)");
  const double radii = 0.1 + config->findObject("stick")->horizontalRadius;
  for (const CollisionMode mode : {CollisionMode::Radius, CollisionMode::Fcl}) {
    auto generator = std::make_shared<const SceneGenerator>(config);
    SampleRequest request;
    request.collisionCheck = mode;
    const PreparedRequest prepared = generator->prepare(request);
    const std::vector<SceneResult> results = generator->sampleScenes(prepared, 4, 500, 1);
    std::size_t inside = 0;  // centres closer than the disks allow
    for (const SceneResult& r : results) {
      ASSERT_TRUE(r.success) << r.message;
      const ObjectPlacement& p = r.placements[0];
      const double centres = p.position.head<2>().norm();
      inside += centres < radii ? 1 : 0;
      if (mode == CollisionMode::Radius) {
        EXPECT_GE(centres - radii, 0.0);
        EXPECT_LE(centres - radii, 0.02);
      }
      // An independent FCL checker: the exact distance within the range.
      std::unique_ptr<CollisionChecker> fcl = makeCollisionChecker(CollisionMode::Fcl, 0.0);
      std::vector<PlacedEntry> entries{PlacedEntry("disc", prepared.fixtures[0].object.get(),
                                                   prepared.fixtures[0].position,
                                                   prepared.fixtures[0].orientation, true)};
      fcl->added(entries, 0);
      Candidate c;
      c.object = p.object;
      c.position = p.position;
      c.orientation = p.orientation;
      double gap = 0.0;
      ASSERT_TRUE(fcl->exactDistance(entries, 0, c, gap));
      if (mode == CollisionMode::Fcl) {
        EXPECT_GE(gap, 0.0);
        EXPECT_LE(gap, 0.02);
      }
      const SceneVerdict v =
          validateScene(*generator, prepared, {{"stick", p.position, p.orientation}});
      EXPECT_TRUE(v.valid) << collisionModeName(mode) << " scene " << r.index;
      const std::vector<RelationLink> links = relationLinks(prepared, r);
      ASSERT_EQ(links.size(), 1u);
      EXPECT_TRUE(links[0].satisfied);
    }
    if (mode == CollisionMode::Fcl) {
      EXPECT_GT(inside, 100u);
    } else {
      EXPECT_EQ(inside, 0u);
    }
  }
}

/// A target that every request gives: a scene without it fails at once naming the relation,
/// one with it holds the relation.
TEST(Relations, RequestFixtureTargets) {
  const auto config = buildFromYaml(kObjects + R"(
samplers:
  - {name: S, objects: [cube], x_range: [-0.5, 0.5], y_range: [-0.5, 0.5],
     relations: [{next_to: robot, distance: [0.0, 0.1], request_fixture: true}]}
)");
  auto generator = std::make_shared<const SceneGenerator>(config);
  const SceneResult missing = generator->sampleScene(generator->prepare(SampleRequest()), 1, 0);
  ASSERT_FALSE(missing.success);
  EXPECT_EQ(missing.message,
            "could not place object 'cube' with sampler 'S': relations[0] (next_to 'robot', gap "
            "[0, 0.1] m) cannot hold: its target is neither a fixture nor an object placed "
            "before it");
  SampleRequest request;
  request.fixtures.push_back({"robot", "mark", std::nullopt, Eigen::Vector3d(0.2, 0.1, 0.0),
                              Eigen::Quaterniond::Identity()});
  const PreparedRequest prepared = generator->prepare(request);
  const std::vector<SceneResult> results = generator->sampleScenes(prepared, 1, 200, 1);
  for (const SceneResult& r : results) {
    ASSERT_TRUE(r.success) << r.message;
    const double gap = (r.placements[0].position.head<2>() - Eigen::Vector2d(0.2, 0.1)).norm() -
                       r.placements[0].object->horizontalRadius -
                       prepared.fixtures.back().object->horizontalRadius;
    EXPECT_GE(gap, -1e-12);
    EXPECT_LE(gap, 0.1 + 1e-12);
  }
}

/// rviz's lines: one per object and relation, satisfied in a sampled scene; a fork moved to the
/// plate's other side breaks its next_to and its face (the chair is in another direction).
TEST(Relations, LinksForDisplay) {
  const auto config = buildSceneConfig(loadYamlFile(kSource + "/config/relations.yaml"));
  Scenes s = scenes(config, 1, 7);
  const PreparedRequest request = s.generator->prepare(SampleRequest());
  ASSERT_TRUE(s.results[0].success);
  std::vector<RelationLink> links = relationLinks(request, s.results[0]);
  // plate: next_to chair1, face; fork, knife: next_to plate, face; glass: next_to plate,
  // away_from knife, face.
  ASSERT_EQ(links.size(), 9u);
  for (const RelationLink& l : links) {
    EXPECT_TRUE(l.satisfied) << l.object << " " << l.index;
  }
  EXPECT_EQ(links[2].object, "fork");
  EXPECT_EQ(links[2].target, "plate");
  EXPECT_EQ(links[2].from, s.results[0].placements[1].position);
  EXPECT_EQ(links[2].to, s.results[0].placements[0].position);
  SceneResult moved = s.results[0];
  const Eigen::Vector3d plate = moved.placements[0].position;
  moved.placements[1].position.head<2>() =
      2 * plate.head<2>() - moved.placements[1].position.head<2>();
  links = relationLinks(request, moved);
  for (const RelationLink& l : links) {
    EXPECT_EQ(l.satisfied, l.object != "fork") << l.object << " " << l.index;
  }
}

/// A uniform sampler with the relation and the same one without, its placements filtered by
/// the relation: the same distribution of x, y and of the direction from the target.
void expectUniformOverAllowed(const std::string& region, const std::string& relation) {
  const auto related = buildFromYaml(kObjects + "samplers:\n  - {name: S, objects: [can], " +
                                     region + ", relations: [" + relation + "]}\n");
  const auto free =
      buildFromYaml(kObjects + "samplers:\n  - {name: S, objects: [can], " + region + "}\n");
  const Scenes a = scenes(related, 20000, 11);
  const Scenes b = scenes(free, 200000, 12);
  const UniformRandomSampler& sampler =
      dynamic_cast<const UniformRandomSampler&>(*related->root->children()[0].sampler);
  const RelationTarget target = relationTarget(
      PlacedEntry("post", related->fixtures[0].object.get(), related->fixtures[0].position,
                  related->fixtures[0].orientation, true));
  const PositionTest test(sampler.params().relations[0], 0, target);
  const double radius = related->findObject("can")->horizontalRadius;
  std::vector<double> ax, ay, aa, bx, by, ba;
  for (const SceneResult& r : a.results) {
    ASSERT_TRUE(r.success);
    const Eigen::Vector2d p = r.placements[0].position.head<2>();
    ASSERT_TRUE(test.holds(p, radius));
    ax.push_back(p.x());
    ay.push_back(p.y());
    aa.push_back(std::atan2(p.y() - target.centre.y(), p.x() - target.centre.x()));
  }
  for (const SceneResult& r : b.results) {
    const Eigen::Vector2d p = r.placements[0].position.head<2>();
    if (test.holds(p, radius)) {
      bx.push_back(p.x());
      by.push_back(p.y());
      ba.push_back(std::atan2(p.y() - target.centre.y(), p.x() - target.centre.x()));
    }
  }
  ASSERT_GT(bx.size(), 2000u);
  const double critical = ksCritical2(ax.size(), bx.size());
  EXPECT_LT(ksTwoSample(ax, bx), critical) << relation;
  EXPECT_LT(ksTwoSample(ay, by), critical) << relation;
  EXPECT_LT(ksTwoSample(aa, ba), critical) << relation;
}

TEST(Relations, PositionsAreUniformOverTheAllowedSet) {
  // The post faces +y: its left is -x.
  const std::string rect =
      "x_range: [-0.4, 0.4], y_range: [-0.4, 0.4], reference_pos: [0.5, 0, 0.8]";
  expectUniformOverAllowed(rect, "{next_to: post, side: left, distance: [0.05, 0.2]}");
  expectUniformOverAllowed(rect, "{away_from: post, distance: 0.25}");
  expectUniformOverAllowed(
      "region: {shape: disk, center: [0, 0], radius: 0.4}, "
      "keep_out: [{shape: disk, center: [0.1, 0.1], radius: 0.05}], "
      "reference_pos: [0.5, 0, 0.8]",
      "{next_to: post, side: front, distance: [0.0, 0.15]}");
}

/// In the fcl modes the exact gap depends on the turn, drawn before the relation tests: the
/// accepted (x, y, yaw) are those of the sampler without the relation, filtered by the exact
/// gap at that pose.
TEST(Relations, FclPosesAreUniformOverTheAllowedSet) {
  const std::string head = R"(
collision_check: fcl
objects:
  plate: {shape: cylinder, radius: 0.1, length: 0.02}
  stick: {shape: box, size: [0.3, 0.02, 0.02]}
fixtures:
  - {name: disc, object: plate, position: [0.0, 0.0, 0.8]}
samplers:
  - {name: S, objects: [stick], x_range: [-0.4, 0.4], y_range: [-0.4, 0.4],
     reference_pos: [0, 0, 0.8])";
  const auto related =
      buildFromYaml(head + ", relations: [{next_to: disc, side: front, distance: [0.0, 0.05]}]}\n");
  const auto free = buildFromYaml(head + "}\n");
  const Scenes a = scenes(related, 20000, 21);
  const Scenes b = scenes(free, 200000, 22);
  const UniformRandomSampler& sampler =
      dynamic_cast<const UniformRandomSampler&>(*related->root->children()[0].sampler);
  const FixtureSpec& disc = related->fixtures[0];
  const std::vector<PlacedEntry> entries{
      PlacedEntry("disc", disc.object.get(), disc.position, disc.orientation, true)};
  const PositionTest test(sampler.params().relations[0], 0, relationTarget(entries[0]));
  std::unique_ptr<CollisionChecker> fcl = makeCollisionChecker(CollisionMode::Fcl, 0.0);
  fcl->added(entries, 0);
  auto holds = [&](const ObjectPlacement& p) {
    double gap = 0.0;
    EXPECT_TRUE(fcl->exactDistance(entries, 0, {p.object, p.position, p.orientation}, gap));
    return test.holdsGap(p.position.head<2>(), gap);
  };
  std::vector<double> values[2][3];  // [related, filtered][x, y, yaw]
  for (int k = 0; k < 2; ++k) {
    for (const SceneResult& r : (k == 0 ? a : b).results) {
      ASSERT_EQ(r.success, k == 0 || r.success);
      if (!r.success) {
        continue;
      }
      const ObjectPlacement& p = r.placements[0];
      if (k == 0) {
        ASSERT_TRUE(holds(p)) << "scene " << r.index;
      } else if (!holds(p)) {
        continue;
      }
      values[k][0].push_back(p.position.x());
      values[k][1].push_back(p.position.y());
      values[k][2].push_back(headingOf(p.orientation));
    }
  }
  ASSERT_GT(values[1][0].size(), 2000u);
  const double critical = ksCritical2(values[0][0].size(), values[1][0].size());
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(ksTwoSample(values[0][i], values[1][i]), critical) << "coordinate " << i;
  }
}

TEST(Relations, FaceDrawsOneTurnWithinTheTolerance) {
  // One object, every attempt accepted: x, y, then U(-tolerance, tolerance) after the angle
  // towards the target.
  const auto config = buildFromYaml(kObjects + R"(
samplers:
  - {name: S, objects: [cube], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3],
     reference_pos: [0, 0, 0.8], relations: [{face: post, tolerance: 0.2}]}
)");
  const Scenes s = scenes(config, 2000, 5);
  std::vector<double> offsets;
  for (const SceneResult& r : s.results) {
    ASSERT_TRUE(r.success);
    Engine e = sceneEngine(5, r.index);
    const double radius = config->findObject("cube")->horizontalRadius;
    const double x = uniform(e, -0.3 + radius, 0.3 - radius);
    const double y = uniform(e, -0.3 + radius, 0.3 - radius);
    const double angle = std::atan2(0.0 - y, 0.5 - x) + uniform(e, -0.2, 0.2);
    const ObjectPlacement& p = r.placements[0];
    EXPECT_NEAR(p.position.x(), x, 1e-15);
    EXPECT_NEAR(p.position.y(), y, 1e-15);
    const Eigen::Quaterniond want(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
    EXPECT_NEAR(std::abs(p.orientation.dot(want)), 1.0, 1e-12);
    offsets.push_back(headingOf(p.orientation) - std::atan2(-y, 0.5 - x));
  }
  for (double& o : offsets) {
    o = std::remainder(o, 2 * M_PI);
  }
  test::expectUniform(offsets, -0.2, 0.2);
}

TEST(Relations, AlignedTurnsCoverTheAllowedIntervalsInOrder) {
  RotationTest t;
  t.centre = 0.3;
  t.tolerance = 0.1;
  t.period = M_PI / 2;
  // [0.2, 0.4] + k pi/2 for k = 0 .. 3 within [0, 2 pi].
  EXPECT_NEAR(alignedLength(t, 0.0, 2 * M_PI), 0.8, 1e-12);
  EXPECT_NEAR(alignedTurn(t, 0.0, 2 * M_PI, 0.0), 0.2, 1e-12);
  EXPECT_NEAR(alignedTurn(t, 0.0, 2 * M_PI, 0.25), 0.25 + M_PI / 2, 1e-12);
  EXPECT_NEAR(alignedTurn(t, 0.0, 2 * M_PI, 0.79), 0.39 + 3 * M_PI / 2, 1e-12);
  // Clipped at both ends: [0.25, 0.4] and [0.2 + pi/2, 1.8].
  EXPECT_NEAR(alignedLength(t, 0.25, 1.8), 0.15 + (1.8 - 0.2 - M_PI / 2), 1e-12);
  EXPECT_NEAR(alignedTurn(t, 0.25, 1.8, 0.1), 0.35, 1e-12);
  EXPECT_NEAR(alignedTurn(t, 0.25, 1.8, 0.16), 0.21 + M_PI / 2, 1e-12);
  EXPECT_EQ(alignedLength(t, 0.5, 0.6), 0.0);  // between two intervals
  t.tolerance = 1.0;                           // wider than the period: everything
  EXPECT_EQ(alignedLength(t, -1.0, 4.0), 5.0);
}

TEST(Relations, AlignWithDrawsOneTurnAlongTheAllowedIntervals) {
  // The post's yaw is pi/2; period pi/2: four intervals of 0.2 rad in [0, 2 pi].
  const auto config = buildFromYaml(kObjects + R"(
samplers:
  - {name: S, objects: [cube], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3],
     reference_pos: [0, 0, 0.8], relations: [{align_with: post, tolerance: 0.1, period: 1.5707963267948966}]}
)");
  const Scenes s = scenes(config, 4000, 6);
  RotationTest t;
  t.centre = M_PI / 2;
  t.tolerance = 0.1;
  t.period = M_PI / 2;
  const double length = alignedLength(t, 0.0, 2 * M_PI);
  EXPECT_NEAR(length, 0.8, 1e-12);
  std::vector<double> turns;
  for (const SceneResult& r : s.results) {
    ASSERT_TRUE(r.success);
    Engine e = sceneEngine(6, r.index);
    uniform(e, 0, 1);  // x
    uniform(e, 0, 1);  // y
    const double angle = alignedTurn(t, 0.0, 2 * M_PI, uniform(e, 0.0, length));
    const Eigen::Quaterniond want(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
    EXPECT_NEAR(std::abs(r.placements[0].orientation.dot(want)), 1.0, 1e-12);
    EXPECT_LE(angleApart(headingOf(r.placements[0].orientation), M_PI / 2, M_PI / 2), 0.1 + 1e-9);
    turns.push_back(angle);
  }
  // Uniform over the union: each of the four intervals a quarter of the turns.
  for (int k = 0; k < 4; ++k) {
    const double c = M_PI / 2 * k;
    const auto in = std::count_if(turns.begin(), turns.end(), [&](double a) {
      return angleApart(a, c, 2 * M_PI) <= 0.1 + 1e-12;
    });
    EXPECT_NEAR(static_cast<double>(in) / turns.size(), 0.25, 0.03) << k;
  }
}

TEST(Relations, ImpossibleRelationsFailAtOnceWithTheReason) {
  const Scenes far = scenes(buildFromYaml(kObjects + R"(
samplers:
  - {name: S, objects: [cube], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3],
     reference_pos: [3, 0, 0.8], relations: [{next_to: post, distance: [0, 0.1]}]}
)"),
                            1, 1);
  ASSERT_FALSE(far.results[0].success);
  EXPECT_EQ(far.results[0].message,
            "could not place object 'cube' with sampler 'S': relations[0] (next_to 'post', gap "
            "[0, 0.1] m) cannot hold anywhere: its region's positions are at least 2.21414 m from "
            "the target's centre, the relation needs at most 0.121213 m");
  // The post faces +y; its back (-y) is outside the region above it.
  const Scenes side = scenes(buildFromYaml(kObjects + R"(
samplers:
  - {name: S, objects: [cube], x_range: [-0.3, 0.3], y_range: [0.1, 0.3],
     reference_pos: [0.5, 0, 0.8], relations: [{next_to: post, side: back, distance: [0, 1]}]}
)"),
                             1, 1);
  ASSERT_FALSE(side.results[0].success);
  EXPECT_EQ(side.results[0].message,
            "could not place object 'cube' with sampler 'S': relations[0] (next_to 'post', side "
            "back, gap [0, 1] m) cannot hold anywhere: no position of its region is on the back "
            "of the target");
  // A fixed rotation that cannot align.
  const Scenes fixed = scenes(buildFromYaml(kObjects + R"(
samplers:
  - {name: S, objects: [cube], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3], rotation: 0.0,
     relations: [{align_with: post, tolerance: 0.1}]}
)"),
                              1, 1);
  EXPECT_EQ(fixed.results[0].message,
            "could not place object 'cube' with sampler 'S': relations[0] (align_with 'post', "
            "tolerance 0.1 rad, period 6.28319 rad) cannot hold: the fixed rotation 0 rad gives "
            "object 'cube' a yaw 1.5708 rad from the target's (modulo the period)");
}

TEST(Relations, AFailureSaysWhichRelationRefusedHowManyAttempts) {
  const Scenes s = scenes(buildFromYaml(kObjects + R"(
samplers:
  - {name: S, objects: [cube], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3], max_attempts: 100,
     reference_pos: [0.5, 0.35, 0.8],
     relations: [{away_from: post, distance: 0}, {next_to: post, distance: [0.05, 0.050001]}]}
)"),
                          1, 1);
  ASSERT_FALSE(s.results[0].success);
  EXPECT_EQ(s.results[0].message,
            "could not place object 'cube' with sampler 'S' in 100 attempts: 100 of them were "
            "refused by relations[1] (next_to 'post', gap [0.05, 0.050001] m)");
}

TEST(Relations, DescribedAndValidated) {
  const auto config = buildFromYaml(kObjects + R"(
samplers:
  - {name: P, objects: [plate], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3]}
  - {name: S, objects: [cube], x_range: [-0.5, 0.5], y_range: [-0.5, 0.5],
     relations: [{next_to: plate, side: left, distance: [0.0, 0.05]}, {face: post, tolerance: 0.1}]}
)");
  const std::string json = configToJson(*config);
  EXPECT_NE(json.find("\"relations\": [{\"next_to\": \"plate\", \"side\": \"left\", \"distance\": "
                      "[0, 0.05], \"objects\": null, \"request_fixture\": false}, {\"face\": "
                      "\"post\", \"tolerance\": 0.1, \"objects\": null, \"request_fixture\": "
                      "false}]"),
            std::string::npos)
      << json;
  const SceneGenerator generator(config);
  const PreparedRequest request = generator.prepare(SampleRequest());
  // The plate at the origin facing +x: its left is +y. The cube on its right instead, 0.03 m
  // off, facing away from the post.
  const std::vector<GivenPose> poses{
      {"plate", Eigen::Vector3d(0, 0, 0.01), Eigen::Quaterniond::Identity()},
      {"cube", Eigen::Vector3d(0, -0.1 - 0.01 * std::sqrt(2.0) - 0.03, 0.01),
       Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()))}};
  const SceneVerdict v = validateScene(generator, request, poses);
  ASSERT_EQ(v.objects.size(), 2u);
  EXPECT_TRUE(v.objects[0].valid) << v.objects[0].reasons[0].message;
  ASSERT_EQ(v.objects[1].reasons.size(), 2u);
  const Violation& side = v.objects[1].reasons[0];
  EXPECT_EQ(side.kind, Violation::Kind::Relation);
  EXPECT_EQ(side.other, "plate");
  EXPECT_NEAR(side.distance, 0.03, 1e-12);
  EXPECT_EQ(side.message,
            "object 'cube': relations[0] (next_to 'plate', side left, gap [0, 0.05] m) of sampler "
            "'S' does not hold: it is on the right of 'plate', not on its left");
  EXPECT_EQ(std::string(violationKindName(side.kind)), "relation");
  const Violation& face = v.objects[1].reasons[1];
  EXPECT_EQ(face.other, "post");
  EXPECT_GT(face.distance, 1.0);
  EXPECT_NEAR(face.distance, M_PI - std::atan2(0.1 + 0.01 * std::sqrt(2.0) + 0.03, 0.5), 1e-12);
  EXPECT_EQ(face.message,
            "object 'cube': relations[1] (face 'post', tolerance 0.1 rad) of sampler 'S' does "
            "not hold: its yaw is 2.86092 rad off the direction to 'post'");
}

}  // namespace
}  // namespace placement_samplers
