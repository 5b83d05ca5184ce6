#include <ros/ros.h>

#include "placement_samplers/malloc_tuning.hpp"
#include "placement_samplers/ros/placement_server.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "placement_server");
  placement_samplers::keepFreedMemoryForBatches();
  placement_samplers::ros_interface::PlacementServer server(ros::NodeHandle("~"));
  try {
    server.start();
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("placement_server: invalid configuration: " << e.what());
    return 1;
  }
  server.watchMaster(ros::WallDuration(1.0));
  ros::AsyncSpinner spinner(server.threads());
  spinner.start();
  ros::waitForShutdown();
  return 0;
}
