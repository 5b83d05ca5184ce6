// Strategy free_space: the same distribution as rejection (two-sample KS on statistics of the
// scenes, fixed seeds), with relations too, every rule still kept, and a failure only when
// nothing is free.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "placement_samplers/sampling/region.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "placement_samplers/validation/scene_validator.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

std::string clutter(int n, const std::string& strategy, const std::string& shape) {
  std::string yaml = "objects:\n";
  std::string names;
  for (int i = 0; i < n; ++i) {
    yaml += "  c" + std::to_string(i) + ": {shape: cylinder, radius: 0.03, length: 0.1}\n";
    names += (i ? ", c" : "c") + std::to_string(i);
  }
  return yaml + "samplers:\n  - {name: S, strategy: " + strategy + ", objects: [" + names + "], " +
         shape + "}\n";
}

std::vector<SceneResult> run(const std::string& yaml, std::uint64_t seed, std::size_t count,
                             CollisionMode mode = CollisionMode::Radius) {
  const SceneGenerator generator(test::buildFromYaml(yaml));
  SampleRequest request;
  request.collisionCheck = mode;
  return generator.sampleScenes(generator.prepare(request), seed, count, 2);
}

/// Two-sample Kolmogorov-Smirnov distance.
double ksDistance(std::vector<double> a, std::vector<double> b) {
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  std::size_t i = 0;
  std::size_t j = 0;
  double d = 0.0;
  while (i < a.size() && j < b.size()) {
    const double x = std::min(a[i], b[j]);
    while (i < a.size() && a[i] <= x) {
      ++i;
    }
    while (j < b.size() && b[j] <= x) {
      ++j;
    }
    d = std::max(d,
                 std::abs(static_cast<double>(i) / a.size() - static_cast<double>(j) / b.size()));
  }
  return d;
}

/// The two-sample KS distance that equal distributions exceed with probability 1e-4.
double ksCritical(std::size_t n, std::size_t m) {
  return std::sqrt(-0.5 * std::log(1e-4 / 2.0)) * std::sqrt(static_cast<double>(n + m) / (n * m));
}

using Statistic = std::function<double(const SceneResult&)>;

/// Scenes of both strategies (different seeds: they draw differently) compared on each
/// statistic; only successful scenes count, as rejection's successes are what it returns.
void expectSameDistribution(const std::string& rejection, const std::string& freeSpace,
                            const std::vector<std::pair<std::string, Statistic>>& statistics,
                            std::size_t scenes) {
  const std::vector<SceneResult> a = run(rejection, 11, scenes);
  const std::vector<SceneResult> b = run(freeSpace, 12, scenes);
  for (const auto& [label, statistic] : statistics) {
    std::vector<double> x;
    std::vector<double> y;
    for (const SceneResult& s : a) {
      if (s.success) {
        x.push_back(statistic(s));
      }
    }
    for (const SceneResult& s : b) {
      if (s.success) {
        y.push_back(statistic(s));
      }
    }
    ASSERT_GT(x.size(), scenes / 2) << label;
    ASSERT_GT(y.size(), scenes / 2) << label;
    EXPECT_LT(ksDistance(x, y), ksCritical(x.size(), y.size())) << label;
  }
}

/// The distance from placement @p k to the nearest placement before it [m].
double nearestEarlier(const SceneResult& s, std::size_t k) {
  double best = INFINITY;
  for (std::size_t i = 0; i < k; ++i) {
    best = std::min(best, (s.placements[i].position - s.placements[k].position).head<2>().norm());
  }
  return best;
}

TEST(FreeSpace, SameDistributionAsRejectionInAClutteredSquare) {
  const std::string range = "x_range: [-0.2, 0.2], y_range: [-0.2, 0.2]";
  std::vector<std::pair<std::string, Statistic>> statistics;
  for (const std::size_t k : {0u, 9u, 24u}) {
    statistics.push_back({"x of object " + std::to_string(k),
                          [k](const SceneResult& s) { return s.placements[k].position.x(); }});
    statistics.push_back(
        {"distance from the centre of object " + std::to_string(k),
         [k](const SceneResult& s) { return s.placements[k].position.head<2>().norm(); }});
  }
  for (const std::size_t k : {9u, 24u}) {
    statistics.push_back({"nearest earlier object of object " + std::to_string(k),
                          [k](const SceneResult& s) { return nearestEarlier(s, k); }});
  }
  expectSameDistribution(clutter(25, "rejection", range), clutter(25, "free_space", range),
                         statistics, 3000);
}

