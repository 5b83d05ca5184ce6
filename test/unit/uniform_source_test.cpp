// A uniform sampler drawing from a caller's UniformSource (what the Python module gives it: a
// numpy Generator), and inputs taken unchecked as robosuite's code takes them.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <stdexcept>
#include <vector>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/sampling/uniform_source.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::makeSphere;
using test::TestScene;

/// numpy's uniform on an engine of its own, every draw and rotation recorded.
class RecordingSource : public UniformSource {
 public:
  explicit RecordingSource(Engine engine) : engine_(engine) {}

  double uniform(double low, double high, Draw what) override {
    if (throwAt_ == draws.size()) {
      throw std::runtime_error("refused");
    }
    kinds.push_back(what);
    draws.push_back(placement_samplers::uniform(engine_, low, high));
    return draws.back();
  }
  void rotation(double angle) override { angles.push_back(angle); }

  std::vector<Draw> kinds;
  std::vector<double> draws;
  std::vector<double> angles;
  std::size_t throwAt_ = static_cast<std::size_t>(-1);

 private:
  Engine engine_;
};

UniformSamplerParams rectangle(double half) {
  UniformSamplerParams p;
  p.xRange = Eigen::Vector2d(-half, half);
  p.yRange = Eigen::Vector2d(-half, half);
  p.referencePos = Eigen::Vector3d(0.0, 0.0, 0.8);
  return p;
}

TEST(UniformSource, OrientationsLeftOutChangeNothingElse) {
  UniformSamplerParams p = rectangle(0.1);
  p.rotation = RotationSpec::range(-0.5, 0.5);
  p.checkInputs = false;
  const std::vector<ObjectPtr> objects = {makeSphere("a", 0.04), makeSphere("b", 0.04),
                                          makeSphere("c", 0.04)};
  const UniformRandomSampler with("S", p, objects);
  p.orientations = false;
  const UniformRandomSampler without("S", p, objects);
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    TestScene a(seed);
    RecordingSource sourceA(sceneEngine(seed, 0));
    a.context.setUniformSource(&sourceA);
    ASSERT_TRUE(with.sample(a.context, Reference::byDefault(), true));
    TestScene b(seed);
    RecordingSource sourceB(sceneEngine(seed, 0));
    b.context.setUniformSource(&sourceB);
    ASSERT_TRUE(without.sample(b.context, Reference::byDefault(), true));
    EXPECT_EQ(sourceB.draws, sourceA.draws);
    EXPECT_EQ(sourceB.angles, sourceA.angles);
    ASSERT_EQ(b.context.placements().size(), a.context.placements().size());
    for (std::size_t i = 0; i < a.context.placements().size(); ++i) {
      const ObjectPlacement& pa = a.context.placements()[i];
      const ObjectPlacement& pb = b.context.placements()[i];
      EXPECT_EQ(pb.position, pa.position);
      EXPECT_EQ(pb.attempts, pa.attempts);
      // Turned about z by the reported angle with them, the identity without.
      EXPECT_NEAR(pa.orientation.angularDistance(Eigen::Quaterniond(
                      Eigen::AngleAxisd(sourceA.angles[i], Eigen::Vector3d::UnitZ()))),
                  0.0, 1e-12);
      EXPECT_EQ(pb.orientation.coeffs(), Eigen::Quaterniond::Identity().coeffs());
    }
  }
}

TEST(UniformSource, DrawsWhatTheEngineWouldInRobosuitesOrder) {
  UniformSamplerParams p = rectangle(0.1);
  p.rotation = RotationSpec::range(-0.5, 0.5);
  const UniformRandomSampler sampler(
      "S", p, {makeSphere("a", 0.04), makeSphere("b", 0.04), makeSphere("c", 0.04)});
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    TestScene own(seed);
    ASSERT_TRUE(sampler.sample(own.context, Reference::byDefault(), true));
    TestScene viaSource(seed);
    RecordingSource source(sceneEngine(seed, 0));
    viaSource.context.setUniformSource(&source);
    ASSERT_TRUE(sampler.sample(viaSource.context, Reference::byDefault(), true));
    test::expectSamePlacements(viaSource.context.placements(), own.context.placements());
    // The scene's own engine was not drawn from; the source drew x, y per attempt and one
    // rotation per object, and reported each object's angle once.
    EXPECT_EQ(viaSource.context.engine()(), sceneEngine(seed, 0)());
    std::size_t attempts = 0;
    for (const ObjectPlacement& placed : own.context.placements()) {
      attempts += placed.attempts;
    }
    ASSERT_EQ(source.draws.size(), 2 * attempts + 3);
    ASSERT_EQ(source.angles.size(), 3u);
    std::size_t rotations = 0;
    for (std::size_t k = 0; k < source.kinds.size(); ++k) {
      if (source.kinds[k] == UniformSource::Draw::Rotation) {
        EXPECT_EQ(source.draws[k], source.angles[rotations++]);
        EXPECT_EQ(source.kinds[k - 1], UniformSource::Draw::Y);
      } else if (source.kinds[k] == UniformSource::Draw::Y) {
        EXPECT_EQ(source.kinds[k - 1], UniformSource::Draw::X);
      }
    }
  }
}

