// The markers of a scene without a master: region shapes and keep-out zones as triangles, what
// physics did to each object, the ground plane, relations as lines, and the scene as a
// PoseArray.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <string>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/ros/scene_markers.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

using visualization_msgs::Marker;

std::map<std::string, std::vector<const Marker*>> byNamespace(
    const visualization_msgs::MarkerArray& array) {
  std::map<std::string, std::vector<const Marker*>> out;
  for (const Marker& m : array.markers) {
    out[m.ns].push_back(&m);
  }
  return out;
}
/// The pointers point into the array: a temporary one would leave them dangling.
std::map<std::string, std::vector<const Marker*>> byNamespace(
    visualization_msgs::MarkerArray&& array) = delete;

/// The label whose text starts with @p name, or null.
const Marker* label(const visualization_msgs::MarkerArray& array, const std::string& name) {
  for (const Marker& m : array.markers) {
    if (m.ns == "labels" && m.text.rfind(name, 0) == 0) {
      return &m;
    }
  }
  return nullptr;
}

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

// A cube on a small table and a ball sampled beyond its edge (on_top of it, so in the air):
// settled, the ball falls and the cube stays.
const char* const kEdgeScene = R"(
physics: settle
objects:
  top: {shape: box, size: [0.2, 0.2, 0.05]}
  cube: {shape: box, size: [0.04, 0.04, 0.04]}
  ball: {shape: sphere, radius: 0.03}
  hidden_cube: {shape: box, size: [0.04, 0.04, 0.04]}
fixtures:
  - {name: table, object: top, position: [0, 0, 0.775]}
samplers:
  - {name: OnTable, objects: [cube], x_range: [0, 0], y_range: [0, 0], z_offset: 0.01,
     ensure_object_boundary_in_range: false, rotation: 0, sample_args: {reference: table}}
  - {name: OffEdge, objects: [ball], x_range: [0.3, 0.3], y_range: [0, 0],
     ensure_object_boundary_in_range: false, sample_args: {reference: table}}
hide: [hidden_cube]
)";

TEST(SceneMarkers, SettledSceneShowsWhatFellAndWhereItWasSampled) {
  const SceneGenerator generator(buildSceneConfig(parseYaml(kEdgeScene, "edge.yaml")));
  const PreparedRequest request = generator.prepare(SampleRequest());
  const SceneResult scene = generator.sampleScene(request, 3, 0);
  ASSERT_TRUE(scene.success) << scene.message;
  ASSERT_TRUE(scene.simulated);
  ASSERT_EQ(scene.physics.size(), 3u);
  const ObjectPlacement& ball = scene.placements[1];
  ASSERT_EQ(ball.name, "ball");
  ASSERT_TRUE(scene.physics[1].fallen);
  ASSERT_FALSE(scene.physics[0].fallen);
  ASSERT_LT(scene.physics[0].moved, 0.01);
  const Eigen::Vector3d sampled = scene.physics[1].sampledPosition;
  ASSERT_LT(ball.position.z(), 0.0);  // it fell past the table for a second

  const visualization_msgs::MarkerArray array =
      makeSceneMarkers(request, scene, "world", ros::Time(1.0));
  auto ns = byNamespace(array);
  // A faint copy of the ball where it was sampled; none of the cube, which stayed.
  ASSERT_EQ(ns["sampled"].size(), 1u);
  const Marker& ghost = *ns["sampled"][0];
  EXPECT_EQ(ghost.type, Marker::SPHERE);
  EXPECT_EQ(ghost.pose.position.x, sampled.x());
  EXPECT_EQ(ghost.pose.position.z, sampled.z());
  EXPECT_FLOAT_EQ(ghost.color.a, 0.3f);
  EXPECT_EQ(ghost.color.r, objectColour("ball").r);
  // A red wire box around the ball where it lies now, and an arrow from where it was sampled.
  ASSERT_EQ(ns["physics"].size(), 2u);
  const Marker& box = *ns["physics"][0];
  EXPECT_EQ(box.type, Marker::LINE_LIST);
  EXPECT_EQ(box.points.size(), 24u);
  EXPECT_EQ(box.pose.position.z, ball.position.z());
  EXPECT_GT(box.color.r, 0.9f);
  EXPECT_LT(box.color.g, 0.5f);
  const Marker& arrow = *ns["physics"][1];
  EXPECT_EQ(arrow.type, Marker::ARROW);
  ASSERT_EQ(arrow.points.size(), 2u);
  EXPECT_EQ(arrow.points[0].z, sampled.z());
  EXPECT_EQ(arrow.points[1].z, ball.position.z());
  // The ball's label says so and stays above the sampled pose, in view; the cube's is its name.
  const Marker* ballLabel = label(array, "ball");
  ASSERT_NE(ballLabel, nullptr);
  std::ostringstream moved;
  moved << std::fixed << std::setprecision(3) << scene.physics[1].moved;
  EXPECT_EQ(ballLabel->text, "ball: fell, moved " + moved.str() + " m");
  EXPECT_EQ(ballLabel->pose.position.x, sampled.x());
  EXPECT_NEAR(ballLabel->pose.position.z, sampled.z() + 0.03 + 0.03, 1e-12);
  EXPECT_GT(ballLabel->color.r, 0.9f);
  ASSERT_NE(label(array, "cube"), nullptr);
  EXPECT_EQ(label(array, "cube")->text, "cube");
  EXPECT_EQ(label(array, "hidden_cube"), nullptr);
  EXPECT_EQ(ns.count("ground"), 0u);  // no ground_z
}

