// Surface regions: objects on the support surfaces of fixtures and earlier objects. Exact
// heights, uniform by area, never in a hole or under too little clearance, insets, request
// fixtures, every error, validation, thread independence.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/output/scene_json.hpp"
#include "placement_samplers/sampling/sampler_regions.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "placement_samplers/validation/scene_validator.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::buildFromYaml;

// A shelf of three 0.6 x 0.3 x 0.02 boards (tops at 0.02, 0.36, 0.70 above its origin) between
// two side panels that touch the boards' ends; a frame of four boards around a 0.2 x 0.2 hole;
// objects of several heights.
const std::string kScene = R"(
objects:
  shelf:
    shapes:
      - {shape: box, size: [0.6, 0.3, 0.02], position: [0, 0, 0.01]}
      - {shape: box, size: [0.6, 0.3, 0.02], position: [0, 0, 0.35]}
      - {shape: box, size: [0.6, 0.3, 0.02], position: [0, 0, 0.69]}
      - {shape: box, size: [0.02, 0.3, 0.72], position: [-0.31, 0, 0.36]}
      - {shape: box, size: [0.02, 0.3, 0.72], position: [0.31, 0, 0.36]}
  frame:
    shapes:
      - {shape: box, size: [0.6, 0.2, 0.04], position: [0, 0.2, 0]}
      - {shape: box, size: [0.6, 0.2, 0.04], position: [0, -0.2, 0]}
      - {shape: box, size: [0.2, 0.2, 0.04], position: [0.2, 0, 0]}
      - {shape: box, size: [0.2, 0.2, 0.04], position: [-0.2, 0, 0]}
  ball: {shape: sphere, radius: 0.1}
  table: {shape: box, size: [0.8, 0.6, 0.05]}
  tray: {shape: box, size: [0.3, 0.2, 0.02]}
  cube: {shape: box, size: [0.04, 0.04, 0.04]}
  can: {shape: cylinder, radius: 0.03, length: 0.12}
  bottle: {shape: cylinder, radius: 0.035, length: 0.4}
fixtures:
  - {name: shelf1, object: shelf, position: [0.5, 0.0, 0.0]}
  - {name: frame1, object: frame, position: [-1.0, 0.0, 0.5]}
  - {name: ball1, object: ball, position: [0.0, 2.0, 0.5]}
  - {name: table1, object: table, position: [0.0, -2.0, 0.775]}
)";

struct Scenes {
  std::shared_ptr<const SceneGenerator> generator;
  PreparedRequest request;
  std::vector<SceneResult> results;
};

Scenes scenes(const std::string& yaml, std::size_t count, unsigned threads = 1,
              const SampleRequest& request = SampleRequest(), std::uint64_t seed = 5) {
  Scenes s;
  s.generator = std::make_shared<const SceneGenerator>(buildFromYaml(kScene + yaml));
  s.request = s.generator->prepare(request);
  s.results = s.generator->sampleScenes(s.request, seed, count, threads);
  return s;
}

std::string buildError(const std::string& yaml) {
  return test::configError([&] { buildFromYaml(kScene + yaml); });
}

std::string requestError(const std::string& yaml, const SampleRequest& request) {
  const SceneGenerator generator(buildFromYaml(kScene + yaml));
  try {
    generator.prepare(request);
  } catch (const RequestError& e) {
    return e.what();
  }
  return "no RequestError";
}

const std::string kOnShelf =
    "samplers:\n  - {name: S, objects: [cube, can], region: {shape: surface, of: shelf1, "
    "min_area: 0.01}, z_offset: 0.001}\n";

TEST(SurfaceRegion, EveryObjectLiesOnABoardAtItsExactHeight) {
  const Scenes s = scenes(kOnShelf, 600);
  std::map<double, int> boards;
  for (const SceneResult& scene : s.results) {
    ASSERT_TRUE(scene.success) << scene.message;
    for (const ObjectPlacement& p : scene.placements) {
      const ObjectModel& o = *p.object;
      // The surface height the placement implies, and the board it must be.
      const double surface = p.position.z() + o.bottomOffset.z() - 0.001;
      bool onBoard = false;
      for (const double top : {0.02, 0.36, 0.70}) {
        if (std::abs(surface - top) < 1e-9) {
          EXPECT_NEAR(p.position.z(), top - o.bottomOffset.z() + 0.001, 1e-12);
          onBoard = true;
          ++boards[top];
        }
      }
      EXPECT_TRUE(onBoard) << p.name << " at z " << p.position.z();
      // Inset by the horizontal radius: the whole disk on the board.
      EXPECT_LE(std::abs(p.position.x() - 0.5), 0.3 - o.horizontalRadius + 1e-12);
      EXPECT_LE(std::abs(p.position.y()), 0.15 - o.horizontalRadius + 1e-12);
    }
  }
  EXPECT_EQ(boards.size(), 3u);
}

