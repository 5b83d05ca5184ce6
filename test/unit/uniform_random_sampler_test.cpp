// UniformRandomSampler against robosuite's semantics: ranges, boundary shrink, rotation,
// z from the reference, the collision test, failure reports, configuration errors, seeding.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "placement_samplers/collision/radius_checker.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::configError;
using test::makeBox;
using test::makeCylinder;
using test::makeSphere;
using test::TestScene;

UniformSamplerParams region(double xMin, double xMax, double yMin, double yMax) {
  UniformSamplerParams p;
  p.xRange = Eigen::Vector2d(xMin, xMax);
  p.yRange = Eigen::Vector2d(yMin, yMax);
  return p;
}

/// Places one object @p n times (a fresh scene each time, one engine) and returns the
/// placements.
std::vector<ObjectPlacement> sampleMany(const UniformRandomSampler& sampler, int n,
                                        std::uint64_t seed,
                                        const Reference& reference = Reference::byDefault(),
                                        bool onTop = true) {
  TestScene scene(seed);
  std::vector<ObjectPlacement> out;
  out.reserve(n);
  for (int i = 0; i < n; ++i) {
    scene.context.clear();
    EXPECT_TRUE(sampler.sample(scene.context, reference, onTop));
    out.insert(out.end(), scene.context.placements().begin(), scene.context.placements().end());
  }
  return out;
}

TEST(UniformRandomSampler, PositionsWithinShrunkRangeAroundReference) {
  UniformSamplerParams p = region(-0.3, 0.2, -0.1, 0.4);
  p.referencePos = Eigen::Vector3d(1.0, -2.0, 0.5);
  p.rotation = RotationSpec::fixed(0.0);
  const double r = 0.05;
  const UniformRandomSampler sampler("S", p, {makeSphere("ball", r)});
  double minX = 1e9, maxX = -1e9;
  for (const ObjectPlacement& pl : sampleMany(sampler, 2000, 1)) {
    EXPECT_GE(pl.position.x(), 1.0 - 0.3 + r);
    EXPECT_LE(pl.position.x(), 1.0 + 0.2 - r);
    EXPECT_GE(pl.position.y(), -2.0 - 0.1 + r);
    EXPECT_LE(pl.position.y(), -2.0 + 0.4 - r);
    minX = std::min(minX, pl.position.x());
    maxX = std::max(maxX, pl.position.x());
  }
  // The whole shrunk interval is used, not a part of it (width 0.4, 2000 samples).
  EXPECT_LT(minX, 1.0 - 0.3 + r + 0.01);
  EXPECT_GT(maxX, 1.0 + 0.2 - r - 0.01);
}

TEST(UniformRandomSampler, NoShrinkUsesTheWholeRange) {
  UniformSamplerParams p = region(-0.3, 0.3, -0.3, 0.3);
  p.ensureObjectBoundaryInRange = false;
  const double r = 0.1;
  const UniformRandomSampler sampler("S", p, {makeSphere("ball", r)});
  int outsideShrunk = 0;
  for (const ObjectPlacement& pl : sampleMany(sampler, 2000, 2)) {
    EXPECT_GE(pl.position.x(), -0.3);
    EXPECT_LE(pl.position.x(), 0.3);
    EXPECT_GE(pl.position.y(), -0.3);
    EXPECT_LE(pl.position.y(), 0.3);
    outsideShrunk += std::abs(pl.position.x()) > 0.3 - r ? 1 : 0;
  }
  // A third of the x values lie in the margin the shrink would have removed.
  EXPECT_GT(outsideShrunk, 500);
}

TEST(UniformRandomSampler, EffectiveRange) {
  UniformSamplerParams p = region(-0.5, 0.5, 0.0, 1.0);
  const ObjectPtr ball = makeSphere("ball", 0.25);
  const UniformRandomSampler shrunk("S", p);
  EXPECT_EQ(shrunk.effectiveRange(*ball, 0), Eigen::Vector2d(-0.25, 0.25));
  EXPECT_EQ(shrunk.effectiveRange(*ball, 1), Eigen::Vector2d(0.25, 0.75));
  p.ensureObjectBoundaryInRange = false;
  const UniformRandomSampler plain("S", p);
  EXPECT_EQ(plain.effectiveRange(*ball, 0), Eigen::Vector2d(-0.5, 0.5));
}

