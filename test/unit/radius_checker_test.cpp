// RadiusChecker: its grids must answer exactly as robosuite's scan of every entry in order
// (the same candidates collide, the same lowest index comes back), whatever the sizes, the
// coordinates and the scan limit.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "placement_samplers/collision/radius_checker.hpp"
#include "placement_samplers/sampling/random.hpp"
#include "placement_samplers/sampling/sample_context.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

constexpr std::size_t kAlwaysScan = std::numeric_limits<std::size_t>::max();
constexpr std::size_t kAlwaysGrid = 0;

/// robosuite's answer: the lowest index of an entry the candidate overlaps.
std::ptrdiff_t bruteForce(const std::vector<PlacedEntry>& entries, const Candidate& candidate) {
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (radiusOverlap(entries[i], candidate)) {
      return static_cast<std::ptrdiff_t>(i);
    }
  }
  return CollisionChecker::kNone;
}

/// An object with only what the radius test reads: radius and offsets [m].
std::shared_ptr<ObjectModel> makeDisc(double radius, double bottom, double top) {
  auto object = std::make_shared<ObjectModel>();
  object->name = "disc";
  object->horizontalRadius = radius;
  object->bottomOffset = Eigen::Vector3d(0.0, 0.0, bottom);
  object->topOffset = Eigen::Vector3d(0.0, 0.0, top);
  return object;
}

/// Random objects and poses over several scales: tiny, zero and negative radii, cylinders,
/// plates, a table, radii far beyond any cell (1e3, 1e200 m), and positions in the work area,
/// at negative coordinates, far away (1e3 and 1e9 m) and where hide() puts objects.
class RandomWorld {
 public:
  explicit RandomWorld(std::uint64_t seed) : engine_(seed) {
    const double radii[] = {0.0,   1e-7, 0.005, 0.02, 0.03,  0.03, 0.03,
                            0.045, 0.09, 0.2,   0.57, -0.04, 1e3,  1e200};
    for (const double r : radii) {
      objects_.push_back(makeDisc(r, -uniform(engine_, 0.0, 0.1), uniform(engine_, 0.0, 0.1)));
    }
  }

  const ObjectModel* object() {
    // Mostly work-sized objects, so that the grids fill up; the odd ones now and then.
    const double u = uniform01(engine_);
    const std::size_t n = objects_.size();
    const std::size_t i = u < 0.8 ? 2 + static_cast<std::size_t>(uniform(engine_, 0.0, 6.0))
                                  : static_cast<std::size_t>(uniform(engine_, 0.0, n - 0.5));
    return objects_[std::min(i, n - 1)].get();
  }

  Eigen::Vector3d position() {
    const double u = uniform01(engine_);
    double scale = 0.4;
    Eigen::Vector3d centre(0.1, -0.25, 0.0);
    if (u > 0.97) {
      scale = 1e9;
    } else if (u > 0.93) {
      scale = 1e3;
    } else if (u > 0.90) {
      centre = Eigen::Vector3d(-15.0, -15.0, 10.0);  // hide()
      scale = 5.0;
    }
    return centre + Eigen::Vector3d(uniform(engine_, -scale, scale),
                                    uniform(engine_, -scale, scale), uniform(engine_, -0.1, 0.1));
  }

  /// A candidate position near @p entry: inside, on or just outside its reach.
  Eigen::Vector3d near(const PlacedEntry& entry, const ObjectModel& object) {
    const double reach = std::abs(entry.object->horizontalRadius + object.horizontalRadius);
    const double angle = uniform(engine_, 0.0, 2.0 * M_PI);
    const double distance = std::isfinite(reach) && reach < 1e6 ? reach * uniform(engine_, 0.9, 1.1)
                                                                : uniform(engine_, 0.0, 1.0);
    return entry.position + Eigen::Vector3d(distance * std::cos(angle), distance * std::sin(angle),
                                            uniform(engine_, -0.1, 0.1));
  }

  Engine& engine() { return engine_; }

 private:
  Engine engine_;
  std::vector<std::shared_ptr<ObjectModel>> objects_;
};