// Under check the answer keeps the sampled poses: an object beyond the tolerances gets the
// outline and a label with the numbers, and nothing is drawn twice.
TEST(SceneMarkers, CheckedObjectBeyondTheTolerancesIsOutlined) {
  const SceneGenerator generator(buildSceneConfig(parseYaml(kEdgeScene, "edge.yaml")));
  SampleRequest none;
  none.physics = PhysicsMode::None;
  const PreparedRequest request = generator.prepare(none);
  SceneResult scene = generator.sampleScene(request, 3, 0);
  ASSERT_TRUE(scene.success);
  ASSERT_FALSE(scene.simulated);
  const auto unsimulated = makeSceneMarkers(request, scene, "world", ros::Time(1.0));
  EXPECT_EQ(byNamespace(unsimulated).count("physics"), 0u);

  // As a check would report it: the cube moved 5 cm and turned 0.3 rad, the ball stayed.
  scene.simulated = true;
  scene.physicsMode = PhysicsMode::Check;
  scene.physics.resize(3);
  scene.physics[0].moved = 0.05;
  scene.physics[0].turned = 0.3;
  scene.physics[1].moved = 0.009;  // under the 0.01 m tolerance
  const visualization_msgs::MarkerArray array =
      makeSceneMarkers(request, scene, "world", ros::Time(1.0));
  auto ns = byNamespace(array);
  EXPECT_EQ(ns.count("sampled"), 0u);
  ASSERT_EQ(ns["physics"].size(), 1u);
  EXPECT_EQ(ns["physics"][0]->type, Marker::LINE_LIST);
  EXPECT_EQ(ns["physics"][0]->pose.position.x, scene.placements[0].position.x());
  // The wire box holds the cube: half its diagonal plus 5 mm across, its height plus 5 mm.
  double maxX = -1.0;
  double maxZ = -1.0;
  for (const geometry_msgs::Point& p : ns["physics"][0]->points) {
    maxX = std::max(maxX, p.x);
    maxZ = std::max(maxZ, p.z);
  }
  EXPECT_NEAR(maxX, std::hypot(0.02, 0.02) + 0.005, 1e-12);
  EXPECT_NEAR(maxZ, 0.02 + 0.005, 1e-12);
  EXPECT_EQ(label(array, "cube")->text, "cube: moved 0.050 m, turned 0.30 rad");
  EXPECT_EQ(label(array, "ball")->text, "ball");
}

TEST(SceneMarkers, GroundZIsDrawnUnderTheObjectsAndRegions) {
  const std::string yaml = R"(
ground_z: 0.8
objects:
  cube: {shape: box, size: [0.04, 0.04, 0.04]}
samplers:
  - {name: A, objects: [cube], x_range: [-0.1, 0.3], y_range: [-0.1, 0.1],
     reference_pos: [0, 0, 0.8]}
)";
  const SceneGenerator generator(buildSceneConfig(parseYaml(yaml, "ground.yaml")));
  const PreparedRequest request = generator.prepare(SampleRequest());
  const SceneResult scene = generator.sampleScene(request, 1, 0);
  ASSERT_TRUE(scene.success);
  const auto array = makeSceneMarkers(request, scene, "world", ros::Time(1.0));
  auto ns = byNamespace(array);
  ASSERT_EQ(ns["ground"].size(), 1u);
  const Marker& ground = *ns["ground"][0];
  EXPECT_EQ(ground.type, Marker::CUBE);
  // Its top just under 0.8, so that the region drawn at 0.8 stays visible.
  const double top = ground.pose.position.z + ground.scale.z / 2;
  EXPECT_LT(top, 0.8);
  EXPECT_GT(top, 0.8 - 0.005);
  // The region [-0.1, 0.3] x [-0.1, 0.1] (the cube inside it) and 0.25 m around it.
  EXPECT_NEAR(ground.pose.position.x, 0.1, 1e-12);
  EXPECT_NEAR(ground.pose.position.y, 0.0, 1e-12);
  EXPECT_NEAR(ground.scale.x, 0.4 + 0.5, 1e-12);
  EXPECT_NEAR(ground.scale.y, 0.2 + 0.5, 1e-12);
}