TEST(UniformRandomSampler, XAndYAreUniform) {
  UniformSamplerParams p = region(-0.5, 0.5, 1.0, 3.0);
  p.ensureObjectBoundaryInRange = false;
  const UniformRandomSampler sampler("S", p, {makeSphere("ball", 0.01)});
  std::vector<double> xs, ys;
  for (const ObjectPlacement& pl : sampleMany(sampler, 20000, 3)) {
    xs.push_back(pl.position.x());
    ys.push_back(pl.position.y());
  }
  test::expectUniform(xs, -0.5, 0.5);
  test::expectUniform(ys, 1.0, 3.0);
}

TEST(UniformRandomSampler, FullRotationIsUniformOverTheCircle) {
  UniformSamplerParams p = region(-0.5, 0.5, -0.5, 0.5);
  p.rotation = RotationSpec::full();
  const UniformRandomSampler sampler("S", p, {makeSphere("ball", 0.01)});
  std::vector<double> angles;
  for (const ObjectPlacement& pl : sampleMany(sampler, 20000, 4)) {
    // A pure rotation about z (identity init orientation).
    EXPECT_NEAR(pl.orientation.x(), 0.0, 1e-15);
    EXPECT_NEAR(pl.orientation.y(), 0.0, 1e-15);
    const double a = test::angleAbout(pl.orientation, Eigen::Vector3d::UnitZ());
    EXPECT_GE(a, 0.0);
    EXPECT_LT(a, 2.0 * M_PI);
    angles.push_back(a);
  }
  test::expectUniform(angles, 0.0, 2.0 * M_PI);
}

TEST(UniformRandomSampler, RotationRangeInEitherOrder) {
  // robosuite takes min and max of the pair, so [1.0, -0.5] is U(-0.5, 1.0).
  const RotationSpec reversed = RotationSpec::range(1.0, -0.5);
  EXPECT_EQ(reversed.kind, RotationSpec::Kind::Range);
  EXPECT_EQ(reversed.low, -0.5);
  EXPECT_EQ(reversed.high, 1.0);
  for (const RotationSpec& spec : {RotationSpec::range(-0.5, 1.0), reversed}) {
    UniformSamplerParams p = region(-0.5, 0.5, -0.5, 0.5);
    p.rotation = spec;
    const UniformRandomSampler sampler("S", p, {makeSphere("ball", 0.01)});
    std::vector<double> angles;
    for (const ObjectPlacement& pl : sampleMany(sampler, 20000, 5)) {
      const double a = test::angleAbout(pl.orientation, Eigen::Vector3d::UnitZ());
      EXPECT_GE(a, -0.5 - 1e-12);
      EXPECT_LT(a, 1.0 + 1e-12);
      angles.push_back(a);
    }
    test::expectUniform(angles, -0.5, 1.0);
  }
}

TEST(UniformRandomSampler, FixedRotationIsExact) {
  UniformSamplerParams p = region(-0.5, 0.5, -0.5, 0.5);
  p.rotation = RotationSpec::fixed(0.3);
  p.rotationAxis = 1;
  const Eigen::Quaterniond init(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()));
  const ObjectPtr cube = makeBox("cube", Eigen::Vector3d(0.05, 0.05, 0.05), init);
  const UniformRandomSampler sampler("S", p, {cube});
  const Eigen::Quaterniond expected =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())) * cube->initOrientation;
  for (const ObjectPlacement& pl : sampleMany(sampler, 50, 6)) {
    EXPECT_NEAR(pl.orientation.angularDistance(expected), 0.0, 1e-12);
  }
}

TEST(UniformRandomSampler, RotationAboutEachWorldAxisAfterInitOrientation) {
  // q = AngleAxis(angle, axis) * init: the sampled rotation is a world-axis rotation applied
  // after the initial one, so q * init^-1 is a rotation about that axis.
  const Eigen::Quaterniond init(
      Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d(1, 1, 0).normalized()));
  const ObjectPtr cube = makeBox("cube", Eigen::Vector3d(0.02, 0.04, 0.06), init);
  for (int axis = 0; axis < 3; ++axis) {
    UniformSamplerParams p = region(-0.5, 0.5, -0.5, 0.5);
    p.rotation = RotationSpec::range(0.2, 1.2);
    p.rotationAxis = axis;
    const UniformRandomSampler sampler("S", p, {cube});
    for (const ObjectPlacement& pl : sampleMany(sampler, 100, 7)) {
      const Eigen::Quaterniond delta = pl.orientation * cube->initOrientation.conjugate();
      const Eigen::Vector3d unit = Eigen::Vector3d::Unit(axis);
      // No component off the axis.
      EXPECT_NEAR((delta.vec() - delta.vec().dot(unit) * unit).norm(), 0.0, 1e-12) << axis;
      const double a = test::angleAbout(delta, unit);
      EXPECT_GE(a, 0.2 - 1e-12);
      EXPECT_LT(a, 1.2 + 1e-12);
    }
  }
}

