#pragma once

#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <condition_variable>
#include <map>
#include <optional>
#include <thread>
#include <memory>
#include <mutex>
#include <random>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <visualization_msgs/MarkerArray.h>

#include "placement_samplers/SamplePlacements.h"
#include "placement_samplers/scene_generator.hpp"

namespace placement_samplers {
namespace ros_interface {

/// The placement_server node: reads the configuration from its private namespace, serves
/// ~sample_placements and ~reload, broadcasts the first scene of each call as static tf frames
/// and publishes ~markers. It converts and wires; the sampling is the core library's.
class PlacementServer {
 public:
  /// @param privateHandle the node's private namespace, where the configuration lives
  explicit PlacementServer(const ros::NodeHandle& privateHandle);
  ~PlacementServer();

  /// Reads and builds the configuration, then advertises the services and topics.
  /// @throw ConfigError naming the full parameter path when the configuration is invalid
  void start();

  /// Service calls served at once (the configuration's `threads`).
  unsigned threads() const;

  /// Checks the master every @p period: when it comes back after a restart, registers the
  /// services and topics again and re-broadcasts the last scene.
  void watchMaster(const ros::WallDuration& period);

  bool sample(SamplePlacements::Request& request, SamplePlacements::Response& response);
  bool reload(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  /// Does nothing: a baseline for measuring the cost of a service call.
  bool ping(std_srvs::Empty::Request&, std_srvs::Empty::Response&) { return true; }

 private:
  std::shared_ptr<const SceneGenerator> generator() const;
  std::uint64_t nextSeed();
  /// A scene waiting to be broadcast by the publishing thread.
  struct PendingScene {
    std::shared_ptr<const SceneGenerator> generator;  // keeps the configuration alive
    PreparedRequest request;
    SceneResult scene;
  };
  void publishLoop();
  void publish(const PendingScene& pending);
  void advertise();
  void checkMaster(const ros::WallTimerEvent&);

  ros::NodeHandle privateHandle_;
  ros::ServiceServer sampleService_;
  ros::ServiceServer reloadService_;
  ros::ServiceServer pingService_;
  ros::Publisher markerPublisher_;
  std::unique_ptr<tf2_ros::StaticTransformBroadcaster> broadcaster_;

  mutable std::mutex generatorMutex_;  // guards generator_: a reload swaps it whole
  std::shared_ptr<const SceneGenerator> generator_;
  std::mutex seedMutex_;  // guards seedStream_
  std::mt19937_64 seedStream_;
  std::mutex publishMutex_;  // one scene's frames and markers at a time; guards the last ones
  std::map<std::string, geometry_msgs::TransformStamped> frames_;  // every frame sent, by child
  visualization_msgs::MarkerArray lastMarkers_;
  // Broadcasting takes tens of microseconds: a thread of its own does it, off the service
  // callback. Only the latest scene waits; an older one not yet sent is superseded.
  std::mutex pendingMutex_;
  std::condition_variable pendingReady_;
  std::optional<PendingScene> pending_;
  bool stopping_ = false;
  std::thread publisher_;
  ros::WallTimer masterTimer_;
  bool masterUp_ = true;
};

}  // namespace ros_interface
}  // namespace placement_samplers
