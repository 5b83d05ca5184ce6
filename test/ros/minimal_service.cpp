// A bare roscpp service, the control of scripts/soak --target minimal: ~ping (std_srvs/Empty)
// served by an AsyncSpinner with ~threads threads (default 2), as placement_server serves its
// services, and nothing else: no configuration, no timers, no publishers. Under the same client
// churn, an error it shows too is roscpp's or rospy's, not the node's.
#include <ros/ros.h>
#include <std_srvs/Empty.h>

namespace {

bool ping(std_srvs::Empty::Request&, std_srvs::Empty::Response&) { return true; }

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "minimal_service");
  ros::NodeHandle privateHandle("~");
  int threads = privateHandle.param("threads", 2);
  if (threads < 1 || threads > 64) {
    ROS_FATAL("minimal_service: ~threads must be 1..64, got %d", threads);
    return 1;
  }
  ros::ServiceServer service = privateHandle.advertiseService("ping", &ping);
  ros::AsyncSpinner spinner(static_cast<uint32_t>(threads));
  spinner.start();
  ros::waitForShutdown();
  return 0;
}
