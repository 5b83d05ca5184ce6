// Requests that can never be placed are recognised early: before sampling (the disks of a
// sampler's objects cannot fit its region), while sampling (after many attempts, no position is
// left), and batches whose first scenes all fail can stop there.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/sampling/packing_bound.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "sampling/free_position_check.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::buildFromYaml;

/// @p n cylinders of radius 0.1 m in a 0.5 m x 0.5 m table sampler, with @p extra keys.
std::string discs(int n, const std::string& extra = "",
                  const std::string& area = "x_range: [-0.25, 0.25], y_range: [-0.25, 0.25]") {
  std::string yaml = "objects:\n";
  std::string names;
  for (int i = 0; i < n; ++i) {
    const std::string name = "d" + std::to_string(i);
    yaml += "  " + name + ": {shape: cylinder, radius: 0.1, length: 0.05}\n";
    names += (i == 0 ? "" : ", ") + name;
  }
  return yaml + "samplers:\n  - {name: Table, objects: [" + names + "], " + area +
         ", reference_pos: [0, 0, 0.8]" + extra + "}\n";
}

std::string prepareError(const std::string& yaml, const SampleRequest& request = {}) {
  const SceneGenerator generator(buildFromYaml(yaml));
  try {
    generator.prepare(request);
  } catch (const RequestError& e) {
    return e.what();
  }
  return "no error";
}

TEST(PackingBound, RegionAreas) {
  const Eigen::Vector2d o(0.3, -0.1);
  EXPECT_DOUBLE_EQ(regionArea(RegionShape::rectangle({-0.25, 0.25}, {0, 0.2})), 0.1);
  EXPECT_DOUBLE_EQ(regionArea(RegionShape::rotatedRectangle(o, {0.4, 0.5}, 0.7)), 0.2);
  EXPECT_DOUBLE_EQ(regionArea(RegionShape::disk(o, 0.2)), M_PI * 0.04);
  EXPECT_DOUBLE_EQ(regionArea(RegionShape::annulus(o, 0.1, 0.2)), M_PI * 0.03);
  // Either winding; a non-convex L of three unit squares.
  EXPECT_DOUBLE_EQ(
      regionArea(RegionShape::polygon({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}})), 3.0);
  EXPECT_DOUBLE_EQ(
      regionArea(RegionShape::polygon({{0, 2}, {1, 2}, {1, 1}, {2, 1}, {2, 0}, {0, 0}})), 3.0);
}

TEST(PackingBound, MoreDiskAreaThanRegionIsRefusedWithTheNumbers) {
  // 8 disks of 0.0314 m^2 = 0.251 m^2 > 0.25 m^2.
  EXPECT_EQ(prepareError(discs(8)),
            "sampler 'Table' cannot place its objects: the disks of 8 objects that must not "
            "overlap ('d0', 'd1', ...) cover 0.251327 m^2, more than its region's 0.25 m^2 that "
            "they must lie in (ensure_object_boundary_in_range): no packing fits them");
  // 7 disks (0.22 m^2) are not refused: no packing argument rules them out.
  EXPECT_EQ(prepareError(discs(7)), "no error");
  // The disk of a region shape.
  EXPECT_NE(prepareError(discs(8, "", "region: {shape: disk, radius: 0.28}"))
                .find("more than its region's 0.246301 m^2"),
            std::string::npos);
}

TEST(PackingBound, OnlyWhereTheRadiusTestAndTheInsetApply) {
  EXPECT_EQ(prepareError(discs(8, ", ensure_object_boundary_in_range: false")), "no error");
  EXPECT_EQ(prepareError(discs(8, ", ensure_valid_placement: false")), "no error");
  SampleRequest fclOnly;
  fclOnly.collisionCheck = CollisionMode::Fcl;
  EXPECT_EQ(prepareError(discs(8), fclOnly), "no error");
  SampleRequest both;
  both.collisionCheck = CollisionMode::RadiusAndFcl;
  EXPECT_NE(prepareError(discs(8), both), "no error");
}

TEST(PackingBound, TheBoundIsNeverWrongOnPlaceableScenes) {
  // Near the bound (7 disks: 88 % of the area, beyond what disks pack) every scene fails; with
  // 4 disks (50 %) scenes are placed: the bound let both through, and refuses neither.
  const SceneGenerator tight(buildFromYaml(discs(7, ", max_attempts: 200")));
  const SceneGenerator loose(buildFromYaml(discs(4)));
  const auto tightScenes = tight.sampleScenes(tight.prepare({}), 3, 20);
  const auto looseScenes = loose.sampleScenes(loose.prepare({}), 3, 20);
  int placed = 0;
  for (const SceneResult& s : looseScenes) {
    placed += s.success;
  }
  EXPECT_GT(placed, 0);
  for (const SceneResult& s : tightScenes) {
    EXPECT_FALSE(s.success);
  }
}