TEST(SurfaceRegion, SurfacesArePickedByAreaAndPointsAreUniformOnOne) {
  // The three boards have the same area: chi-square with 2 degrees of freedom on the board
  // picked (p = 0.001: 13.8); x uniform over the inset board (KS).
  const Scenes s = scenes(
      "samplers:\n  - {name: S, objects: [cube], region: {shape: surface, of: shelf1}}\n", 3000);
  std::map<long, int> counts;
  std::vector<double> xs;
  for (const SceneResult& scene : s.results) {
    ASSERT_TRUE(scene.success);
    const ObjectPlacement& p = scene.placements[0];
    ++counts[std::lround(100.0 * (p.position.z() + p.object->bottomOffset.z()))];
    xs.push_back(p.position.x());
  }
  ASSERT_EQ(counts.size(), 3u);
  double chi2 = 0.0;
  for (const auto& [board, n] : counts) {
    const double expected = 1000.0;
    chi2 += (n - expected) * (n - expected) / expected;
  }
  EXPECT_LT(chi2, 13.8);
  const double r = s.generator->config().findObject("cube")->horizontalRadius;
  test::expectUniform(xs, 0.2 + r, 0.8 - r);
}

TEST(SurfaceRegion, NothingLandsInAHole) {
  const Scenes s = scenes(
      "samplers:\n  - {name: S, objects: [cube], region: {shape: surface, of: frame1}, "
      "ensure_object_boundary_in_range: false}\n",
      2000);
  std::size_t nearHole = 0;
  for (const SceneResult& scene : s.results) {
    ASSERT_TRUE(scene.success);
    const Eigen::Vector3d& p = scene.placements[0].position;
    // The hole: x in [-1.1, -0.9], y in [-0.1, 0.1].
    EXPECT_FALSE(std::abs(p.x() + 1.0) < 0.1 && std::abs(p.y()) < 0.1) << p.transpose();
    nearHole += std::abs(p.x() + 1.0) < 0.15 && std::abs(p.y()) < 0.15 ? 1 : 0;
    EXPECT_NEAR(p.z(), 0.52 + 0.02, 1e-12);
  }
  EXPECT_GT(nearHole, 0u);  // the ring around the hole is reached
}

TEST(SurfaceRegion, ATallObjectStandsOnlyWhereTheClearanceTakesIt) {
  const Scenes s = scenes(
      "samplers:\n  - {name: S, objects: [bottle, can], region: {shape: surface, of: shelf1}}\n",
      300);
  std::size_t canLow = 0;
  for (const SceneResult& scene : s.results) {
    ASSERT_TRUE(scene.success) << scene.message;
    EXPECT_NEAR(scene.placements[0].position.z(), 0.70 + 0.2, 1e-12);  // the bottle: top board
    canLow += scene.placements[1].position.z() < 0.5 ? 1 : 0;
  }
  EXPECT_GT(canLow, 0u);  // the can fits under the boards
}

TEST(SurfaceRegion, TheInsetKeepsADiskOffTheWallsOfABin) {
  const std::string yaml = R"(
samplers:
  - {name: S, objects: [can, cube], region: {shape: surface, of: bin1, select: [0]}}
)";
  const std::string bin = R"(
  bin:
    shapes:
      - {shape: box, size: [0.40, 0.50, 0.01], position: [0, 0, 0.005]}
      - {shape: box, size: [0.01, 0.50, 0.10], position: [0.195, 0, 0.05]}
      - {shape: box, size: [0.01, 0.50, 0.10], position: [-0.195, 0, 0.05]}
      - {shape: box, size: [0.38, 0.01, 0.10], position: [0, 0.245, 0.05]}
      - {shape: box, size: [0.38, 0.01, 0.10], position: [0, -0.245, 0.05]}
)";
  std::string text = kScene;
  text.insert(text.find("  ball:"), bin.substr(1));
  text += "  - {name: bin1, object: bin, position: [2.0, 0.0, 0.8]}\n" + yaml;
  const SceneGenerator generator(buildFromYaml(text));
  const PreparedRequest request = generator.prepare(SampleRequest());
  for (const SceneResult& scene : generator.sampleScenes(request, 9, 500, 1)) {
    ASSERT_TRUE(scene.success) << scene.message;
    for (const ObjectPlacement& p : scene.placements) {
      const double r = p.object->horizontalRadius;
      EXPECT_LE(std::abs(p.position.x() - 2.0), 0.19 - r + 1e-12);
      EXPECT_LE(std::abs(p.position.y()), 0.24 - r + 1e-12);
      EXPECT_NEAR(p.position.z() + p.object->bottomOffset.z(), 0.81, 1e-12);
    }
  }
}