TEST(UniformRandomSampler, RotationComposesInWorldFrameNotBodyFrame) {
  // With init = 90 deg about y and a 90 deg turn about z, the two orders differ; only
  // AngleAxis(z) * init is robosuite's intent.
  UniformSamplerParams p = region(-0.5, 0.5, -0.5, 0.5);
  p.rotation = RotationSpec::fixed(M_PI / 2.0);
  const Eigen::Quaterniond init(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitY()));
  const ObjectPtr cube = makeBox("cube", Eigen::Vector3d(0.02, 0.04, 0.06), init);
  const UniformRandomSampler sampler("S", p, {cube});
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitZ()));
  const Eigen::Quaterniond world = turn * init;
  const Eigen::Quaterniond body = init * turn;
  ASSERT_GT(world.angularDistance(body), 0.5);
  const ObjectPlacement pl = sampleMany(sampler, 1, 8).front();
  EXPECT_NEAR(pl.orientation.angularDistance(world), 0.0, 1e-12);
}

TEST(UniformRandomSampler, ZOnTopSubtractsBottomOffset) {
  UniformSamplerParams p = region(-0.1, 0.1, -0.1, 0.1);
  p.referencePos = Eigen::Vector3d(0.0, 0.0, 0.8);
  p.zOffset = 0.01;
  const ObjectPtr can = makeCylinder("can", 0.03, 0.12);
  const UniformRandomSampler sampler("S", p, {can});
  const double bottom = can->bottomOffset.z();
  ASSERT_NEAR(bottom, -0.06, 1e-12);
  for (const ObjectPlacement& pl : sampleMany(sampler, 20, 9, Reference::byDefault(), true)) {
    EXPECT_DOUBLE_EQ(pl.position.z(), 0.01 + 0.8 - bottom);
  }
  for (const ObjectPlacement& pl : sampleMany(sampler, 20, 9, Reference::byDefault(), false)) {
    EXPECT_DOUBLE_EQ(pl.position.z(), 0.01 + 0.8);
  }
}

TEST(UniformRandomSampler, NamedReferenceAddsItsTopOffsetWhenOnTop) {
  UniformSamplerParams p = region(-0.1, 0.1, -0.2, 0.2);
  p.referencePos = Eigen::Vector3d(5.0, 5.0, 5.0);  // ignored for a named reference
  p.zOffset = 0.01;
  // Unchecked: with on_top false the ball sits inside the table.
  p.ensureValidPlacement = false;
  const ObjectPtr table = makeBox("table_top", Eigen::Vector3d(1.0, 1.0, 0.1));
  const ObjectPtr ball = makeSphere("ball", 0.05);
  const UniformRandomSampler sampler("S", p, {ball});
  const Eigen::Vector3d at(0.2, 0.3, 0.8);
  for (bool onTop : {true, false}) {
    TestScene scene(10);
    scene.context.addFixture("table", table.get(), at, Eigen::Quaterniond::Identity());
    ASSERT_TRUE(sampler.sample(scene.context, Reference::named("table"), onTop));
    const ObjectPlacement& pl = scene.context.placements().at(0);
    if (onTop) {
      EXPECT_DOUBLE_EQ(pl.position.z(), 0.01 + (0.8 + 0.05) + 0.05);
    } else {
      // No top offset and no bottom offset: robosuite's on_top=False.
      EXPECT_DOUBLE_EQ(pl.position.z(), 0.01 + 0.8);
    }
    // x and y around the reference object, shrunk by the ball's radius.
    EXPECT_GE(pl.position.x(), 0.2 - 0.1 + 0.05);
    EXPECT_LE(pl.position.x(), 0.2 + 0.1 - 0.05);
    EXPECT_GE(pl.position.y(), 0.3 - 0.2 + 0.05);
    EXPECT_LE(pl.position.y(), 0.3 + 0.2 - 0.05);
  }
}