/// free_space tries rejection first and builds the cells only when those attempts failed (an
/// eighth of max_attempts, at most 512): with 64 attempts, 8 are rejection's, and many crowded
/// objects are placed from the cells, so the scenes are a mixture of both ways. Each is uniform
/// over the free positions, so the mixture is too: the same distribution as rejection.
TEST(FreeSpace, RejectionFirstThenCellsIsStillRejectionsDistribution) {
  const std::string range = "x_range: [-0.2, 0.2], y_range: [-0.2, 0.2]";
  std::vector<std::pair<std::string, Statistic>> statistics;
  for (const std::size_t k : {9u, 24u}) {
    statistics.push_back({"x of object " + std::to_string(k),
                          [k](const SceneResult& s) { return s.placements[k].position.x(); }});
    statistics.push_back({"nearest earlier object of object " + std::to_string(k),
                          [k](const SceneResult& s) { return nearestEarlier(s, k); }});
  }
  const std::string freeSpace = clutter(25, "free_space", range + ", max_attempts: 64");
  expectSameDistribution(clutter(25, "rejection", range + ", max_attempts: 100000"), freeSpace,
                         statistics, 3000);
  // The cells really placed a good share of the objects (an attempt after the 8th is theirs).
  std::size_t fromCells = 0;
  std::size_t placed = 0;
  for (const SceneResult& s : run(freeSpace, 12, 3000)) {
    for (const ObjectPlacement& p : s.placements) {
      fromCells += p.attempts > 8 ? 1 : 0;
      ++placed;
    }
  }
  EXPECT_GT(fromCells, placed / 50) << fromCells << " of " << placed;
}

TEST(FreeSpace, SameDistributionAsRejectionInAnAnnulusWithKeepOut) {
  const std::string shape =
      "region: {shape: annulus, inner_radius: 0.1, outer_radius: 0.3}, keep_out: [{shape: "
      "polygon, vertices: [[0, 0], [0.3, 0], [0.3, 0.2]]}]";
  std::vector<std::pair<std::string, Statistic>> statistics;
  for (const std::size_t k : {0u, 14u}) {
    statistics.push_back({"angle of object " + std::to_string(k), [k](const SceneResult& s) {
                            return std::atan2(s.placements[k].position.y(),
                                              s.placements[k].position.x());
                          }});
    statistics.push_back({"radius of object " + std::to_string(k), [k](const SceneResult& s) {
                            return s.placements[k].position.head<2>().norm();
                          }});
  }
  statistics.push_back({"nearest earlier object of object 14",
                        [](const SceneResult& s) { return nearestEarlier(s, 14); }});
  expectSameDistribution(clutter(15, "rejection", shape), clutter(15, "free_space", shape),
                         statistics, 3000);
}

/// Where rejection runs out of attempts (60 cylinders on a 0.6 m square, 200 attempts each),
/// free_space still places them, keeping every rule: inside the inset square, no overlap.
TEST(FreeSpace, FillsWhereRejectionRunsOut) {
  const std::string range = "x_range: [-0.3, 0.3], y_range: [-0.3, 0.3], max_attempts: 200";
  std::size_t rejected = 0;
  for (const SceneResult& s : run(clutter(60, "rejection", range), 5, 100)) {
    rejected += s.success ? 0 : 1;
  }
  std::size_t placed = 0;
  for (const SceneResult& s : run(clutter(60, "free_space", range), 5, 100)) {
    placed += s.success ? 1 : 0;
    for (std::size_t i = 0; i < s.placements.size(); ++i) {
      EXPECT_LE(s.placements[i].position.head<2>().lpNorm<Eigen::Infinity>(), 0.27 + 1e-12);
      for (std::size_t j = 0; j < i; ++j) {
        EXPECT_GT((s.placements[i].position - s.placements[j].position).head<2>().norm(), 0.06);
      }
    }
  }
  EXPECT_GT(rejected, 50u);
  EXPECT_GE(placed, 95u);
}

