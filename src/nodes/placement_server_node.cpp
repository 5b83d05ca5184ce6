#include <ros/ros.h>

#include <csignal>

#include "placement_samplers/process/malloc_tuning.hpp"
#include "placement_samplers/ros/placement_server.hpp"

namespace {

// SIGTERM (systemd, docker stop, roslaunch's escalation) shuts down as SIGINT does: the node
// unregisters its services instead of leaving the master pointing at a dead node.
void requestShutdown(int) { ros::requestShutdown(); }

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "placement_server");
  std::signal(SIGTERM, requestShutdown);
  placement_samplers::keepFreedMemoryForBatches();
  placement_samplers::ros_interface::PlacementServer server(ros::NodeHandle("~"));
  try {
    server.start();
  } catch (const std::exception& e) {
    // Named as the node runs (namespace, remapped name), as the parameter paths in e.what().
    ROS_FATAL_STREAM(ros::this_node::getName() << ": invalid configuration: " << e.what());
    return 1;
  }
  ros::AsyncSpinner spinner(server.threads());
  spinner.start();
  ros::waitForShutdown();
  return 0;
}