TEST(SceneMarkers, RelationsAreLinesColouredBySatisfied) {
  const std::string yaml = R"(
objects:
  plate: {shape: cylinder, radius: 0.1, length: 0.02}
  cube: {shape: box, size: [0.04, 0.04, 0.04]}
samplers:
  - {name: P, objects: [plate], x_range: [-0.1, 0.1], y_range: [-0.1, 0.1]}
  - {name: C, objects: [cube], x_range: [-0.5, 0.5], y_range: [-0.5, 0.5],
     relations: [{next_to: plate, side: left, distance: [0.0, 0.05]}]}
)";
  const SceneGenerator generator(buildSceneConfig(parseYaml(yaml, "relations.yaml")));
  const PreparedRequest request = generator.prepare(SampleRequest());
  SceneResult scene = generator.sampleScene(request, 1, 0);
  ASSERT_TRUE(scene.success);
  // The array kept: byNamespace() points into it.
  const visualization_msgs::MarkerArray array =
      makeSceneMarkers(request, scene, "world", ros::Time(1.0));
  auto ns = byNamespace(array);
  ASSERT_EQ(ns["relations"].size(), 1u);
  const Marker& line = *ns["relations"][0];
  EXPECT_EQ(line.type, Marker::LINE_LIST);
  ASSERT_EQ(line.points.size(), 2u);
  EXPECT_EQ(line.points[0].x, scene.placements[1].position.x());  // from the cube
  EXPECT_EQ(line.points[1].y, scene.placements[0].position.y());  // to the plate
  EXPECT_GT(line.color.g, line.color.r);                          // green: it holds
  // The cube moved to the plate's other side: red.
  scene.placements[1].position.head<2>() =
      2 * scene.placements[0].position.head<2>() - scene.placements[1].position.head<2>();
  const visualization_msgs::MarkerArray moved =
      makeSceneMarkers(request, scene, "world", ros::Time(1.0));
  ns = byNamespace(moved);
  ASSERT_EQ(ns["relations"].size(), 1u);
  EXPECT_GT(ns["relations"][0]->color.r, ns["relations"][0]->color.g);
}

TEST(SceneMarkers, PoseArrayHoldsThePlacedObjectsInSamplingOrder) {
  const SceneGenerator generator(buildSceneConfig(parseYaml(kEdgeScene, "edge.yaml")));
  SampleRequest none;
  none.physics = PhysicsMode::None;
  const PreparedRequest request = generator.prepare(none);
  const SceneResult scene = generator.sampleScene(request, 3, 0);
  ASSERT_TRUE(scene.success);
  const geometry_msgs::PoseArray poses = makeScenePoses(scene, "table_frame", ros::Time(2.0));
  EXPECT_EQ(poses.header.frame_id, "table_frame");
  EXPECT_EQ(poses.header.stamp, ros::Time(2.0));
  ASSERT_EQ(poses.poses.size(), 2u);  // the hidden cube is left out
  for (std::size_t i = 0; i < 2; ++i) {
    const ObjectPlacement& p = scene.placements[i];
    EXPECT_EQ(poses.poses[i].position.x, p.position.x());
    EXPECT_EQ(poses.poses[i].position.z, p.position.z());
    EXPECT_EQ(poses.poses[i].orientation.z, p.orientation.z());
    EXPECT_EQ(poses.poses[i].orientation.w, p.orientation.w());
  }
  EXPECT_TRUE(makeScenePoses(SceneResult(), "world", ros::Time(2.0)).poses.empty());
}

}  // namespace
}  // namespace ros_interface
}  // namespace placement_samplers