/// Nothing is free: the rejection attempts (512 of the default 5000) fail, and the cells built
/// then are empty, which ends the attempts.
TEST(FreeSpace, FailsAtOnceWhenNothingIsFree) {
  const std::vector<SceneResult> out =
      run("objects:\n  a: {shape: cylinder, radius: 0.1, length: 0.1}\n  b: {shape: cylinder, "
          "radius: 0.1, length: 0.1}\nsamplers:\n  - {name: S, strategy: free_space, objects: [a, "
          "b], x_range: [-0.05, 0.05], y_range: [-0.05, 0.05], ensure_object_boundary_in_range: "
          "false}\n",
          1, 1);
  ASSERT_FALSE(out[0].success);
  EXPECT_EQ(out[0].message,
            "could not place object 'b' with sampler 'S': no free position is left (strategy "
            "free_space, 512 attempts)");
}

/// Under fcl the radius test does not prune (fcl may accept what it refuses): the scenes still
/// keep the region and the keep-out zones, and pass the check.
TEST(FreeSpace, FclModesKeepZones) {
  const std::string shape =
      "region: {shape: disk, radius: 0.3}, keep_out: [{shape: disk, centre: [0.1, 0], radius: "
      "0.1}]";
  for (const CollisionMode mode : {CollisionMode::Fcl, CollisionMode::RadiusAndFcl}) {
    for (const SceneResult& s : run(clutter(20, "free_space", shape), 3, 50, mode)) {
      ASSERT_TRUE(s.success) << s.message;
      for (const ObjectPlacement& p : s.placements) {
        EXPECT_LE(p.position.head<2>().norm(), 0.27 + 1e-12);
        EXPECT_GE((p.position.head<2>() - Eigen::Vector2d(0.1, 0)).norm(), 0.13 - 1e-12);
      }
    }
  }
}

/// A mug next to a post (gap at most 2 cm) among 24 more posts on a 12 cm grid, all fixtures:
/// the free positions where the relation holds are bits of the four gaps around the post.
/// Relations are tests of each attempt under free_space too, so its mug is where rejection's
/// is: uniform over that set. With 64 attempts, 8 are rejection's and most mugs come from the
/// cells.
std::string postsAndMug(const std::string& strategy, int attempts) {
  std::string yaml =
      "objects:\n  mug: {shape: cylinder, radius: 0.03, length: 0.1}\n"
      "  rod: {shape: cylinder, radius: 0.03, length: 0.1}\nfixtures:\n";
  for (int i = -2; i <= 2; ++i) {
    for (int j = -2; j <= 2; ++j) {
      yaml += "  - {name: p" + std::to_string(5 * (i + 2) + j + 2) + ", object: rod, position: [" +
              std::to_string(0.12 * i) + ", " + std::to_string(0.12 * j) + ", 0.05]}\n";
    }
  }
  return yaml + "samplers:\n  - {name: S, strategy: " + strategy +
         ", objects: [mug], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3], max_attempts: " +
         std::to_string(attempts) + ", relations: [{next_to: p12, distance: [0.0, 0.02]}]}\n";
}

