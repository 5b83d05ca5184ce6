// SequentialCompositeSampler against robosuite's semantics: order, sample_args, call-level
// arguments (without robosuite's sticking stored-args bug), add_objects_to_sampler, hide(),
// reset(), nesting and fixtures.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "placement_samplers/collision/radius_checker.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/sampling/sequential_composite_sampler.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::configError;
using test::findPlacement;
using test::makeBox;
using test::makeCylinder;
using test::makeSphere;
using test::TestScene;

std::shared_ptr<UniformRandomSampler> uniform(
    const std::string& name, const std::vector<ObjectPtr>& objects, double halfWidth = 0.3,
    const Eigen::Vector3d& referencePos = Eigen::Vector3d::Zero()) {
  UniformSamplerParams p;
  p.xRange = Eigen::Vector2d(-halfWidth, halfWidth);
  p.yRange = Eigen::Vector2d(-halfWidth, halfWidth);
  p.referencePos = referencePos;
  p.maxAttempts = 1000;
  return std::make_shared<UniformRandomSampler>(name, p, objects);
}

SampleArgs args(const Reference& reference, bool onTop) {
  SampleArgs a;
  a.reference = reference;
  a.onTop = onTop;
  return a;
}

std::vector<std::string> names(const std::vector<ObjectPtr>& objects) {
  std::vector<std::string> out;
  for (const ObjectPtr& o : objects) {
    out.push_back(o->name);
  }
  return out;
}

std::vector<std::string> names(const std::vector<ObjectPlacement>& placements) {
  std::vector<std::string> out;
  for (const ObjectPlacement& p : placements) {
    out.emplace_back(p.name);
  }
  return out;
}

TEST(SequentialCompositeSampler, RunsSubSamplersInOrder) {
  SequentialCompositeSampler root("root");
  root.appendSampler(uniform("B", {makeSphere("b1", 0.02), makeSphere("b2", 0.02)}));
  root.appendSampler(uniform("A", {makeSphere("a1", 0.02)}));
  EXPECT_EQ(root.size(), 2u);
  EXPECT_EQ(names(root.objects()), (std::vector<std::string>{"b1", "b2", "a1"}));
  TestScene scene(1);
  ASSERT_TRUE(root.sample(scene.context, Reference::byDefault(), true));
  const std::vector<ObjectPlacement>& placed = scene.context.placements();
  EXPECT_EQ(names(placed), (std::vector<std::string>{"b1", "b2", "a1"}));
  EXPECT_EQ(placed[0].sampler, "B");
  EXPECT_EQ(placed[2].sampler, "A");
}

TEST(SequentialCompositeSampler, LaterSamplersAvoidEarlierObjects) {
  SequentialCompositeSampler root("root");
  root.appendSampler(
      uniform("A", {makeCylinder("a1", 0.05, 0.1), makeCylinder("a2", 0.05, 0.1)}, 0.25));
  root.appendSampler(
      uniform("B", {makeCylinder("b1", 0.05, 0.1), makeCylinder("b2", 0.05, 0.1)}, 0.25));
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    TestScene scene(seed);
    ASSERT_TRUE(root.sample(scene.context, Reference::byDefault(), true));
    const std::vector<ObjectPlacement>& placed = scene.context.placements();
    for (std::size_t i = 0; i < placed.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        EXPECT_FALSE(radiusOverlap(test::asEntry(placed[j]), test::asCandidate(placed[i])));
      }
    }
  }
}

TEST(SequentialCompositeSampler, SampleArgsReferenceStacksOnEarlierObject) {
  SequentialCompositeSampler root("root");
  const ObjectPtr plate = makeCylinder("plate", 0.09, 0.02);
  const ObjectPtr cup = makeCylinder("cup", 0.04, 0.09);
  root.appendSampler(uniform("PlateSampler", {plate}, 0.3, Eigen::Vector3d(0, 0, 0.8)));
  auto cupSampler = uniform("CupSampler", {cup}, 0.05);
  root.appendSampler(cupSampler, args(Reference::named("plate"), true));
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    TestScene scene(seed);
    ASSERT_TRUE(root.sample(scene.context, Reference::byDefault(), true));
    const ObjectPlacement* p = findPlacement(scene.context.placements(), "plate");
    const ObjectPlacement* c = findPlacement(scene.context.placements(), "cup");
    ASSERT_TRUE(p != nullptr && c != nullptr);
    // z = ref.z + ref.top - bottom (z_offset 0); x, y around the plate.
    EXPECT_DOUBLE_EQ(c->position.z(),
                     p->position.z() + plate->topOffset.z() - cup->bottomOffset.z());
    EXPECT_LE(std::abs(c->position.x() - p->position.x()), 0.05 - 0.04 + 1e-12);
    EXPECT_LE(std::abs(c->position.y() - p->position.y()), 0.05 - 0.04 + 1e-12);
    // Stacked over the plate it overlaps in x-y, which the one-sided test allows.
    EXPECT_EQ(c->attempts, 1u);
  }
}

