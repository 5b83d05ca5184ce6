// Two instances of the node in namespaces robot1 and robot2 (launch/placement_server.launch
// with ns:=...): their frames and markers are their own, seen by a real listener.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <mutex>

#include "node_test_helpers.hpp"

namespace {

using namespace placement_samplers;
using placement_samplers::test::seeded;
using placement_samplers::test::waitFor;

TEST(Namespaces, InstancesHaveTheirOwnFramesAndMarkers) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ros::NodeHandle nh;
  std::mutex mutex;
  std::map<std::string, visualization_msgs::MarkerArray> markers;
  std::vector<ros::Subscriber> subscribers;
  std::map<std::string, geometry_msgs::Point> cube;
  for (const std::string robot : {"robot1", "robot2"}) {
    const std::string node = "/" + robot + "/placement_server";
    ASSERT_TRUE(ros::service::waitForService(node + "/sample_placements", ros::Duration(30.0)));
    subscribers.push_back(nh.subscribe<visualization_msgs::MarkerArray>(
        node + "/markers", 5, [&, robot](const visualization_msgs::MarkerArray::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          markers[robot] = *m;
        }));
    // Different seeds: the two cubes stand in different places.
    const SamplePlacements srv =
        test::callService(node + "/sample_placements", seeded(robot == "robot1" ? 1 : 2));
    ASSERT_TRUE(srv.response.success) << srv.response.message;
    cube[robot] = test::byName(srv.response.scenes[0]).at("cube").pose.position;
  }
  ASSERT_NE(cube["robot1"], cube["robot2"]);

  for (const std::string robot : {"robot1", "robot2"}) {
    // The default tf prefix is the node's namespace and name.
    const std::string frame = robot + "/placement_server/cube";
    geometry_msgs::Point seen;
    EXPECT_TRUE(waitFor(
        [&] {
          try {
            const auto t = buffer.lookupTransform("world", frame, ros::Time(0));
            seen.x = t.transform.translation.x;
            seen.y = t.transform.translation.y;
            seen.z = t.transform.translation.z;
            return seen == cube[robot];
          } catch (const tf2::TransformException&) {
            return false;
          }
        },
        10.0))
        << frame << " is not where " << robot << " put its cube";
    // Each instance's markers show its own cube.
    EXPECT_TRUE(waitFor(
        [&] {
          std::lock_guard<std::mutex> lock(mutex);
          for (const auto& m : markers[robot].markers) {
            if (m.ns == "objects" && m.pose.position == cube[robot]) {
              return true;
            }
          }
          return false;
        },
        10.0))
        << robot;
  }
  // No frame without a namespace: the instances share nothing.
  EXPECT_FALSE(buffer._frameExists("placement_server/cube"));
  EXPECT_FALSE(buffer._frameExists("placement/cube"));
}

}  // namespace

int main(int argc, char** argv) {
  return placement_samplers::test::runNodeTests(argc, argv, "namespaces_test");
}