TEST(SurfaceRegion, ObjectsStandOnTheTopOfAnObjectAnEarlierSamplerPlaced) {
  const Scenes s = scenes(
      "samplers:\n"
      "  - {name: Trays, objects: [tray], region: {shape: surface, of: table1}}\n"
      "  - {name: OnTray, objects: [cube], region: {shape: surface, of: tray}}\n",
      400);
  for (const SceneResult& scene : s.results) {
    ASSERT_TRUE(scene.success) << scene.message;
    const ObjectPlacement& tray = scene.placements[0];
    const ObjectPlacement& cube = scene.placements[1];
    EXPECT_NEAR(tray.position.z(), 0.8 + 0.01, 1e-12);
    EXPECT_NEAR(cube.position.z(), 0.82 + 0.02, 1e-12);
    // In the tray's own frame the cube's disk is on the tray's top.
    const Eigen::Vector3d local = tray.orientation.inverse() * (cube.position - tray.position);
    const double r = cube.object->horizontalRadius;
    EXPECT_LE(std::abs(local.x()), 0.15 - r + 1e-9);
    EXPECT_LE(std::abs(local.y()), 0.10 - r + 1e-9);
  }
}

TEST(SurfaceRegion, RequestFixturesAreFoundPerCall) {
  SampleRequest request;
  RequestFixture f;
  f.name = "cart";
  f.shape = Shape::box(Eigen::Vector3d(0.5, 0.4, 0.1));
  f.position = Eigen::Vector3d(3.0, 3.0, 0.05);
  request.fixtures.push_back(f);
  const std::string yaml =
      "samplers:\n  - {name: S, objects: [cube], region: {shape: surface, of: cart}}\n";
  const Scenes s = scenes(yaml, 200, 1, request);
  // strategy free_space too, with 24 cubes and few attempts, so that its cells are built on
  // the request's fixture.
  std::string objects;
  std::string cubes = "cube";
  for (int i = 0; i < 23; ++i) {
    objects += "  k" + std::to_string(i) + ": {shape: box, size: [0.04, 0.04, 0.04]}\n";
    cubes += ", k" + std::to_string(i);
  }
  std::string crowded = kScene;
  crowded.insert(crowded.find("fixtures:"), objects);
  crowded += "samplers:\n  - {name: S, objects: [" + cubes +
             "], strategy: free_space, max_attempts: 40, region: {shape: surface, of: cart}}\n";
  const SceneGenerator freeSpace(buildFromYaml(crowded));
  const std::vector<SceneResult> crowdedScenes =
      freeSpace.sampleScenes(freeSpace.prepare(request), 5, 200, 1);
  std::size_t placed = 0;
  std::size_t fromCells = 0;
  for (const SceneResult& scene : crowdedScenes) {
    placed += scene.success ? 1 : 0;
    for (const ObjectPlacement& placement : scene.placements) {
      fromCells += placement.attempts > 5 ? 1 : 0;  // 5 = 40 / 8 are rejection's
    }
  }
  EXPECT_GT(placed, 180u);
  EXPECT_GT(fromCells, 200u);
  for (const std::vector<SceneResult>* results : {&s.results, &crowdedScenes}) {
    for (const SceneResult& scene : *results) {
      ASSERT_TRUE(scene.success || results == &crowdedScenes) << scene.message;
      for (const ObjectPlacement& placement : scene.placements) {
        const Eigen::Vector3d& p = placement.position;
        EXPECT_NEAR(p.z(), 0.1 + 0.02, 1e-12);
        EXPECT_LE(std::abs(p.x() - 3.0), 0.25 - 0.028);
        EXPECT_LE(std::abs(p.y() - 3.0), 0.2 - 0.028);
      }
    }
  }
  // The configuration warns that the name must come with each request; a request without it
  // is refused.
  const auto config = buildFromYaml(kScene + yaml);
  const std::string warning =
      "sampler 'S': region.of 'cart' is neither a configured fixture nor an object: every "
      "request must give a fixture of that name";
  EXPECT_NE(std::find(config->warnings.begin(), config->warnings.end(), warning),
            config->warnings.end());
  EXPECT_EQ(requestError(yaml, SampleRequest()),
            "sampler 'S': region.of 'cart' is neither a configured fixture, a fixture of this "
            "request nor an object an earlier sampler places");
  // A request fixture with no surface: said at once.
  request.fixtures[0].shape = Shape::sphere(0.2);
  EXPECT_EQ(requestError(yaml, request),
            "sampler 'S': region.of 'cart' has no support surface of at least 0.0025 m^2 "
            "(min_area) facing up within 0.1 rad (normal_tolerance); it has no up-facing face at "
            "all");
}