TEST(SequentialCompositeSampler, CallReferenceFillsOnlyChildrenWithout) {
  SequentialCompositeSampler root("root");
  const Eigen::Vector3d own(10.0, 0.0, 1.0);
  const Eigen::Vector3d call(-10.0, 0.0, 2.0);
  root.appendSampler(uniform("Fixed", {makeSphere("a", 0.02)}, 0.1),
                     args(Reference::at(own), true));
  root.appendSampler(uniform("Free", {makeSphere("b", 0.02)}, 0.1));
  TestScene scene(2);
  ASSERT_TRUE(root.sample(scene.context, Reference::at(call), false));
  const ObjectPlacement* a = findPlacement(scene.context.placements(), "a");
  const ObjectPlacement* b = findPlacement(scene.context.placements(), "b");
  ASSERT_TRUE(a != nullptr && b != nullptr);
  // Fixed keeps its own point and on_top (z = point.z - bottom).
  EXPECT_NEAR(a->position.x(), own.x(), 0.1);
  EXPECT_DOUBLE_EQ(a->position.z(), own.z() + 0.02);
  // Free takes the call's point and on_top=false (z = point.z).
  EXPECT_NEAR(b->position.x(), call.x(), 0.1);
  EXPECT_DOUBLE_EQ(b->position.z(), call.z());
}

TEST(SequentialCompositeSampler, CallArgumentsDoNotStickBetweenCalls) {
  // robosuite writes the first call's reference into the stored sample_args; here the second
  // call with no reference goes back to the sampler's own reference_pos.
  SequentialCompositeSampler root("root");
  const Eigen::Vector3d referencePos(3.0, 4.0, 0.5);
  root.appendSampler(uniform("Free", {makeSphere("b", 0.02)}, 0.1, referencePos));
  TestScene first(3);
  ASSERT_TRUE(root.sample(first.context, Reference::at(Eigen::Vector3d(-10, -10, 0)), false));
  EXPECT_NEAR(first.context.placements().at(0).position.x(), -10.0, 0.1);
  TestScene second(3);
  ASSERT_TRUE(root.sample(second.context, Reference::byDefault(), true));
  const ObjectPlacement& b = second.context.placements().at(0);
  EXPECT_NEAR(b.position.x(), referencePos.x(), 0.1);
  EXPECT_NEAR(b.position.y(), referencePos.y(), 0.1);
  EXPECT_DOUBLE_EQ(b.position.z(), referencePos.z() + 0.02);
}

TEST(SequentialCompositeSampler, PartialSampleArgs) {
  // Only on_top is stored: the reference still comes from the call.
  SequentialCompositeSampler root("root");
  SampleArgs onlyOnTop;
  onlyOnTop.onTop = false;
  root.appendSampler(uniform("S", {makeSphere("b", 0.02)}, 0.1), onlyOnTop);
  TestScene scene(4);
  ASSERT_TRUE(root.sample(scene.context, Reference::at(Eigen::Vector3d(1.0, 1.0, 1.0)), true));
  const ObjectPlacement& b = scene.context.placements().at(0);
  EXPECT_NEAR(b.position.x(), 1.0, 0.1);
  EXPECT_DOUBLE_EQ(b.position.z(), 1.0);
}

TEST(SequentialCompositeSampler, AddObjectsToSampler) {
  SequentialCompositeSampler root("root");
  root.appendSampler(uniform("A", {makeSphere("a", 0.02)}));
  root.addObjectsToSampler("A", {makeSphere("a2", 0.02)});
  EXPECT_EQ(names(root.objects()), (std::vector<std::string>{"a", "a2"}));
  TestScene scene(5);
  ASSERT_TRUE(root.sample(scene.context, Reference::byDefault(), true));
  EXPECT_EQ(names(scene.context.placements()), (std::vector<std::string>{"a", "a2"}));
}

