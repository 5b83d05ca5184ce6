// Uniform samplers with region shapes and keep-out zones: robosuite's draws where they apply,
// insets, zones never entered, configuration errors naming the parameter, description, display.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "placement_samplers/output/scene_json.hpp"
#include "placement_samplers/sampling/region.hpp"
#include "placement_samplers/sampling/sampler_regions.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/validation/region_test.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::buildFromYaml;

const std::string kObjects = R"(
objects:
  can: {shape: cylinder, radius: 0.03, length: 0.1}
  cube: {shape: box, size: [0.04, 0.04, 0.04]}
  plate: {shape: cylinder, radius: 0.09, length: 0.02}
fixtures:
  - {name: table, object: plate, position: [0.5, -0.2, 0.8]}
)";

std::string buildError(const std::string& yaml) {
  return test::configError([&] { buildFromYaml(kObjects + yaml); });
}

/// Scenes of a generator kept alive with them: placements hold views of its names.
struct Scenes {
  std::shared_ptr<const SceneGenerator> generator;
  std::vector<SceneResult> results;
  std::size_t size() const { return results.size(); }
  const SceneResult& operator[](std::size_t i) const { return results[i]; }
  auto begin() const { return results.begin(); }
  auto end() const { return results.end(); }
};

Scenes scenes(const std::string& yaml, std::size_t count, std::uint64_t seed = 3) {
  auto generator = std::make_shared<const SceneGenerator>(buildFromYaml(kObjects + yaml));
  auto results = generator->sampleScenes(generator->prepare(SampleRequest()), seed, count, 1);
  return Scenes{generator, std::move(results)};
}

TEST(RegionSampler, RectangleRegionIsXAndYRange) {
  const Scenes a = scenes(
      "samplers:\n  - {name: S, objects: [can, cube, plate], x_range: [-0.2, 0.2], "
      "y_range: [-0.1, 0.15]}\n",
      300);
  const Scenes b = scenes(
      "samplers:\n  - {name: S, objects: [can, cube, plate], region: {shape: rectangle, "
      "x_range: [-0.2, 0.2], y_range: [-0.1, 0.15]}}\n",
      300);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].success, b[i].success);
    test::expectSamePlacements(a[i].placements, b[i].placements);
  }
}

/// A keep-out zone that nothing reaches changes no draw: the shaped loop draws what
/// robosuite's does.
TEST(RegionSampler, FarKeepOutChangesNothing) {
  const std::string base =
      "samplers:\n  - {name: S, objects: [can, cube, plate], x_range: [-0.2, 0.2], "
      "y_range: [-0.2, 0.2], rotation: [0, 1]";
  const Scenes a = scenes(base + "}\n", 300);
  const Scenes b = scenes(base + ", keep_out: [{shape: disk, center: [5, 5], radius: 1}]}\n", 300);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].success, b[i].success);
    test::expectSamePlacements(a[i].placements, b[i].placements);
  }
}

/// The documented key `center` and its alias `centre` give the same scenes.
TEST(RegionSampler, CentreIsAnAliasOfCenter) {
  const std::string base = "samplers:\n  - {name: S, objects: [can, cube], region: {shape: disk, ";
  const Scenes a = scenes(base + "center: [0.05, -0.02], radius: 0.3}}\n", 200);
  const Scenes b = scenes(base + "centre: [0.05, -0.02], radius: 0.3}}\n", 200);
  const Scenes c = scenes(base + "radius: 0.3}}\n", 200);
  ASSERT_EQ(a.size(), b.size());
  std::size_t differentFromOrigin = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].success, b[i].success);
    test::expectSamePlacements(a[i].placements, b[i].placements);
    differentFromOrigin +=
        a[i].placements.front().position.x() != c[i].placements.front().position.x();
  }
  EXPECT_EQ(differentFromOrigin, a.size());  // the key is read, not ignored
}

/// Every placement keeps its disk inside the region and out of every zone (sampler frame
/// around a named reference, and world frame), over many scenes; the zones are really in the
/// way (attempts were spent on them).
TEST(RegionSampler, KeepOutZonesAreNeverEntered) {
  const std::string yaml = R"(
samplers:
  - name: S
    objects: [can, cube]
    region: {shape: annulus, inner_radius: 0.05, outer_radius: 0.3}
    keep_out:
      - {shape: rotated_rectangle, center: [0.1, 0], size: [0.2, 0.08], yaw: 0.5}
      - {shape: polygon, vertices: [[0.3, -0.4], [0.7, -0.4], [0.5, -0.3]], frame: world}
    ensure_valid_placement: false
    sample_args: {reference: table}
)";
  const RegionShape region = RegionShape::annulus(Eigen::Vector2d(0.5, -0.2), 0.05, 0.3);
  const RegionShape sampler =
      RegionShape::rotatedRectangle(Eigen::Vector2d(0.6, -0.2), Eigen::Vector2d(0.2, 0.08), 0.5);
  const RegionShape world = RegionShape::polygon({{0.3, -0.4}, {0.7, -0.4}, {0.5, -0.3}});
  std::size_t extra = 0;
  for (const SceneResult& scene : scenes(yaml, 2000)) {
    ASSERT_TRUE(scene.success) << scene.message;
    for (const ObjectPlacement& p : scene.placements) {
      const Eigen::Vector2d xy = p.position.head<2>();
      const double r = p.object->horizontalRadius;
      EXPECT_TRUE(shapeContains(region, xy));
      const double d = (xy - Eigen::Vector2d(0.5, -0.2)).norm();
      EXPECT_GE(d, 0.05 + r - 1e-12);
      EXPECT_LE(d, 0.3 - r + 1e-12);
      EXPECT_GE(distanceToShape(sampler, xy), r - 1e-12);
      EXPECT_GE(distanceToShape(world, xy), r - 1e-12);
      extra += p.attempts - 1;
    }
  }
  EXPECT_GT(extra, 500u);
}