TEST(FreeSpace, RelationsKeepRejectionsDistribution) {
  std::vector<std::pair<std::string, Statistic>> statistics;
  const auto mug = [](const SceneResult& s) { return s.placements.back().position; };
  statistics.push_back({"x of the mug", [&](const SceneResult& s) { return mug(s).x(); }});
  statistics.push_back({"y of the mug", [&](const SceneResult& s) { return mug(s).y(); }});
  statistics.push_back(
      {"distance from the post", [&](const SceneResult& s) { return mug(s).head<2>().norm(); }});
  statistics.push_back({"direction from the post",
                        [&](const SceneResult& s) { return std::atan2(mug(s).y(), mug(s).x()); }});
  const std::string freeSpace = postsAndMug("free_space", 64);
  expectSameDistribution(postsAndMug("rejection", 100000), freeSpace, statistics, 3000);
  std::size_t fromCells = 0;
  std::size_t placed = 0;
  for (const SceneResult& s : run(freeSpace, 12, 3000)) {
    if (s.success) {
      const Eigen::Vector3d p = mug(s);
      EXPECT_LE(p.head<2>().norm(), 0.08 + 1e-9);
      fromCells += s.placements.back().attempts > 8 ? 1 : 0;
      ++placed;
    }
  }
  // 56 draws from the cells find the set three times in four; a mug not placed changes no
  // other (the posts are fixtures), so the placed ones are still the set's uniform draws.
  EXPECT_GT(placed, 2000u);
  EXPECT_GT(fromCells, placed / 2) << fromCells << " of " << placed;
}

/// Under free_space a relation's failure reads as under rejection: which relation refused how
/// many attempts, or at once when it cannot hold in the region.
TEST(FreeSpace, RelationFailuresNameTheRelation) {
  const std::string objects =
      "objects:\n  a: {shape: cylinder, radius: 0.03, length: 0.1}\n  b: {shape: cylinder, "
      "radius: 0.03, length: 0.1}\nfixtures:\n  - {name: far, object: a, position: [5, 0, 0]}\n";
  const std::vector<SceneResult> impossible =
      run(objects +
              "samplers:\n  - {name: S, strategy: free_space, objects: [b], x_range: [-0.2, 0.2], "
              "y_range: [-0.2, 0.2], relations: [{next_to: far, distance: [0, 0.1]}]}\n",
          1, 1);
  ASSERT_FALSE(impossible[0].success);
  EXPECT_EQ(impossible[0].message.rfind("could not place object 'b' with sampler 'S': "
                                        "relations[0] (next_to 'far', gap [0, 0.1] m) cannot "
                                        "hold anywhere",
                                        0),
            0u)
      << impossible[0].message;
  EXPECT_EQ(test::configError([&] {
              test::buildFromYaml(objects +
                                  "samplers:\n  - {name: S, strategy: dense, objects: [b], "
                                  "relations: [{away_from: far, distance: 0.1}]}\n");
            }),
            "samplers[0].relations: sampler 'S': relations take strategy rejection or "
            "free_space, not dense");
}

/// Surfaces: a shelf of three 0.6 x 0.3 boards (0.32 m apart), a 0.6 x 0.6 frame around a
/// 0.2 x 0.2 hole (drawn whole, its inset by rejection) and a 0.8 x 0.6 table.
const std::string kSurfaceObjects = R"(
  shelf:
    shapes:
      - {shape: box, size: [0.6, 0.3, 0.02], position: [0, 0, 0.01]}
      - {shape: box, size: [0.6, 0.3, 0.02], position: [0, 0, 0.35]}
      - {shape: box, size: [0.6, 0.3, 0.02], position: [0, 0, 0.69]}
  frame:
    shapes:
      - {shape: box, size: [0.6, 0.2, 0.04], position: [0, 0.2, 0]}
      - {shape: box, size: [0.6, 0.2, 0.04], position: [0, -0.2, 0]}
      - {shape: box, size: [0.2, 0.2, 0.04], position: [0.2, 0, 0]}
      - {shape: box, size: [0.2, 0.2, 0.04], position: [-0.2, 0, 0]}
  table: {shape: box, size: [0.8, 0.6, 0.05]}
fixtures:
  - {name: shelf1, object: shelf, position: [0.5, 0.0, 0.0]}
  - {name: frame1, object: frame, position: [-1.0, 0.0, 0.5]}
  - {name: table1, object: table, position: [0.0, -2.0, 0.775]}
)";