TEST(SequentialCompositeSampler, AddObjectsToNestedSampler) {
  SequentialCompositeSampler root("root");
  auto inner = std::make_shared<SequentialCompositeSampler>("Inner");
  inner->appendSampler(uniform("Deep", {}));
  root.appendSampler(uniform("A", {makeSphere("a", 0.02)}));
  root.appendSampler(inner);
  root.addObjectsToSampler("Deep", {makeSphere("d", 0.02)});
  EXPECT_EQ(names(inner->objects()), (std::vector<std::string>{"d"}));
  EXPECT_EQ(names(root.objects()), (std::vector<std::string>{"a", "d"}));
  TestScene scene(6);
  ASSERT_TRUE(root.sample(scene.context, Reference::byDefault(), true));
  EXPECT_EQ(findPlacement(scene.context.placements(), "d")->sampler, "Deep");
}

TEST(SequentialCompositeSampler, AddObjectsToUnknownOrCompositeSamplerThrows) {
  SequentialCompositeSampler root("root");
  root.appendSampler(std::make_shared<SequentialCompositeSampler>("Inner"));
  EXPECT_EQ(configError([&] { root.addObjectsToSampler("Nope", {makeSphere("x", 0.02)}); }),
            "sampler 'root': no uniform sub-sampler named 'Nope'");
  EXPECT_EQ(configError([&] { root.addObjectsToSampler("Inner", {makeSphere("x", 0.02)}); }),
            "sampler 'root': no uniform sub-sampler named 'Inner'");
}

TEST(SequentialCompositeSampler, DuplicateObjectAcrossSamplersThrows) {
  SequentialCompositeSampler root("root");
  const ObjectPtr ball = makeSphere("ball", 0.02);
  root.appendSampler(uniform("A", {ball}));
  EXPECT_EQ(configError([&] { root.appendSampler(uniform("B", {ball})); }),
            "sampler 'root': object 'ball' already has a sampler");
  root.appendSampler(uniform("C", {}));
  EXPECT_EQ(configError([&] { root.addObjectsToSampler("C", {ball}); }),
            "sampler 'root': object 'ball' already has a sampler");
  // Inside a nested composite too.
  auto inner = std::make_shared<SequentialCompositeSampler>("Inner");
  inner->appendSampler(uniform("D", {ball}));
  EXPECT_EQ(configError([&] { root.appendSampler(inner); }),
            "sampler 'root': object 'ball' already has a sampler");
  EXPECT_EQ(root.size(), 2u);
}

TEST(SequentialCompositeSampler, DuplicateSamplerNameThrows) {
  SequentialCompositeSampler root("root");
  root.appendSampler(uniform("A", {}));
  EXPECT_EQ(configError([&] { root.appendSampler(uniform("A", {})); }),
            "sampler 'root': a sampler named 'A' is already here");
  EXPECT_EQ(configError([&] { root.appendSampler(uniform("root", {})); }),
            "sampler 'root': a sampler named 'root' is already here");
  // A clash anywhere in the incoming subtree.
  auto inner = std::make_shared<SequentialCompositeSampler>("Inner");
  inner->appendSampler(uniform("A", {}));
  EXPECT_EQ(configError([&] { root.appendSampler(inner); }),
            "sampler 'root': a sampler named 'A' is already here");
  EXPECT_EQ(root.size(), 1u);
}

TEST(SequentialCompositeSampler, NullSamplerThrows) {
  SequentialCompositeSampler root("root");
  EXPECT_EQ(configError([&] { root.appendSampler(nullptr); }),
            "sampler 'root': cannot append a null sampler");
}

TEST(SequentialCompositeSampler, HidePlacesFarAwayWithoutChecks) {
  SequentialCompositeSampler root("root");
  const ObjectPtr ball = makeSphere("ball", 0.05);
  const ObjectPtr can = makeCylinder("can", 0.03, 0.12);
  root.hide({ball, can});
  // A slab over the whole hiding area: hidden objects are not checked against it.
  const ObjectPtr slab = makeBox("slab_geometry", Eigen::Vector3d(40.0, 40.0, 40.0));
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    TestScene scene(seed);
    scene.context.addFixture("slab", slab.get(), Eigen::Vector3d(-15, -15, 10),
                             Eigen::Quaterniond::Identity());
    // The call's reference and on_top do not move hidden objects.
    ASSERT_TRUE(root.sample(scene.context, Reference::at(Eigen::Vector3d(5, 5, 5)), false));
    ASSERT_EQ(scene.context.placements().size(), 2u);
    for (const ObjectPlacement& p : scene.context.placements()) {
      EXPECT_TRUE(p.hidden);
      EXPECT_EQ(p.sampler, SequentialCompositeSampler::kHideSamplerName);
      EXPECT_EQ(p.attempts, 1u);
      EXPECT_GE(p.position.x(), -20.0);
      EXPECT_LE(p.position.x(), -10.0);
      EXPECT_GE(p.position.y(), -20.0);
      EXPECT_LE(p.position.y(), -10.0);
      EXPECT_DOUBLE_EQ(p.position.z(), 10.0 - p.object->bottomOffset.z());
    }
  }
}

