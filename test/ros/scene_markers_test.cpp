// The markers of a scene without a master: region shapes and keep-out zones as triangles.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/ros/scene_markers.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

using visualization_msgs::Marker;

TEST(SceneMarkers, RegionShapesAndKeepOutZones) {
  const std::string yaml = R"(
objects:
  cube: {shape: box, size: [0.04, 0.04, 0.04]}
  can: {shape: cylinder, radius: 0.03, length: 0.1}
samplers:
  - {name: A, objects: [cube], x_range: [-0.1, 0.1], y_range: [-0.2, 0.2]}
  - name: B
    objects: [can]
    region: {shape: annulus, centre: [1, 0], inner_radius: 0.1, outer_radius: 0.3}
    keep_out:
      - {shape: polygon, vertices: [[0.9, 0], [1.1, 0], [1, 0.2]]}
      - {shape: disk, centre: [5, 5], radius: 0.2, frame: world}
    reference_pos: [0, 1, 0.8]
)";
  const SceneGenerator generator(buildSceneConfig(parseYaml(yaml, "test.yaml")));
  const PreparedRequest request = generator.prepare(SampleRequest());
  const std::vector<SceneResult> scenes = generator.sampleScenes(request, 1, 1, 1);
  ASSERT_TRUE(scenes[0].success);
  const visualization_msgs::MarkerArray array =
      makeSceneMarkers(request, scenes[0], "world", ros::Time(1.0));
  std::map<std::string, std::vector<const Marker*>> byNamespace;
  for (const Marker& m : array.markers) {
    byNamespace[m.ns].push_back(&m);
  }
  ASSERT_EQ(byNamespace["regions"].size(), 2u);
  EXPECT_EQ(byNamespace["regions"][0]->type, Marker::CUBE);  // robosuite's rectangle, as before
  const Marker& ring = *byNamespace["regions"][1];
  EXPECT_EQ(ring.type, Marker::TRIANGLE_LIST);
  EXPECT_EQ(ring.points.size(), 6u * 48u);  // two triangles per segment
  for (const geometry_msgs::Point& p : ring.points) {
    const double d = std::hypot(p.x - 1.0, p.y - 1.0);  // centre [1, 0] around [0, 1]
    EXPECT_GE(d, 0.1 - 1e-9);
    EXPECT_LE(d, 0.3 + 1e-9);
    EXPECT_EQ(p.z, 0.8);
  }
  ASSERT_EQ(byNamespace["keep_out"].size(), 2u);
  const Marker& triangle = *byNamespace["keep_out"][0];
  EXPECT_EQ(triangle.type, Marker::TRIANGLE_LIST);
  ASSERT_EQ(triangle.points.size(), 3u);
  EXPECT_NEAR(triangle.points[0].y, 1.0, 1e-12);  // in the sampler's frame: moved by [0, 1]
  EXPECT_GT(triangle.color.r, triangle.color.g);  // red
  const Marker& world = *byNamespace["keep_out"][1];
  EXPECT_EQ(world.points.size(), 3u * 48u);
  EXPECT_EQ(world.points[0].x, 5.0);  // the world zone's centre, not moved
  EXPECT_EQ(world.points[0].y, 5.0);
}

}  // namespace
}  // namespace ros_interface
}  // namespace placement_samplers
