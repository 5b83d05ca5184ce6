#pragma once
// Helpers of the node tests: calls, requests and waiting for a condition.

#include <gtest/gtest.h>
#include <ros/ros.h>

#include <functional>
#include <map>
#include <string>

#include "placement_samplers/SamplePlacements.h"

namespace placement_samplers {
namespace test {

/// Calls @p service (it must answer at the transport level).
inline SamplePlacements callService(const std::string& service,
                                    const SamplePlacements::Request& request) {
  SamplePlacements srv;
  srv.request = request;
  EXPECT_TRUE(ros::service::call(service, srv)) << "the service call itself failed";
  return srv;
}

inline SamplePlacements::Request seeded(std::uint64_t seed, std::uint32_t scenes = 1) {
  SamplePlacements::Request r;
  r.seed = seed;
  r.num_scenes = scenes;
  return r;
}

inline std::map<std::string, Placement> byName(const Scene& scene) {
  std::map<std::string, Placement> out;
  for (const auto& p : scene.placements) {
    out[p.name] = p;
  }
  return out;
}

/// A box over the whole table top: nothing on the table can avoid it.
inline Fixture tableCoveringWall() {
  Fixture wall;
  wall.name = "wall";
  wall.shape.type = shape_msgs::SolidPrimitive::BOX;
  wall.shape.dimensions = {2.0, 2.0, 0.5};
  wall.pose.position.z = 0.8;
  wall.pose.orientation.w = 1.0;
  return wall;
}

/// A small box fixture called @p name at (@p x, 0, 1).
inline Fixture boxFixture(const std::string& name, double x) {
  Fixture box;
  box.name = name;
  box.shape.type = shape_msgs::SolidPrimitive::BOX;
  box.shape.dimensions = {0.1, 0.1, 0.1};
  box.pose.position.x = x;
  box.pose.position.z = 1.0;
  box.pose.orientation.w = 1.0;
  return box;
}

/// Polls @p condition every 20 ms until it holds or @p seconds pass; true when it held.
inline bool waitFor(const std::function<bool()>& condition, double seconds) {
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::WallTime::now() < until) {
    if (condition()) {
      return true;
    }
    ros::WallDuration(0.02).sleep();
  }
  return condition();
}

/// main() of a node test: gtest, a ROS node called @p name and two spinner threads (for
/// subscriptions and tf listeners), then RUN_ALL_TESTS.
inline int runNodeTests(int argc, char** argv, const char* name) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, name);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}

}  // namespace test
}  // namespace placement_samplers