TEST(SequentialCompositeSampler, HideTwiceAddsToTheSameHideSampler) {
  // Upstream's second hide() replaces the first; here both sets stay hidden.
  SequentialCompositeSampler root("root");
  root.appendSampler(uniform("A", {makeSphere("a", 0.02)}));
  root.hide({makeSphere("h1", 0.02)});
  root.hide({makeSphere("h2", 0.02)});
  EXPECT_EQ(root.size(), 2u);
  std::vector<const PlacementSampler*> all;
  root.collectSamplers(all);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[2]->name(), SequentialCompositeSampler::kHideSamplerName);
  EXPECT_EQ(names(all[2]->objects()), (std::vector<std::string>{"h1", "h2"}));
  TestScene scene(7);
  ASSERT_TRUE(root.sample(scene.context, Reference::byDefault(), true));
  EXPECT_FALSE(findPlacement(scene.context.placements(), "a")->hidden);
  EXPECT_TRUE(findPlacement(scene.context.placements(), "h1")->hidden);
  EXPECT_TRUE(findPlacement(scene.context.placements(), "h2")->hidden);
  // An object already here cannot be hidden as well.
  EXPECT_EQ(configError([&] { root.hide({makeSphere("a", 0.02)}); }),
            "sampler 'root': object 'a' already has a sampler");
  EXPECT_EQ(configError([&] { root.hide({makeSphere("h1", 0.02)}); }),
            "sampler 'root': object 'h1' already has a sampler");
}

TEST(SequentialCompositeSampler, ResetRemovesEveryObjectKeepsSamplers) {
  SequentialCompositeSampler root("root");
  auto inner = std::make_shared<SequentialCompositeSampler>("Inner");
  inner->appendSampler(uniform("Deep", {makeSphere("d", 0.02)}));
  root.appendSampler(uniform("A", {makeSphere("a", 0.02)}));
  root.appendSampler(inner);
  root.hide({makeSphere("h", 0.02)});
  root.reset();
  EXPECT_TRUE(root.objects().empty());
  EXPECT_EQ(root.size(), 3u);
  TestScene scene(8);
  ASSERT_TRUE(root.sample(scene.context, Reference::byDefault(), true));
  EXPECT_TRUE(scene.context.placements().empty());
  // The objects can be added again after a reset.
  root.addObjectsToSampler("A", {makeSphere("a", 0.02)});
  EXPECT_EQ(names(root.objects()), (std::vector<std::string>{"a"}));
}