TEST(RadiusChecker, GridsAgreeWithTheScanOnRandomScenes) {
  std::size_t collisions = 0;
  std::size_t queries = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    RandomWorld world(seed);
    RadiusChecker grid(kAlwaysGrid);
    RadiusChecker standard;
    RadiusChecker scan(kAlwaysScan);
    std::vector<PlacedEntry> entries;
    // The checkers are kept from scene to scene, as SceneGenerator's workers keep theirs.
    for (int scene = 0; scene < 3; ++scene) {
      entries.clear();
      grid.clear();
      standard.clear();
      scan.clear();
      const int count = scene == 0 ? 30 : scene == 1 ? 150 : 5;
      for (int e = 0; e < count; ++e) {
        PlacedEntry entry;
        entry.name = "entry";
        entry.object = world.object();
        entry.position = world.position();
        entries.push_back(entry);
        for (RadiusChecker* checker : {&grid, &standard, &scan}) {
          checker->added(entries, entries.size() - 1);
        }
        for (int q = 0; q < 20; ++q) {
          Candidate candidate;
          candidate.object = world.object();
          const PlacedEntry& target =
              entries[static_cast<std::size_t>(uniform(world.engine(), 0.0, entries.size() - 0.5))];
          candidate.position =
              q % 4 == 0 ? world.position() : world.near(target, *candidate.object);
          const std::ptrdiff_t expected = bruteForce(entries, candidate);
          ASSERT_EQ(grid.firstCollision(entries, candidate), expected)
              << "seed " << seed << " scene " << scene << " entries " << entries.size();
          ASSERT_EQ(standard.firstCollision(entries, candidate), expected);
          ASSERT_EQ(scan.firstCollision(entries, candidate), expected);
          collisions += expected != CollisionChecker::kNone ? 1 : 0;
          ++queries;
        }
      }
    }
  }
  // Both answers must be well represented, or the comparison proves little.
  EXPECT_GT(collisions, queries / 5);
  EXPECT_LT(collisions, queries * 4 / 5);
}

TEST(RadiusChecker, TouchingCountsInTheGridAsInTheScan) {
  // Dyadic values: the distance equals the reach exactly.
  const auto object = makeDisc(0.125, -0.05, 0.05);
  std::vector<PlacedEntry> entries;
  RadiusChecker grid(kAlwaysGrid);
  for (int i = 0; i < 20; ++i) {
    PlacedEntry entry;
    entry.object = object.get();
    entry.position = Eigen::Vector3d(-3.0 + 0.5 * i, -2.0, 0.0);
    entries.push_back(entry);
    grid.added(entries, entries.size() - 1);
  }
  // Reach 0.25 m spans several cells; reach 0.1875 m stays within the candidate's own cell.
  const auto smaller = makeDisc(0.0625, -0.05, 0.05);
  for (const ObjectModel* o : {object.get(), smaller.get()}) {
    const double reach = 0.125 + o->horizontalRadius;
    Candidate candidate;
    candidate.object = o;
    for (int i = 0; i < 20; ++i) {
      const double x = -3.0 + 0.5 * i;
      candidate.position = Eigen::Vector3d(x, -2.0 + reach, 0.0);
      EXPECT_EQ(grid.firstCollision(entries, candidate), i);
      candidate.position.y() = std::nextafter(-2.0 + reach, 0.0);
      EXPECT_EQ(grid.firstCollision(entries, candidate), CollisionChecker::kNone);
      EXPECT_EQ(bruteForce(entries, candidate), CollisionChecker::kNone);
      candidate.position = Eigen::Vector3d(x + reach, -2.0, 0.0);
      EXPECT_EQ(grid.firstCollision(entries, candidate), i);
      candidate.position = Eigen::Vector3d(x, -2.0 - reach, 0.0);
      EXPECT_EQ(grid.firstCollision(entries, candidate), i);
    }
  }
}

TEST(RadiusChecker, ReturnsTheLowestCollidingIndex) {
  // A table first, stacked plates, then cups over them: several entries overlap the candidate.
  const auto table = makeDisc(0.57, -0.025, 0.025);
  const auto plate = makeDisc(0.09, -0.01, 0.01);
  const auto cup = makeDisc(0.04, -0.045, 0.045);
  std::vector<PlacedEntry> entries;
  RadiusChecker grid(kAlwaysGrid);
  auto add = [&](const ObjectModel* object, const Eigen::Vector3d& position) {
    PlacedEntry entry;
    entry.object = object;
    entry.position = position;
    entries.push_back(entry);
    grid.added(entries, entries.size() - 1);
  };
  for (int i = 0; i < 12; ++i) {
    add(plate.get(), Eigen::Vector3d(0.01 * i, 0.0, 0.8));
  }
  add(table.get(), Eigen::Vector3d(0.0, 0.0, 0.775));
  for (int i = 0; i < 12; ++i) {
    add(cup.get(), Eigen::Vector3d(0.01 * i, 0.005, 0.85));
  }
  Candidate candidate{cup.get(), Eigen::Vector3d(0.05, 0.0, 0.85), Eigen::Quaterniond::Identity()};
  EXPECT_EQ(grid.firstCollision(entries, candidate), bruteForce(entries, candidate));
  EXPECT_EQ(grid.firstCollision(entries, candidate), 0);
  // High above the plates and the table: only the cups count.
  candidate.position.z() = 0.9;
  EXPECT_EQ(grid.firstCollision(entries, candidate), 13);
  // On top of everything: nothing (robosuite's test is one-sided in z).
  candidate.position.z() = 2.0;
  EXPECT_EQ(grid.firstCollision(entries, candidate), CollisionChecker::kNone);
}