TEST(SurfaceRegion, TheSameScenesOnOneAndTwoThreads) {
  const std::string yaml =
      "samplers:\n"
      "  - {name: Trays, objects: [tray], region: {shape: surface, of: table1}}\n"
      "  - {name: OnTray, objects: [cube], region: {shape: surface, of: tray}}\n"
      "  - {name: Shelf, objects: [can, bottle], region: {shape: surface, of: shelf1}}\n";
  const Scenes one = scenes(yaml, 200, 1);
  const Scenes two = scenes(yaml, 200, 2);
  for (std::size_t i = 0; i < one.results.size(); ++i) {
    test::expectSamePlacements(one.results[i].placements, two.results[i].placements);
  }
}

TEST(SurfaceRegion, TheRadiusTestSkipsTheSupportAndTheFclTestChecksIt) {
  // Under the radius test the table's circle would cover its whole top.
  const std::string yaml =
      "samplers:\n  - {name: S, objects: [cube, can], region: {shape: surface, of: table1}}\n";
  for (const CollisionMode mode :
       {CollisionMode::Radius, CollisionMode::Fcl, CollisionMode::RadiusAndFcl}) {
    SampleRequest request;
    request.collisionCheck = mode;
    const Scenes s = scenes(yaml, 100, 1, request);
    for (const SceneResult& scene : s.results) {
      EXPECT_TRUE(scene.success) << scene.message;
      EXPECT_EQ(scene.placements.size(), 2u);
    }
  }
}

TEST(SurfaceRegion, ConfigurationErrorsSayWhatIsWrong) {
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [cube], region: {shape: surface}}\n"),
            "samplers[0].region: missing required key 'of'");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [cube], region: {shape: surface, of: "
                       "cube}}\n"),
            "samplers[0].region.of: region.of 'cube' is an object of sampler 'S' itself: name a "
            "fixture or an object an earlier sampler places");
  EXPECT_EQ(
      buildError("samplers:\n  - {name: S, objects: [cube], region: {shape: surface, of: "
                 "tray}}\n  - {name: T, objects: [tray], x_range: [0, 1], y_range: [0, 1]}\n"),
      "samplers[0].region.of: region.of 'tray' of sampler 'S' is an object that no earlier "
      "sampler places: it is not in the scene yet");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [cube], region: {shape: surface, of: "
                       "ball1}}\n"),
            "samplers[0].region: region.of 'ball1' has no support surface of at least 0.0025 m^2 "
            "(min_area) facing up within 0.1 rad (normal_tolerance); it has no up-facing face at "
            "all");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [cube], region: {shape: surface, of: "
                       "table1, min_area: 1}}\n"),
            "samplers[0].region: region.of 'table1' has no support surface of at least 1 m^2 "
            "(min_area) facing up within 0.1 rad (normal_tolerance); the largest one found has "
            "0.48 m^2");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [bottle], region: {shape: surface, of: "
                       "shelf1, select: [0, 1]}}\n"),
            "samplers[0].region: sampler 'S': object 'bottle' (height 0.4 m) fits on no selected "
            "surface of 'shelf1' (select: [0, 1]): the largest clearance is 0.32 m");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [cube], region: {shape: surface, of: "
                       "shelf1, select: [5]}}\n"),
            "samplers[0].region: region.select: index 5 is past the last support surface of "
            "'shelf1', which has 5 surfaces (indices 0 to 4, as --describe lists them)");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [cube], region: {shape: surface, of: "
                       "shelf1, select: [1, 0, 1]}}\n"),
            "samplers[0].region: region.select: index 1 is listed twice");
  // Surfaces 3 and 4 are the side panels' tops, 0.02 m wide.
  EXPECT_EQ(
      buildError("samplers:\n  - {name: S, objects: [cube], region: {shape: surface, of: "
                 "shelf1, select: top}}\n"),
      "samplers[0].region: sampler 'S': object 'cube' finds no room on the selected "
      "surfaces of 'shelf1' (select: top) that it fits under: none has a point 0.0282843 m "
      "from its edges (its horizontal radius 0.0282843 m with ensure_object_boundary_in_range "
      "on, plus margin 0 m)");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [cube], region: {shape: surface, of: "
                       "shelf1, select: middle}}\n"),
            "samplers[0].region.select: expected all, top or a list of surface indices (as "
            "--describe lists them)");
  EXPECT_EQ(
      buildError("samplers:\n  - {name: S, objects: [cube], region: {shape: surface, of: "
                 "shelf1, margin: 0.2}}\n"),
      "samplers[0].region: sampler 'S': object 'cube' finds no room on the selected "
      "surfaces of 'shelf1' (select: all) that it fits under: none has a point 0.228284 m "
      "from its edges (its horizontal radius 0.0282843 m with ensure_object_boundary_in_range "
      "on, plus margin 0.2 m)");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [cube], region: {shape: surface, of: "
                       "shelf1, normal_tolerance: 2}}\n"),
            "samplers[0].region.normal_tolerance: expected an angle in [0, pi/2) [rad]");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [cube], strategy: dense, region: "
                       "{shape: surface, of: shelf1}}\n"),
            "samplers[0].region: sampler 'S': region (surface) takes strategy rejection or "
            "free_space");
}