TEST(SequentialCompositeSampler, NestedCompositePassesItsArgsDown) {
  // root: [Plate, Inner (sample_args: on the plate) [Cup, Spoon (own point)]].
  SequentialCompositeSampler root("root");
  const ObjectPtr plate = makeCylinder("plate", 0.09, 0.02);
  const ObjectPtr cup = makeCylinder("cup", 0.04, 0.09);
  const ObjectPtr spoon = makeSphere("spoon", 0.01);
  root.appendSampler(uniform("Plate", {plate}, 0.3, Eigen::Vector3d(0, 0, 0.8)));
  auto inner = std::make_shared<SequentialCompositeSampler>("Inner");
  auto cupSampler = uniform("Cup", {cup}, 0.05);
  inner->appendSampler(cupSampler);
  inner->appendSampler(uniform("Spoon", {spoon}, 0.05),
                       args(Reference::at(Eigen::Vector3d(2, 2, 0)), true));
  root.appendSampler(inner, args(Reference::named("plate"), true));
  EXPECT_EQ(names(root.objects()), (std::vector<std::string>{"plate", "cup", "spoon"}));

  TestScene scene(9);
  ASSERT_TRUE(root.sample(scene.context, Reference::byDefault(), true));
  const std::vector<ObjectPlacement>& placed = scene.context.placements();
  EXPECT_EQ(names(placed), (std::vector<std::string>{"plate", "cup", "spoon"}));
  const ObjectPlacement* p = findPlacement(placed, "plate");
  const ObjectPlacement* c = findPlacement(placed, "cup");
  const ObjectPlacement* s = findPlacement(placed, "spoon");
  EXPECT_DOUBLE_EQ(c->position.z(), p->position.z() + plate->topOffset.z() - cup->bottomOffset.z());
  EXPECT_LE(std::abs(c->position.x() - p->position.x()), 0.01 + 1e-12);
  EXPECT_NEAR(s->position.x(), 2.0, 0.05);
  EXPECT_DOUBLE_EQ(s->position.z(), 0.01);

  // find() reports each sampler with the args its parent gives it.
  SampleArgs found;
  EXPECT_EQ(root.find("Inner", &found), inner.get());
  ASSERT_TRUE(found.reference.has_value());
  EXPECT_EQ(found.reference->name, "plate");
  EXPECT_EQ(root.find("Spoon", &found)->name(), "Spoon");
  ASSERT_TRUE(found.reference.has_value());
  EXPECT_EQ(found.reference->kind, Reference::Kind::Point);
  // Cup has no args of its own: it gets Inner's, as in the full run.
  EXPECT_EQ(root.find("Cup", &found), cupSampler.get());
  ASSERT_TRUE(found.reference.has_value());
  EXPECT_EQ(found.reference->name, "plate");
  EXPECT_EQ(found.onTop, std::optional<bool>(true));
  EXPECT_EQ(root.find("root", &found), &root);
  EXPECT_FALSE(found.reference.has_value());
  EXPECT_EQ(root.find("Nope", &found), nullptr);
}

TEST(SequentialCompositeSampler, FailureStopsTheSequence) {
  SequentialCompositeSampler root("root");
  UniformSamplerParams p;
  p.xRange = Eigen::Vector2d(-0.1, 0.1);
  p.yRange = Eigen::Vector2d(-0.1, 0.1);
  p.maxAttempts = 20;
  root.appendSampler(std::make_shared<UniformRandomSampler>(
      "Crowded", p, std::vector<ObjectPtr>{makeSphere("a", 0.1), makeSphere("b", 0.1)}));
  root.appendSampler(uniform("After", {makeSphere("c", 0.01)}, 1.0));
  TestScene scene(10);
  EXPECT_FALSE(root.sample(scene.context, Reference::byDefault(), true));
  ASSERT_TRUE(scene.context.failure().has_value());
  EXPECT_EQ(scene.context.failure()->object, "b");
  EXPECT_EQ(scene.context.failure()->sampler, "Crowded");
  EXPECT_EQ(findPlacement(scene.context.placements(), "c"), nullptr);
}

TEST(SequentialCompositeSampler, FixturesAreAvoidedButNotPlaced) {
  // A post in the middle of the region: objects go around it, and it is no placement.
  SequentialCompositeSampler root("root");
  std::vector<ObjectPtr> objects;
  for (int i = 0; i < 5; ++i) {
    objects.push_back(makeCylinder("can" + std::to_string(i), 0.03, 0.1));
  }
  root.appendSampler(uniform("S", objects, 0.3));
  const ObjectPtr post = makeCylinder("post_geometry", 0.15, 1.0);
  int blocked = 0;
  for (std::uint64_t seed = 1; seed <= 100; ++seed) {
    TestScene scene(seed);
    scene.context.addFixture("post", post.get(), Eigen::Vector3d::Zero(),
                             Eigen::Quaterniond::Identity());
    ASSERT_TRUE(root.sample(scene.context, Reference::byDefault(), true));
    EXPECT_EQ(findPlacement(scene.context.placements(), "post"), nullptr);
    EXPECT_EQ(scene.context.placements().size(), 5u);
    const PlacedEntry& fixture = scene.context.entries().front();
    ASSERT_TRUE(fixture.fixture);
    for (const ObjectPlacement& p : scene.context.placements()) {
      EXPECT_FALSE(radiusOverlap(fixture, test::asCandidate(p)));
      blocked += p.attempts > 1 ? 1 : 0;
    }
  }
  // The post covers a fair part of the region, so it did reject samples.
  EXPECT_GT(blocked, 0);
}

}  // namespace
}  // namespace placement_samplers