TEST(RadiusChecker, HugeAndNonFiniteEntriesAreAlwaysConsidered) {
  const auto small = makeDisc(0.03, -0.05, 0.05);
  const auto huge = makeDisc(1e200, -0.05, 0.05);
  const auto endless = makeDisc(std::numeric_limits<double>::infinity(), -0.05, 0.05);
  std::vector<PlacedEntry> entries;
  RadiusChecker grid(kAlwaysGrid);
  auto add = [&](const ObjectModel* object, const Eigen::Vector3d& position) {
    PlacedEntry entry;
    entry.object = object;
    entry.position = position;
    entries.push_back(entry);
    grid.added(entries, entries.size() - 1);
  };
  for (int i = 0; i < 16; ++i) {
    add(small.get(), Eigen::Vector3d(0.1 * i, 0.0, 0.0));
  }
  add(huge.get(), Eigen::Vector3d(1e6, -1e6, 0.0));
  add(endless.get(), Eigen::Vector3d(0.0, 0.0, -10.0));  // far below: only low candidates hit it
  const double nan = std::numeric_limits<double>::quiet_NaN();
  add(small.get(), Eigen::Vector3d(nan, 0.0, 0.0));  // never collides, but must not break others
  Candidate candidate{small.get(), Eigen::Vector3d(50.0, 50.0, 0.0),
                      Eigen::Quaterniond::Identity()};
  EXPECT_EQ(grid.firstCollision(entries, candidate), 16);
  EXPECT_EQ(bruteForce(entries, candidate), 16);
  candidate.position = Eigen::Vector3d(0.3, 0.01, 0.0);
  EXPECT_EQ(grid.firstCollision(entries, candidate), 3);
  // A candidate as large as the world, and candidates at non-finite positions.
  const auto world = makeDisc(1e300, -0.05, 0.05);
  const Candidate big{world.get(), Eigen::Vector3d(-7.0, 3.0, -10.0),
                      Eigen::Quaterniond::Identity()};
  EXPECT_EQ(grid.firstCollision(entries, big), bruteForce(entries, big));
  for (const double bad : {nan, std::numeric_limits<double>::infinity()}) {
    const Candidate odd{small.get(), Eigen::Vector3d(bad, 0.0, -10.0),
                        Eigen::Quaterniond::Identity()};
    EXPECT_EQ(grid.firstCollision(entries, odd), bruteForce(entries, odd));
  }
}

TEST(RadiusChecker, ClearForgetsTheScene) {
  const auto object = makeDisc(0.03, -0.05, 0.05);
  std::vector<PlacedEntry> entries;
  RadiusChecker grid(kAlwaysGrid);
  for (int i = 0; i < 40; ++i) {
    PlacedEntry entry;
    entry.object = object.get();
    entry.position = Eigen::Vector3d(0.05 * (i % 8), 0.05 * (i / 8), 0.0);
    entries.push_back(entry);
    grid.added(entries, entries.size() - 1);
  }
  const Candidate candidate{object.get(), Eigen::Vector3d(0.1, 0.1, 0.0),
                            Eigen::Quaterniond::Identity()};
  EXPECT_NE(grid.firstCollision(entries, candidate), CollisionChecker::kNone);
  entries.clear();
  grid.clear();
  EXPECT_EQ(grid.firstCollision(entries, candidate), CollisionChecker::kNone);
  // A scene 4 m away, in the same wrapped buckets: the old lists must not answer for it.
  for (int i = 0; i < 12; ++i) {
    PlacedEntry far;
    far.object = object.get();
    far.position = Eigen::Vector3d(4.0 + 0.05 * (i % 4), 4.0 + 0.05 * (i / 4), 0.0);
    entries.push_back(far);
    grid.added(entries, entries.size() - 1);
  }
  EXPECT_EQ(grid.firstCollision(entries, candidate), CollisionChecker::kNone);
  const Candidate there{object.get(), Eigen::Vector3d(4.1, 4.1, 0.0),
                        Eigen::Quaterniond::Identity()};
  EXPECT_EQ(grid.firstCollision(entries, there), bruteForce(entries, there));
  EXPECT_NE(grid.firstCollision(entries, there), CollisionChecker::kNone);
}