TEST(UniformRandomSampler, PointReferenceAddsNoTopOffset) {
  UniformSamplerParams p = region(-0.1, 0.1, -0.1, 0.1);
  p.referencePos = Eigen::Vector3d(5.0, 5.0, 5.0);  // replaced by the point
  p.zOffset = 0.02;
  const ObjectPtr ball = makeSphere("ball", 0.05);
  const UniformRandomSampler sampler("S", p, {ball});
  const Eigen::Vector3d point(-1.0, 2.0, 0.7);
  for (const ObjectPlacement& pl : sampleMany(sampler, 20, 11, Reference::at(point), true)) {
    EXPECT_DOUBLE_EQ(pl.position.z(), 0.02 + 0.7 + 0.05);
    EXPECT_LE(std::abs(pl.position.x() - point.x()), 0.05 + 1e-12);
    EXPECT_LE(std::abs(pl.position.y() - point.y()), 0.05 + 1e-12);
  }
}

TEST(UniformRandomSampler, MissingNamedReferenceFails) {
  const UniformRandomSampler sampler("S", region(-0.1, 0.1, -0.1, 0.1), {makeSphere("ball", 0.01)});
  TestScene scene(12);
  EXPECT_FALSE(sampler.sample(scene.context, Reference::named("nowhere"), true));
  ASSERT_TRUE(scene.context.failure().has_value());
  EXPECT_EQ(scene.context.failure()->sampler, "S");
  EXPECT_EQ(scene.context.failure()->message,
            "sampler 'S': reference 'nowhere' is neither a fixture nor an object placed before "
            "this sampler");
  EXPECT_TRUE(scene.context.placements().empty());
}

TEST(UniformRandomSampler, ManyObjectsNeverOverlap) {
  std::vector<ObjectPtr> objects;
  for (int i = 0; i < 12; ++i) {
    objects.push_back(i % 2 == 0 ? makeSphere("ball" + std::to_string(i), 0.04)
                                 : makeCylinder("can" + std::to_string(i), 0.05, 0.1));
  }
  const UniformRandomSampler sampler("S", region(-0.4, 0.4, -0.4, 0.4), objects);
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    TestScene scene(seed);
    ASSERT_TRUE(sampler.sample(scene.context, Reference::byDefault(), true));
    const std::vector<ObjectPlacement>& placed = scene.context.placements();
    ASSERT_EQ(placed.size(), objects.size());
    for (std::size_t i = 0; i < placed.size(); ++i) {
      EXPECT_EQ(placed[i].name, objects[i]->name);  // sampling order
      for (std::size_t j = 0; j < i; ++j) {
        // The later one was tested against the earlier one, and vice versa by symmetry here.
        EXPECT_FALSE(radiusOverlap(test::asEntry(placed[j]), test::asCandidate(placed[i])));
        EXPECT_FALSE(radiusOverlap(test::asEntry(placed[i]), test::asCandidate(placed[j])));
      }
    }
  }
}

TEST(UniformRandomSampler, TouchingCountsAsOverlap) {
  const ObjectPtr a = makeSphere("a", 0.25);
  const ObjectPtr b = makeSphere("b", 0.5);
  const PlacedEntry other{"a", a.get(), Eigen::Vector3d(1.0, 2.0, 0.0),
                          Eigen::Quaterniond::Identity(), false};
  // Distance exactly r1 + r2 = 0.75 (all values exact in binary), same z.
  EXPECT_TRUE(radiusOverlap(
      other, Candidate{b.get(), Eigen::Vector3d(1.75, 2.0, 0.0), Eigen::Quaterniond::Identity()}));
  EXPECT_FALSE(radiusOverlap(other, Candidate{b.get(), Eigen::Vector3d(1.75 + 1e-9, 2.0, 0.0),
                                              Eigen::Quaterniond::Identity()}));
}

TEST(UniformRandomSampler, ZTestIsOneSided) {
  const ObjectPtr a = makeSphere("a", 0.25);
  const ObjectPtr b = makeSphere("b", 0.5);
  const PlacedEntry below{"a", a.get(), Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(),
                          false};
  // Same x-y; b's bottom exactly on a's top (z - z_o = top_o - bottom = 0.75): touching.
  EXPECT_TRUE(radiusOverlap(
      below, Candidate{b.get(), Eigen::Vector3d(0.0, 0.0, 0.75), Eigen::Quaterniond::Identity()}));
  // Above it: passes, which is what allows stacking.
  EXPECT_FALSE(radiusOverlap(
      below, Candidate{b.get(), Eigen::Vector3d(0.0, 0.0, 0.76), Eigen::Quaterniond::Identity()}));
  // Far below it: still an overlap, the test only looks one way.
  EXPECT_TRUE(radiusOverlap(
      below, Candidate{b.get(), Eigen::Vector3d(0.0, 0.0, -10.0), Eigen::Quaterniond::Identity()}));
}