/// @p n cans on the surfaces of @p of.
std::string cansOn(int n, const std::string& of, const std::string& strategy, int attempts,
                   const std::string& extra = "") {
  std::string yaml = "objects:\n";
  std::string names;
  for (int i = 0; i < n; ++i) {
    yaml += "  c" + std::to_string(i) + ": {shape: cylinder, radius: 0.03, length: 0.12}\n";
    names += (i ? ", c" : "c") + std::to_string(i);
  }
  return yaml + kSurfaceObjects.substr(1) + "samplers:\n  - {name: S, strategy: " + strategy +
         ", objects: [" + names + "], region: {shape: surface, of: " + of +
         "}, max_attempts: " + std::to_string(attempts) + extra + "}\n";
}

/// Scenes @p seed of @p yaml, every placed one checked by the validator (on a surface it is
/// on, at its height, no overlap) while its generator lives (the names are views into it).
void expectValid(const std::string& yaml, std::uint64_t seed, std::size_t count) {
  const SceneGenerator generator(test::buildFromYaml(yaml));
  const PreparedRequest request = generator.prepare(SampleRequest());
  for (const SceneResult& r : generator.sampleScenes(request, seed, count, 2)) {
    if (!r.success) {
      continue;
    }
    std::vector<GivenPose> poses;
    for (const ObjectPlacement& p : r.placements) {
      poses.push_back({std::string(p.name), p.position, p.orientation});
    }
    const SceneVerdict v = validateScene(generator, request, poses);
    std::string why;
    for (const ObjectVerdict& o : v.objects) {
      why += o.reasons.empty() ? "" : o.reasons[0].message + "; ";
    }
    ASSERT_TRUE(v.valid) << "scene " << r.index << ": " << why;
  }
}

/// On three boards (24 cans): free_space's scenes are rejection's, boards chosen by free area
/// included; most objects after the first few come from the cells with 64 attempts.
TEST(FreeSpace, OnSurfacesSameDistributionAsRejection) {
  std::vector<std::pair<std::string, Statistic>> statistics;
  for (const std::size_t k : {0u, 12u, 23u}) {
    statistics.push_back({"z of object " + std::to_string(k),
                          [k](const SceneResult& s) { return s.placements[k].position.z(); }});
    statistics.push_back({"x of object " + std::to_string(k),
                          [k](const SceneResult& s) { return s.placements[k].position.x(); }});
  }
  statistics.push_back(
      {"y of object 23", [](const SceneResult& s) { return s.placements[23].position.y(); }});
  const std::string freeSpace = cansOn(24, "shelf1", "free_space", 64);
  expectSameDistribution(cansOn(24, "shelf1", "rejection", 100000), freeSpace, statistics, 3000);
  const std::vector<SceneResult> out = run(freeSpace, 12, 3000);
  std::size_t fromCells = 0;
  std::size_t placed = 0;
  for (const SceneResult& s : out) {
    for (const ObjectPlacement& p : s.placements) {
      fromCells += p.attempts > 8 ? 1 : 0;
      ++placed;
    }
  }
  EXPECT_GT(fromCells, placed / 50) << fromCells << " of " << placed;
  expectValid(freeSpace, 12, 500);
}

/// A surface with a hole, drawn whole, its inset by rejection; a keep-out zone.
TEST(FreeSpace, OnASurfaceWithAHoleSameDistributionAsRejection) {
  const std::string zone =
      ", keep_out: [{shape: disk, center: [-1.2, 0.2], radius: 0.08, frame: world}]";
  std::vector<std::pair<std::string, Statistic>> statistics;
  for (const std::size_t k : {0u, 14u}) {
    statistics.push_back({"x of object " + std::to_string(k),
                          [k](const SceneResult& s) { return s.placements[k].position.x(); }});
    statistics.push_back({"y of object " + std::to_string(k),
                          [k](const SceneResult& s) { return s.placements[k].position.y(); }});
  }
  statistics.push_back({"nearest earlier object of object 14",
                        [](const SceneResult& s) { return nearestEarlier(s, 14); }});
  const std::string freeSpace = cansOn(15, "frame1", "free_space", 64, zone);
  expectSameDistribution(cansOn(15, "frame1", "rejection", 100000, zone), freeSpace, statistics,
                         3000);
  const std::vector<SceneResult> out = run(freeSpace, 12, 500);
  for (const SceneResult& s : out) {
    for (const ObjectPlacement& p : s.placements) {
      // At least its radius from the hole, [-0.1, 0.1] x [-0.1, 0.1] about the frame's centre.
      const Eigen::Vector2d local = p.position.head<2>() - Eigen::Vector2d(-1.0, 0.0);
      const Eigen::Vector2d out = (local.cwiseAbs() - Eigen::Vector2d(0.1, 0.1)).cwiseMax(0.0);
      EXPECT_GE(out.norm(), 0.03 - 1e-9) << "near the hole: " << local.transpose();
      EXPECT_GE((p.position.head<2>() - Eigen::Vector2d(-1.2, 0.2)).norm(), 0.11 - 1e-9);
    }
  }
  expectValid(freeSpace, 12, 500);
}