TEST(SurfaceRegion, SelectTopTakesTheHighestSurfaces) {
  const Scenes s = scenes(
      "samplers:\n  - {name: S, objects: [cube], region: {shape: surface, of: shelf1, "
      "select: top, min_area: 0.01}}\n",
      100);
  for (const SceneResult& scene : s.results) {
    EXPECT_NEAR(scene.placements[0].position.z(), 0.72, 1e-12);
  }
}

TEST(SurfaceRegion, TheValidatorKnowsSurfaceRegions) {
  const Scenes s = scenes(kOnShelf, 5);
  for (const SceneResult& scene : s.results) {
    std::vector<GivenPose> poses;
    for (const ObjectPlacement& p : scene.placements) {
      poses.push_back(GivenPose{std::string(p.name), p.position, p.orientation});
    }
    const SceneVerdict good = validateScene(*s.generator, s.request, poses);
    EXPECT_TRUE(good.valid);
    for (const ObjectVerdict& o : good.objects) {
      for (const Violation& v : o.reasons) {
        ADD_FAILURE() << o.name << ": " << v.message;
      }
    }
    // Off the shelf's side, and a little high.
    poses[0].position.x() = 0.5 + 0.45;
    poses[0].position.z() += 0.01;
    const SceneVerdict verdict = validateScene(*s.generator, s.request, poses);
    ASSERT_FALSE(verdict.valid);
    const std::vector<Violation>& reasons = verdict.objects[0].reasons;
    ASSERT_EQ(reasons.size(), 2u);
    EXPECT_EQ(reasons[0].kind, Violation::Kind::OutsideRegion);
    EXPECT_NEAR(reasons[0].distance, 0.15 + 0.028284271247461901, 1e-9);
    EXPECT_EQ(reasons[1].kind, Violation::Kind::Height);
    EXPECT_NEAR(reasons[1].distance, 0.01, 1e-9);
  }
}

TEST(SurfaceRegion, DescribeAndRvizShowTheSurfaces) {
  const Scenes s = scenes(kOnShelf, 1);
  const std::string json = configToJson(s.generator->config());
  EXPECT_NE(json.find("\"region\": {\"shape\": \"surface\", \"of\": \"shelf1\", \"select\": "
                      "\"all\", \"min_area\": 0.01, \"normal_tolerance\": 0.1, \"margin\": 0, "
                      "\"surfaces_frame\": \"world\", \"surfaces\": [{\"index\": 0, \"selected\": "
                      "true, \"z\": 0.02, "
                      "\"area\": 0.18"),
            std::string::npos)
      << json;
  const std::size_t top =
      json.find("{\"index\": 2, \"selected\": true, \"z\": 0.7, \"area\": 0.18");
  ASSERT_NE(top, std::string::npos);
  EXPECT_EQ(json.find("\"clearance\": ", top), json.find("\"clearance\": null", top));
  std::size_t surfaces = 0;
  for (const SamplerRegion& r : samplerRegions(s.request, s.results[0])) {
    if (r.surface) {
      EXPECT_EQ(r.label.rfind("shelf1: surface " + std::to_string(surfaces) + ", clearance ", 0),
                0u);
      ++surfaces;
    }
  }
  EXPECT_EQ(surfaces, 3u);
}

}  // namespace
}  // namespace placement_samplers