TEST(UniformSource, FixedRotationIsReportedWithoutADraw) {
  UniformSamplerParams p = rectangle(0.1);
  p.rotation = RotationSpec::fixed(0.7);
  const UniformRandomSampler sampler("S", p, {makeSphere("a", 0.04)});
  TestScene scene(3);
  RecordingSource source(sceneEngine(3, 0));
  scene.context.setUniformSource(&source);
  ASSERT_TRUE(sampler.sample(scene.context, Reference::byDefault(), true));
  EXPECT_EQ(source.draws.size(), 2u);
  EXPECT_EQ(source.angles, std::vector<double>{0.7});
}

TEST(UniformSource, AnExceptionStopsTheSamplingWithTheDrawsBeforeIt) {
  const UniformRandomSampler sampler("S", rectangle(0.1),
                                     {makeSphere("a", 0.04), makeSphere("b", 0.04)});
  TestScene scene(4);
  RecordingSource source(sceneEngine(4, 0));
  source.throwAt_ = 3;  // a's x, y, rotation; then b's x is refused
  scene.context.setUniformSource(&source);
  EXPECT_THROW(sampler.sample(scene.context, Reference::byDefault(), true), std::runtime_error);
  EXPECT_EQ(source.draws.size(), 3u);
  EXPECT_EQ(scene.context.placements().size(), 1u);
}

TEST(UniformSource, ServesRectangularRejectionOnly) {
  UniformSamplerParams p = rectangle(0.1);
  p.strategy = UniformSamplerParams::Strategy::FreeSpace;
  const UniformRandomSampler sampler("S", p, {makeSphere("a", 0.04)});
  TestScene scene(5);
  RecordingSource source(sceneEngine(5, 0));
  scene.context.setUniformSource(&source);
  try {
    sampler.sample(scene.context, Reference::byDefault(), true);
    FAIL() << "expected a logic_error";
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(),
                 "sampler 'S': a UniformSource serves rectangular rejection sampling only");
  }
}

TEST(UncheckedInputs, TakesWhatRobosuitesCodeTakes) {
  UniformSamplerParams p = rectangle(0.1);
  p.checkInputs = false;
  p.xRange = Eigen::Vector2d(0.3, -0.3);  // reversed
  p.yRange = Eigen::Vector2d(-1e7, 1e7);  // beyond limits::kCoordinate
  p.rotation = RotationSpec::fixed(std::numeric_limits<double>::infinity());
  p.zOffset = std::nan("");
  // The boundary shrink empties x for this radius; robosuite draws anyway (numpy decides).
  const UniformRandomSampler sampler("S", p, {makeSphere("a", 0.5)});
  EXPECT_EQ(sampler.effectiveRange(*sampler.objects()[0], 0), Eigen::Vector2d(0.8, -0.8));
  TestScene scene(6);
  Engine replay = scene.engine;
  ASSERT_TRUE(sampler.sample(scene.context, Reference::byDefault(), true));
  // The engine's own uniform is low + (high - low) u: the mirrored interval.
  EXPECT_EQ(scene.context.placements()[0].position.x(), uniform(replay, 0.8, -0.8) + 0.0);
  EXPECT_TRUE(std::isnan(scene.context.placements()[0].position.z()));
}

TEST(UncheckedInputs, OnlyForRectangularRejection) {
  UniformSamplerParams p = rectangle(0.1);
  p.checkInputs = false;
  p.strategy = UniformSamplerParams::Strategy::Dense;
  EXPECT_EQ(test::configError([&] { UniformRandomSampler("S", p, {}); }),
            "sampler 'S': unchecked inputs are for rectangular rejection sampling only");
  p.strategy = UniformSamplerParams::Strategy::Rejection;
  p.maxAttempts = 0;
  EXPECT_EQ(test::configError([&] { UniformRandomSampler("S", p, {}); }),
            "sampler 'S': max_attempts must be at least 1");
}

}  // namespace
}  // namespace placement_samplers