TEST(UniformRandomSampler, StacksOnAFixtureItOverlapsInXY) {
  // The table covers the whole region in x-y; on_top puts the ball above it, so it passes.
  const ObjectPtr table = makeBox("table_top", Eigen::Vector3d(2.0, 2.0, 0.1));
  const UniformRandomSampler sampler("S", region(-0.3, 0.3, -0.3, 0.3), {makeSphere("ball", 0.05)});
  TestScene scene(13);
  scene.context.addFixture("table", table.get(), Eigen::Vector3d(0, 0, 0.5),
                           Eigen::Quaterniond::Identity());
  ASSERT_TRUE(sampler.sample(scene.context, Reference::named("table"), true));
  EXPECT_EQ(scene.context.placements().at(0).attempts, 1u);
}

TEST(UniformRandomSampler, FailureReportsObjectSamplerAttemptsAndBlocker) {
  // A slab at the reference height covering the region: every sample overlaps it.
  const ObjectPtr slab = makeBox("slab_geometry", Eigen::Vector3d(3.0, 3.0, 0.5));
  UniformSamplerParams p = region(-0.3, 0.3, -0.3, 0.3);
  p.maxAttempts = 50;
  const UniformRandomSampler sampler("TableSampler", p, {makeSphere("ball", 0.05)});
  TestScene scene(14);
  scene.context.addFixture("slab", slab.get(), Eigen::Vector3d::Zero(),
                           Eigen::Quaterniond::Identity());
  EXPECT_FALSE(sampler.sample(scene.context, Reference::byDefault(), true));
  ASSERT_TRUE(scene.context.failure().has_value());
  const Failure& f = *scene.context.failure();
  EXPECT_EQ(f.object, "ball");
  EXPECT_EQ(f.sampler, "TableSampler");
  EXPECT_EQ(f.attempts, 50u);
  EXPECT_EQ(f.blocker, "slab");
  EXPECT_EQ(f.blockerCount, 50u);
  EXPECT_EQ(f.message,
            "could not place object 'ball' with sampler 'TableSampler' in 50 attempts: 50 of them "
            "overlapped fixture 'slab'");
  EXPECT_TRUE(scene.context.placements().empty());
}

TEST(UniformRandomSampler, FailureAfterOneAttemptSaysAttemptInTheSingular) {
  const ObjectPtr slab = makeBox("slab_geometry", Eigen::Vector3d(3.0, 3.0, 0.5));
  UniformSamplerParams p = region(-0.3, 0.3, -0.3, 0.3);
  p.maxAttempts = 1;
  const UniformRandomSampler sampler("S", p, {makeSphere("ball", 0.05)});
  TestScene scene(14);
  scene.context.addFixture("slab", slab.get(), Eigen::Vector3d::Zero(),
                           Eigen::Quaterniond::Identity());
  EXPECT_FALSE(sampler.sample(scene.context, Reference::byDefault(), true));
  ASSERT_TRUE(scene.context.failure().has_value());
  EXPECT_EQ(scene.context.failure()->message,
            "could not place object 'ball' with sampler 'S' in 1 attempt: 1 of them overlapped "
            "fixture 'slab'");
}

TEST(Text, CountTextUsesThePluralUnlessTheCountIsOne) {
  EXPECT_EQ(countText(0, "fixture"), "0 fixtures");
  EXPECT_EQ(countText(1, "fixture"), "1 fixture");
  EXPECT_EQ(countText(2, "object"), "2 objects");
  EXPECT_EQ(countText(18446744073709551615ull, "scene"), "18446744073709551615 scenes");
}

TEST(UniformRandomSampler, FailureNamesTheMostFrequentBlocker) {
  // An earlier object covers the whole region; a post at its centre, listed first, takes the
  // samples near the centre (about a quarter). The report names the one that blocked most and
  // counts the others.
  const ObjectPtr big = makeSphere("big", 0.6);
  const ObjectPtr post = makeCylinder("post_geometry", 0.15, 1.0);
  UniformSamplerParams p = region(-0.3, 0.3, -0.3, 0.3);
  p.ensureObjectBoundaryInRange = false;
  p.maxAttempts = 200;
  const UniformRandomSampler sampler("S", p, {makeSphere("ball", 0.02)});
  TestScene scene(15);
  scene.context.addFixture("post", post.get(), Eigen::Vector3d::Zero(),
                           Eigen::Quaterniond::Identity());
  scene.context.addPlacement("earlier", Candidate{big.get()}, 1, false);
  EXPECT_FALSE(sampler.sample(scene.context, Reference::byDefault(), true));
  const Failure& f = *scene.context.failure();
  EXPECT_EQ(f.blocker, "big");
  EXPECT_GT(f.blockerCount, 100u);
  EXPECT_LT(f.blockerCount, 200u);
  EXPECT_EQ(f.message, "could not place object 'ball' with sampler 'S' in 200 attempts: " +
                           std::to_string(f.blockerCount) +
                           " of them overlapped object 'big' (and 1 other blocked too)");
}