TEST(RegionSampler, WithoutBoundaryOnlyTheCentreStaysOut) {
  const std::string yaml = R"(
samplers:
  - name: S
    objects: [plate]
    region: {shape: disk, radius: 0.2}
    keep_out: [{shape: disk, radius: 0.1}]
    ensure_object_boundary_in_range: false
)";
  double nearest = 1.0;
  double farthest = 0.0;
  for (const SceneResult& scene : scenes(yaml, 3000)) {
    ASSERT_TRUE(scene.success);
    const double d = scene.placements[0].position.head<2>().norm();
    nearest = std::min(nearest, d);
    farthest = std::max(farthest, d);
  }
  EXPECT_GE(nearest, 0.1);
  EXPECT_LT(nearest, 0.101);  // the plate's disk (0.09 m) reaches into the zone
  EXPECT_LE(farthest, 0.2);
  EXPECT_GT(farthest, 0.199);  // and out of the region
}

TEST(RegionSampler, AZoneOverEverythingIsAFailedScene) {
  const Scenes out = scenes(
      "max_attempts: 50\nsamplers:\n  - {name: S, objects: [cube], region: {shape: disk, "
      "radius: 0.2}, keep_out: [{shape: disk, radius: 0.25}]}\n",
      1);
  ASSERT_FALSE(out[0].success);
  EXPECT_EQ(out[0].message,
            "could not place object 'cube' with sampler 'S' in 50 attempts: 50 of them fell into "
            "a keep-out zone or too near the region's edge");
}

TEST(RegionSampler, ConfigurationErrorsNameTheParameter) {
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [can], region: {shape: polygon, "
                       "vertices: [[0, 0], [1, 1], [1, 0], [0, 1]]}}\n"),
            "samplers[0].region.vertices: the polygon intersects itself: the edge from vertex 0 "
            "[0, 0] to vertex 1 [1, 1] crosses the edge from vertex 2 [1, 0] to vertex 3 [0, 1]");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [can], region: {shape: annulus, "
                       "inner_radius: 0.4, outer_radius: 0.3}}\n"),
            "samplers[0].region.inner_radius: the inner radius 0.4 m must be less than "
            "outer_radius 0.3 m");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [can], region: {shape: polygon, "
                       "vertices: [[0, 0], [.nan, 1], [1, 0]]}}\n"),
            "samplers[0].region.vertices[1][0]: expected a finite number, got a number (nan)");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [can], region: {shape: polygon, "
                       "vertices: [[0, 0], [1, 0]]}}\n"),
            "samplers[0].region.vertices: expected 3 to 1000 vertices [x, y], got 2");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, region: {shape: circle, radius: 1}}\n"),
            "samplers[0].region.shape: expected rectangle, rotated_rectangle, disk, annulus, "
            "polygon or surface, got 'circle'");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, region: {shape: disk, size: 1}}\n"),
            "samplers[0].region: unknown key 'size' (expected one of: shape, center, radius)");
  // `centre` is an alias of `center`: listed when the user wrote it, never both.
  EXPECT_EQ(
      buildError("samplers:\n  - {name: S, region: {shape: disk, centre: [0, 0], size: 1}}\n"),
      "samplers[0].region: unknown key 'size' (expected one of: shape, center, centre, "
      "radius)");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, region: {shape: disk, center: [0, 0], centre: "
                       "[0, 0], radius: 1}}\n"),
            "samplers[0].region.centre: 'centre' is an alias of 'center': give one of them");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, keep_out: [{shape: disk, centre: [2e6, 0], "
                       "radius: 1}]}\n"),
            "samplers[0].keep_out[0].centre: expected [x, y] within [-1e+06, 1e+06] m, got [2e+06, "
            "0]");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, region: {shape: disk}}\n"),
            "samplers[0].region: missing required key 'radius'");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, x_range: [0, 1], region: {shape: disk, "
                       "radius: 1}}\n"),
            "samplers[0].x_range: region replaces x_range: give one or the other");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, objects: [plate], region: {shape: disk, "
                       "radius: 0.08}}\n"),
            "samplers[0].region: sampler 'S': region (disk) leaves no room for object 'plate' "
            "(horizontal radius 0.09 m) with ensure_object_boundary_in_range on: no point of it "
            "is that far from its edge");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, keep_out: [{shape: disk, radius: 0.1, "
                       "frame: map}]}\n"),
            "samplers[0].keep_out[0].frame: expected sampler (around the sampler's reference) or "
            "world, got 'map'");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, keep_out: [{shape: disk, radius: -1}]}\n"),
            "samplers[0].keep_out[0].radius: expected a length > 0 [m] within [-1e+06, 1e+06] m, "
            "got -1");
  // Built without the configuration, the sampler says the same.
  UniformSamplerParams p;
  p.region = RegionShape::annulus(Eigen::Vector2d::Zero(), 0.3, 0.2);
  EXPECT_EQ(test::configError([&] { UniformRandomSampler("S", p); }),
            "sampler 'S': region.inner_radius: the inner radius 0.3 m must be less than "
            "outer_radius 0.2 m");
}