/// 80 cans on a 0.8 x 0.6 table top with 200 attempts each: rejection fails most scenes,
/// free_space places nearly all, every one valid.
TEST(FreeSpace, OnASurfaceFillsWhereRejectionRunsOut) {
  std::size_t rejected = 0;
  for (const SceneResult& s : run(cansOn(80, "table1", "rejection", 200), 5, 100)) {
    rejected += s.success ? 0 : 1;
  }
  const std::string freeSpace = cansOn(80, "table1", "free_space", 200);
  const std::vector<SceneResult> out = run(freeSpace, 5, 100);
  std::size_t placed = 0;
  for (const SceneResult& s : out) {
    placed += s.success ? 1 : 0;
  }
  EXPECT_GT(rejected, 50u);
  EXPECT_GE(placed, 95u);
  expectValid(freeSpace, 5, 100);
}

TEST(FreeSpace, UnknownStrategyIsAnError) {
  EXPECT_EQ(test::configError(
                [] { test::buildFromYaml("samplers:\n  - {name: S, strategy: greedy}\n"); }),
            "samplers[0].strategy: expected rejection, free_space or dense, got 'greedy'");
}

/// Pruning the cells of many keep-out zones for objects of many sizes reads the clock: with a
/// limit that has passed, the scene fails instead of pruning on. (With max_attempts 7 the cells
/// are built at once: the rejection attempts before them are an eighth of the limit.)
TEST(FreeSpace, StopsPruningWhenTimeRunsOut) {
  std::string yaml = "objects:\n";
  std::string names;
  for (int i = 0; i < 4; ++i) {
    yaml += "  o" + std::to_string(i) + ": {shape: sphere, radius: 0.00" + std::to_string(i + 1) +
            "}\n";
    names += (i ? ", o" : "o") + std::to_string(i);
  }
  yaml += "samplers:\n  - {name: S, strategy: free_space, max_attempts: 7, objects: [" + names +
          "], x_range: [-1, 1], y_range: [-1, 1], keep_out: [";
  for (int k = 0; k < 200; ++k) {
    yaml += (k ? ", " : "") + std::string("{shape: disk, centre: [") +
            std::to_string(-0.95 + 0.1 * (k % 20)) + ", " + std::to_string(-0.95 + 0.1 * (k / 20)) +
            "], radius: 0.01}";
  }
  yaml += "]}\n";
  const SceneGenerator generator(test::buildFromYaml(yaml));
  SampleRequest request;
  EXPECT_TRUE(generator.sampleScene(generator.prepare(request), 1, 0).success);
  request.maxSceneSeconds = 1e-9;
  const SceneResult scene = generator.sampleScene(generator.prepare(request), 1, 0);
  EXPECT_FALSE(scene.success);
  EXPECT_EQ(scene.message.rfind("stopped placing object 'o", 0), 0u) << scene.message;
  EXPECT_NE(scene.message.find("with sampler 'S' after "), std::string::npos) << scene.message;
  EXPECT_NE(scene.message.find(" attempts: the scene ran out of time (its limit is 1e-09 s)"),
            std::string::npos)
      << scene.message;
}

}  // namespace
}  // namespace placement_samplers