TEST(UniformRandomSampler, ContextMaxAttemptsOverridesTheSampler) {
  const ObjectPtr slab = makeBox("slab_geometry", Eigen::Vector3d(3.0, 3.0, 0.5));
  UniformSamplerParams p = region(-0.3, 0.3, -0.3, 0.3);
  p.maxAttempts = 5000;
  const UniformRandomSampler sampler("S", p, {makeSphere("ball", 0.05)});
  TestScene scene(16, 7);
  scene.context.addFixture("slab", slab.get(), Eigen::Vector3d::Zero(),
                           Eigen::Quaterniond::Identity());
  EXPECT_FALSE(sampler.sample(scene.context, Reference::byDefault(), true));
  EXPECT_EQ(scene.context.failure()->attempts, 7u);
}

TEST(UniformRandomSampler, NoValidityCheckIgnoresObstacles) {
  const ObjectPtr slab = makeBox("slab_geometry", Eigen::Vector3d(3.0, 3.0, 0.5));
  UniformSamplerParams p = region(-0.3, 0.3, -0.3, 0.3);
  p.ensureValidPlacement = false;
  p.maxAttempts = 1;
  const UniformRandomSampler sampler("S", p, {makeSphere("a", 0.05), makeSphere("b", 0.05)});
  TestScene scene(17);
  scene.context.addFixture("slab", slab.get(), Eigen::Vector3d::Zero(),
                           Eigen::Quaterniond::Identity());
  ASSERT_TRUE(sampler.sample(scene.context, Reference::byDefault(), true));
  ASSERT_EQ(scene.context.placements().size(), 2u);
  EXPECT_EQ(scene.context.placements()[0].attempts, 1u);
  EXPECT_EQ(scene.context.placements()[1].attempts, 1u);
}

TEST(UniformRandomSampler, PlacementRecordsSamplerAndObject) {
  const ObjectPtr ball = makeSphere("ball", 0.05);
  const UniformRandomSampler sampler("S", region(-0.3, 0.3, -0.3, 0.3), {ball});
  const ObjectPlacement pl = sampleMany(sampler, 1, 18).front();
  EXPECT_EQ(pl.name, "ball");
  EXPECT_EQ(pl.sampler, "S");
  EXPECT_EQ(pl.object, ball.get());
  EXPECT_EQ(pl.attempts, 1u);  // nothing to collide with
  EXPECT_FALSE(pl.hidden);
}

TEST(UniformRandomSampler, ReversedRangeThrows) {
  EXPECT_EQ(configError([] { UniformRandomSampler("S", region(0.5, -0.5, -0.1, 0.1)); }),
            "sampler 'S': x_range must be [min, max] with min <= max, got [0.5, -0.5]");
  EXPECT_EQ(configError([] { UniformRandomSampler("S", region(-0.1, 0.1, 0.25, 0.2)); }),
            "sampler 'S': y_range must be [min, max] with min <= max, got [0.25, 0.2]");
}

TEST(UniformRandomSampler, InvalidParametersThrow) {
  EXPECT_EQ(configError([] { UniformRandomSampler("S", region(-INFINITY, 0.1, -0.1, 0.1)); }),
            "sampler 'S': x_range must be finite, got [-inf, 0.1]");
  UniformSamplerParams p = region(-0.1, 0.1, -0.1, 0.1);
  p.rotationAxis = 3;
  EXPECT_EQ(configError([&] { UniformRandomSampler("S", p); }),
            "sampler 'S': rotation_axis must be x, y or z");
  p = region(-0.1, 0.1, -0.1, 0.1);
  p.maxAttempts = 0;
  EXPECT_EQ(configError([&] { UniformRandomSampler("S", p); }),
            "sampler 'S': max_attempts must be at least 1");
  p = region(-0.1, 0.1, -0.1, 0.1);
  p.rotation = RotationSpec::fixed(NAN);
  EXPECT_EQ(configError([&] { UniformRandomSampler("S", p); }),
            "sampler 'S': rotation must be finite");
  p = region(-0.1, 0.1, -0.1, 0.1);
  p.zOffset = INFINITY;
  EXPECT_EQ(configError([&] { UniformRandomSampler("S", p); }),
            "sampler 'S': z_offset must be finite");
  p = region(-0.1, 0.1, -0.1, 0.1);
  p.referencePos.x() = NAN;
  EXPECT_EQ(configError([&] { UniformRandomSampler("S", p); }),
            "sampler 'S': reference_pos must be finite");
}