TEST(RegionSampler, DescribedAndDisplayed) {
  const std::string yaml = R"(
samplers:
  - name: S
    objects: [cube]
    region: {shape: polygon, vertices: [[0, 0], [0.4, 0], [0.4, 0.4], [0.2, 0.1], [0, 0.4]]}
    keep_out: [{shape: disk, center: [1, 2], radius: 0.1, frame: world}]
    reference_pos: [0.5, 0, 0.8]
    z_offset: 0.01
)";
  const auto config = buildFromYaml(kObjects + yaml);
  const std::string json = configToJson(*config);
  EXPECT_NE(json.find("\"max_attempts\": 5000, \"region\": {\"shape\": \"polygon\", \"vertices\": "
                      "[[0, 0], [0.4, 0], [0.4, 0.4], [0.2, 0.1], [0, 0.4]]}, \"keep_out\": "
                      "[{\"shape\": \"disk\", \"center\": [1, 2], \"radius\": 0.1, \"frame\": "
                      "\"world\"}], \"hides\": false}"),
            std::string::npos)
      << json;
  const SceneGenerator generator(config);
  const PreparedRequest request = generator.prepare(SampleRequest());
  const std::vector<SceneResult> out = generator.sampleScenes(request, 1, 1, 1);
  const std::vector<SamplerRegion> regions = samplerRegions(request, out[0]);
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_FALSE(regions[0].keepOut);
  ASSERT_EQ(regions[0].triangles.size(), 9u);  // five vertices, three triangles
  for (const Eigen::Vector3d& v : regions[0].triangles) {
    EXPECT_EQ(v.z(), 0.81);
    EXPECT_GE(v.x(), 0.5);
    EXPECT_LE(v.x(), 0.9);
  }
  EXPECT_TRUE(regions[1].keepOut);
  EXPECT_EQ(regions[1].triangles.size(), 3u * 48u);
  EXPECT_EQ(regions[1].triangles[0], Eigen::Vector3d(1, 2, 0.81));  // world: not moved
}

/// The validator's region test knows the shapes and the zones.
TEST(RegionSampler, ValidatorSeesShapesAndZones) {
  UniformSamplerParams p;
  p.region = RegionShape::disk(Eigen::Vector2d(0, 0), 0.3);
  p.keepOut.push_back({RegionShape::disk(Eigen::Vector2d(0.1, 0), 0.05), false});
  // A strip in the world frame, just left of the region (whose world x spans 0.7 .. 1.3).
  p.keepOut.push_back(
      {RegionShape::rectangle(Eigen::Vector2d(0.7, 0.75), Eigen::Vector2d(0.7, 1.3)), true});
  const auto cube = test::makeBox("cube", Eigen::Vector3d(0.06, 0.08, 0.1));  // radius 0.05
  const UniformRandomSampler sampler("S", p, {cube});
  const Eigen::Vector3d base(1, 1, 0.8);
  const auto outside = [&](double x, double y) {
    return distanceOutsideRegion(sampler, *cube, base, Eigen::Vector3d(x, y, 0.9));
  };
  EXPECT_EQ(outside(0.9, 1.0), 0.0);
  EXPECT_NEAR(outside(1.0, 1.25), 0.0, 1e-12);   // on the inset's edge
  EXPECT_NEAR(outside(1.0, 1.3), 0.05, 1e-12);   // on the region's edge
  EXPECT_NEAR(outside(1.15, 1.0), 0.05, 1e-12);  // its disk reaches 0.05 into the zone
  EXPECT_NEAR(outside(1.1, 1.0), 0.1, 1e-12);    // its centre in the zone
  EXPECT_NEAR(outside(0.8, 1.0), 0.0, 1e-12);    // touching the world strip
  EXPECT_NEAR(outside(0.78, 1.0), 0.02, 1e-12);  // 0.02 into it
}

}  // namespace
}  // namespace placement_samplers
