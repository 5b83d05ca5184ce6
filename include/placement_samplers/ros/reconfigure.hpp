#pragma once

#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>

#include <boost/thread/recursive_mutex.hpp>
#include <functional>
#include <memory>
#include <string>

#include "placement_samplers/PlacementServerConfig.h"
#include "placement_samplers/sampling/scene_config.hpp"

namespace XmlRpc {
class XmlRpcValue;
}

namespace placement_samplers {
namespace ros_interface {

/// The top-level knobs of cfg/PlacementServer.cfg with the configuration's values.
PlacementServerConfig knobsOf(const SceneConfig& config);

/// Sets the knobs' parameters in @p tree (the private namespace's parameters) to @p knobs.
void setKnobs(const PlacementServerConfig& knobs, XmlRpc::XmlRpcValue& tree);

/// dynamic_reconfigure for the node's top-level knobs (collision_check, collision_margin,
/// max_attempts, physics, physics_seconds, the physics tolerances, tf_rate,
/// max_request_seconds), in the node's private namespace. A change is applied as a ~reload of
/// the parameters with the knobs set; dynamic_reconfigure then writes them to the parameter
/// server. A value the configuration refuses leaves every knob as it was: the answer holds the
/// old values, and the configuration's message is logged.
class Reconfigure {
 public:
  /// Serves the configuration's parameters with @p knobs set; false with the configuration's
  /// error in the string when it is refused.
  using Apply = std::function<bool(const PlacementServerConfig& knobs, std::string& error)>;

  /// @param handle the private namespace, on the queue the changes are to run on
  Reconfigure(const ros::NodeHandle& handle, Apply apply);

  /// Starts the server (it writes each knob's value to the parameter server) showing @p served.
  void start(const SceneConfig& served);
  /// Serves again, with the knobs shown (after a master restart: the new master has none of
  /// the old one's services and parameters). From the thread of the handle's queue.
  void restart();
  /// After a ~reload or a region handle: shows the knobs of the configuration now served.
  void show(const SceneConfig& served);

 private:
  void onChange(PlacementServerConfig& config, std::uint32_t level);

  ros::NodeHandle handle_;
  Apply apply_;
  boost::recursive_mutex mutex_;  // the server's: show() takes it, as its callback does
  std::unique_ptr<dynamic_reconfigure::Server<PlacementServerConfig>> server_;
  PlacementServerConfig served_;  // the knobs of the configuration served
  bool inCallback_ = false;
};

}  // namespace ros_interface
}  // namespace placement_samplers