TEST(UniformRandomSampler, EmptyShrunkRegionThrows) {
  // A ball of radius 0.05 needs 0.1 m; the x range is 0.08 m wide.
  const ObjectPtr ball = makeSphere("ball", 0.05);
  EXPECT_EQ(configError([&] { UniformRandomSampler("S", region(-0.04, 0.04, -1, 1), {ball}); }),
            "sampler 'S': x_range [-0.04, 0.04] leaves no room for object 'ball' (horizontal "
            "radius 0.05 m) with ensure_object_boundary_in_range on: the range must be at least "
            "0.1 m wide");
  // Exactly as wide as the object: a single admissible centre, accepted.
  UniformRandomSampler exact("S", region(-0.05, 0.05, -1, 1), {ball});
  for (const ObjectPlacement& pl : sampleMany(exact, 10, 19)) {
    EXPECT_EQ(pl.position.x(), 0.0);
  }
  // Through addObjects too, naming the y range.
  UniformRandomSampler later("S", region(-1, 1, 0.0, 0.09));
  EXPECT_EQ(configError([&] { later.addObjects({ball}); }),
            "sampler 'S': y_range [0, 0.09] leaves no room for object 'ball' (horizontal radius "
            "0.05 m) with ensure_object_boundary_in_range on: the range must be at least 0.1 m "
            "wide");
  EXPECT_TRUE(later.objects().empty());
}

TEST(UniformRandomSampler, DuplicateObjectThrows) {
  const ObjectPtr ball = makeSphere("ball", 0.05);
  EXPECT_EQ(configError([&] {
              UniformRandomSampler("S", region(-1, 1, -1, 1), {ball, ball});
            }),
            "sampler 'S': object 'ball' is already in this sampler");
  UniformRandomSampler sampler("S", region(-1, 1, -1, 1), {ball});
  // Another model with the same name is the same object as far as names go.
  EXPECT_EQ(configError([&] { sampler.addObjects({makeSphere("ball", 0.01)}); }),
            "sampler 'S': object 'ball' is already in this sampler");
  EXPECT_EQ(sampler.objects().size(), 1u);
}

TEST(UniformRandomSampler, AddObjectsAppendsAndResetRemoves) {
  UniformRandomSampler sampler("S", region(-1, 1, -1, 1), {makeSphere("a", 0.05)});
  sampler.addObjects({makeSphere("b", 0.05), makeSphere("c", 0.05)});
  const std::vector<ObjectPtr> objects = sampler.objects();
  ASSERT_EQ(objects.size(), 3u);
  EXPECT_EQ(objects[0]->name, "a");
  EXPECT_EQ(objects[1]->name, "b");
  EXPECT_EQ(objects[2]->name, "c");
  sampler.reset();
  EXPECT_TRUE(sampler.objects().empty());
  TestScene scene(20);
  EXPECT_TRUE(sampler.sample(scene.context, Reference::byDefault(), true));
  EXPECT_TRUE(scene.context.placements().empty());
}

TEST(UniformRandomSampler, SameSeedSamePlacements) {
  std::vector<ObjectPtr> objects;
  for (int i = 0; i < 8; ++i) {
    objects.push_back(makeCylinder("can" + std::to_string(i), 0.05, 0.1));
  }
  UniformSamplerParams p = region(-0.3, 0.3, -0.3, 0.3);
  p.rotation = RotationSpec::full();
  const UniformRandomSampler sampler("S", p, objects);
  auto run = [&](std::uint64_t seed) {
    TestScene scene(seed);
    EXPECT_TRUE(sampler.sample(scene.context, Reference::byDefault(), true));
    return scene.context.placements();
  };
  const std::vector<ObjectPlacement> first = run(42);
  test::expectSamePlacements(first, run(42));
  EXPECT_TRUE(test::anyPositionDiffers(first, run(43)));
}

}  // namespace
}  // namespace placement_samplers