TEST(RadiusChecker, EntriesItWasNotToldAboutAreScanned) {
  const auto object = makeDisc(0.03, -0.05, 0.05);
  std::vector<PlacedEntry> entries(3);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    entries[i].object = object.get();
    entries[i].position = Eigen::Vector3d(0.2 * static_cast<double>(i), 0.0, 0.0);
  }
  RadiusChecker checker(kAlwaysGrid);
  const Candidate candidate{object.get(), Eigen::Vector3d(0.41, 0.0, 0.0),
                            Eigen::Quaterniond::Identity()};
  EXPECT_EQ(checker.firstCollision(entries, candidate), 2);
  // Announced out of order: it indexes everything again.
  checker.added(entries, 2);
  EXPECT_EQ(checker.firstCollision(entries, candidate), 2);
}

/// The same scenes, failures included, whatever the scan limit: sampling sees no difference.
/// @return the number of failed scenes
int expectSameScenes(const std::string& yaml, int scenes) {
  const SceneGenerator generator(test::buildFromYaml(yaml));
  const PreparedRequest request = generator.prepare(SampleRequest());
  std::vector<std::vector<ObjectPlacement>> placements;
  std::vector<std::string> failures;
  for (const std::size_t limit : {kAlwaysScan, RadiusChecker::kDefaultScanLimit, kAlwaysGrid}) {
    Engine engine;
    RadiusChecker checker(limit);
    SampleContext context(engine, checker);
    for (int i = 0; i < scenes; ++i) {
      const auto k = static_cast<std::size_t>(i);
      engine = sceneEngine(7, k);
      context.clear();
      for (const FixtureSpec& f : request.fixtures) {
        context.addFixture(f.name, f.object.get(), f.position, f.orientation);
      }
      request.sampler->sample(context, request.reference, request.onTop);
      const std::string failure = context.failure() ? context.failure()->message : "";
      if (limit == kAlwaysScan) {
        placements.push_back(context.placements());
        failures.push_back(failure);
      } else {
        SCOPED_TRACE("scan limit " + std::to_string(limit) + ", scene " + std::to_string(i));
        test::expectSamePlacements(placements[k], context.placements());
        EXPECT_EQ(failures[k], failure);
      }
    }
  }
  int failed = 0;
  for (const std::string& f : failures) {
    failed += f.empty() ? 0 : 1;
  }
  return failed;
}

TEST(RadiusChecker, SamplingGivesTheSameScenesWithGridsOrScan) {
  // Clutter dense enough that some scenes fail, so the failure messages (which name the most
  // frequent blocker) are compared too.
  std::ostringstream clutter;
  clutter << "max_attempts: 300\nobjects:\n";
  for (int i = 0; i < 120; ++i) {
    clutter << "  c" << i << ": {shape: cylinder, radius: " << (i % 3 == 0 ? 0.05 : 0.03)
            << ", length: 0.1}\n";
  }
  clutter << "samplers:\n  - name: Clutter\n    objects: [";
  for (int i = 0; i < 120; ++i) {
    clutter << (i ? ", " : "") << "c" << i;
  }
  clutter << "]\n    x_range: [-0.6, 0.6]\n    y_range: [-0.6, 0.6]\n";
  const int failed = expectSameScenes(clutter.str(), 30);
  EXPECT_GT(failed, 0);
  EXPECT_LT(failed, 30);

  // A table fixture, stacked objects and hidden ones.
  EXPECT_EQ(expectSameScenes(R"(
objects:
  table_top: {shape: box, size: [0.8, 0.8, 0.05]}
  cube: {shape: box, size: [0.042, 0.042, 0.042]}
  can: {shape: cylinder, radius: 0.033, length: 0.12}
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
    sample_args: {reference: table, on_top: true}
  - name: CupSampler
    objects: [cup]
    x_range: [-0.02, 0.02]
    y_range: [-0.02, 0.02]
    ensure_object_boundary_in_range: false
    sample_args: {reference: plate, on_top: true}
  - name: TableSampler
    objects: [cube, can]
    x_range: [-0.35, 0.35]
    y_range: [-0.35, 0.35]
    sample_args: {reference: table, on_top: true}
hide: [pill]
)",
                             200),
            0);
}

}  // namespace
}  // namespace placement_samplers