TEST(GiveUp, StopsWhenTheFirstScenesAllFail) {
  const SceneGenerator tight(buildFromYaml(discs(7, ", max_attempts: 50")));
  const PreparedRequest request = tight.prepare({});
  std::vector<SceneResult> out;
  EXPECT_TRUE(tight.sampleSceneRangeOrGiveUp(request, 5, 100, 1000, 2, 8, out));
  ASSERT_EQ(out.size(), 8u);
  // The probe scenes are the range's first ones: the same as sampling them alone.
  const std::vector<SceneResult> alone = tight.sampleSceneRange(request, 5, 100, 8, 1);
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_FALSE(out[i].success);
    test::expectSamePlacements(out[i].placements, alone[i].placements);
  }
}

TEST(GiveUp, KeepsGoingWhenAnyProbeSceneIsPlaced) {
  const SceneGenerator loose(buildFromYaml(discs(3)));
  const PreparedRequest request = loose.prepare({});
  std::vector<SceneResult> out;
  EXPECT_FALSE(loose.sampleSceneRangeOrGiveUp(request, 5, 0, 300, 2, 8, out));
  const std::vector<SceneResult> all = loose.sampleSceneRange(request, 5, 0, 300, 1);
  ASSERT_EQ(out.size(), all.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(out[i].success, all[i].success);
    test::expectSamePlacements(out[i].placements, all[i].placements);
  }
  // probe 0 never gives up, and a probe as long as the range is the whole range.
  EXPECT_FALSE(loose.sampleSceneRangeOrGiveUp(request, 5, 0, 10, 1, 0, out));
  EXPECT_EQ(out.size(), 10u);
  const SceneGenerator tight(buildFromYaml(discs(7, ", max_attempts: 50")));
  EXPECT_FALSE(tight.sampleSceneRangeOrGiveUp(tight.prepare({}), 5, 0, 8, 1, 8, out));
  EXPECT_EQ(out.size(), 8u);
}

TEST(NoRoom, DisksThatCoverTheBoxTogether) {
  const ObjectPtr cube = test::makeBox("cube", Eigen::Vector3d(0.04, 0.04, 0.04));
  const ObjectPtr post = test::makeCylinder("post", 0.3, 0.5);
  const Eigen::Vector2d lo(-0.25, -0.25);
  const Eigen::Vector2d hi(0.25, 0.25);
  auto at = [&](double x, double y, double z) {
    return PlacedEntry("post", post.get(), Eigen::Vector3d(x, y, z), Eigen::Quaterniond::Identity(),
                       true);
  };
  // Two posts of reach 0.3 + 0.028 at x = -0.2 and 0.2 cover the box together, neither alone.
  EXPECT_TRUE(detail::noFreePosition({at(-0.2, 0, 0.8), at(0.2, 0, 0.8)}, *cube, 0.8, lo, hi));
  EXPECT_FALSE(detail::noFreePosition({at(-0.2, 0, 0.8)}, *cube, 0.8, lo, hi));
  // Moved apart, a strip between them is free.
  EXPECT_FALSE(detail::noFreePosition({at(-0.4, 0, 0.8), at(0.4, 0, 0.8)}, *cube, 0.8, lo, hi));
  // A post whose top is below the cube's bottom does not block it (the one-sided z test).
  EXPECT_FALSE(detail::noFreePosition({at(-0.2, 0, 0.8), at(0.2, 0, 0.2)}, *cube, 0.8, lo, hi));
  EXPECT_FALSE(detail::noFreePosition({}, *cube, 0.8, lo, hi));
}

/// A table sampler with a wall over it and an absurd attempt limit ends after the probe's
/// attempts, well before its time limit, and says why.
TEST(NoRoom, AWallOverTheRegionEndsTheAttemptsEarly) {
  const std::string yaml = R"(
objects:
  cube: {shape: box, size: [0.04, 0.04, 0.04]}
  can: {shape: cylinder, radius: 0.03, length: 0.1}
samplers:
  - {name: Table, objects: [can, cube], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3],
     reference_pos: [0, 0, 0.8]}
)";
  const SceneGenerator generator(buildFromYaml(yaml));
  auto run = [&](const std::vector<RequestFixture>& fixtures) {
    SampleRequest request;
    request.maxAttempts = 4000000000u;
    request.maxSeconds = 60.0;
    request.fixtures = fixtures;
    return generator.sampleScene(generator.prepare(request), 1, 0);
  };
  auto box = [](const std::string& name, double x, double y, double side) {
    RequestFixture f;
    f.name = name;
    f.shape = Shape::box(Eigen::Vector3d(side, side, 0.4));
    f.position = Eigen::Vector3d(x, y, 0.9);
    return f;
  };
  const SceneResult walled = run({box("wall", 0, 0, 1.0)});
  ASSERT_FALSE(walled.success);
  EXPECT_EQ(walled.message,
            "could not place object 'can' with sampler 'Table': after 131071 attempts, no "
            "position is left (every position of its range overlaps a fixture or an object "
            "placed before it)");
  // Four tiles that cover it only together.
  const SceneResult tiled = run({box("a", -0.2, -0.2, 0.45), box("b", 0.2, -0.2, 0.45),
                                 box("c", -0.2, 0.2, 0.45), box("d", 0.2, 0.2, 0.45)});
  ASSERT_FALSE(tiled.success);
  EXPECT_NE(tiled.message.find("no position is left"), std::string::npos) << tiled.message;
}

}  // namespace
}  // namespace placement_samplers