namespace placement_samplers {
namespace {

// robosuite's draws, replayed on a copy of the scene's engine: per attempt x then y (a point
// range draws too), after the accepted attempt one draw for a rotation pair even when
// min == max, none for a fixed angle; rejected attempts draw no rotation.
TEST(UniformRandomSampler, DrawOrderIsRobosuites) {
  UniformSamplerParams p = region(-0.2, 0.2, 0.1, 0.1);
  p.rotation = RotationSpec::range(0.25, 0.25);
  p.ensureObjectBoundaryInRange = false;
  p.referencePos = Eigen::Vector3d(0.5, 0.0, 0.8);
  const UniformRandomSampler first("First", p, {makeSphere("a", 0.02)});
  UniformSamplerParams q = region(-0.1, 0.1, -0.01, 0.01);
  q.rotation = RotationSpec::fixed(0.7);
  q.ensureObjectBoundaryInRange = false;
  q.referencePos = p.referencePos + Eigen::Vector3d(0.0, 0.1, 0.0);  // on "a"'s line
  const UniformRandomSampler second("Second", q, {makeSphere("b", 0.02)});

  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    TestScene scene(seed);
    Engine replay = scene.engine;
    ASSERT_TRUE(first.sample(scene.context, Reference::byDefault(), true));
    ASSERT_TRUE(second.sample(scene.context, Reference::byDefault(), true));
    const auto& placed = scene.context.placements();
    ASSERT_EQ(placed.size(), 2u);
    EXPECT_EQ(placed[0].position.x(), uniform(replay, -0.2, 0.2) + 0.5);
    EXPECT_EQ(placed[0].position.y(), uniform(replay, 0.1, 0.1) + 0.0);
    EXPECT_EQ(uniform(replay, 0.25, 0.25), 0.25);  // the rotation pair's draw
    // b is rejected while it lands within 0.04 m of a.
    for (std::uint32_t attempt = 1; attempt < placed[1].attempts; ++attempt) {
      const double x = uniform(replay, -0.1, 0.1) + 0.5;
      const double y = uniform(replay, -0.01, 0.01) + 0.1;
      EXPECT_LE(std::hypot(x - placed[0].position.x(), y - placed[0].position.y()), 0.04 + 1e-12);
    }
    EXPECT_EQ(placed[1].position.x(), uniform(replay, -0.1, 0.1) + 0.5);
    EXPECT_EQ(placed[1].position.y(), uniform(replay, -0.01, 0.01) + 0.1);
    // The next number of the scene's stream is the one after b's y: no rotation draw.
    EXPECT_EQ(scene.context.engine()(), replay());
  }
}

// Hidden objects draw from a stream of their own (hiddenEngine(seed, index)): hiding one
// leaves the scene's stream where it was, and its position comes from the hidden stream.
TEST(UniformRandomSampler, HiddenObjectsDrawNothingFromTheSceneStream) {
  const std::string objects = R"(
objects:
  a: {shape: sphere, radius: 0.03}
  b: {shape: sphere, radius: 0.03}
  h: {shape: sphere, radius: 0.03}
samplers:
  - {name: A, objects: [a], x_range: [-0.2, 0.2], y_range: [-0.2, 0.2]}
  - {name: B, objects: [b], x_range: [-0.2, 0.2], y_range: [-0.2, 0.2]}
)";
  const auto plain = test::buildFromYaml(objects);
  const auto hiding = test::buildFromYaml(objects + "hide: [h]\n");
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    TestScene without(seed);
    TestScene with(seed);
    ASSERT_TRUE(plain->root->sample(without.context, Reference::byDefault(), true));
    ASSERT_TRUE(hiding->root->sample(with.context, Reference::byDefault(), true));
    ASSERT_EQ(with.context.placements().size(), 3u);
    test::expectSamePlacements(
        without.context.placements(),
        {with.context.placements().begin(), with.context.placements().begin() + 2});
    EXPECT_EQ(with.context.engine()(), without.context.engine()());
    const ObjectPlacement& hidden = with.context.placements().back();
    EXPECT_TRUE(hidden.hidden);
    Engine stream = hiddenEngine(seed, 0);
    EXPECT_EQ(hidden.position.x(), uniform(stream, -20.0, -10.0) + 0.0);
    EXPECT_EQ(hidden.position.y(), uniform(stream, -20.0, -10.0) + 0.0);
  }
}

}  // namespace
}  // namespace placement_samplers
