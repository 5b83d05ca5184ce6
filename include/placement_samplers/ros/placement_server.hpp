#pragma once

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <std_srvs/Trigger.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/TransformStamped.h>
#include <visualization_msgs/MarkerArray.h>

#include "placement_samplers/PlacedScene.h"
#include "placement_samplers/SamplePlacements.h"
#include "placement_samplers/ValidatePlacements.h"
#include "placement_samplers/ros/call_options.hpp"
#include "placement_samplers/ros/logger_services.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"

namespace XmlRpc {
class XmlRpcValue;
}

namespace placement_samplers {
namespace ros_interface {

class NodeDiagnostics;
class Reconfigure;
class RegionHandles;
class SampleAction;

/// The placement_server node: reads the configuration from its private namespace, serves
/// ~sample_placements, the ~sample action, ~reload and ~ping, shows the latest scene as tf
/// frames, ~markers, the latched ~scene and ~poses, reports its health on /diagnostics, takes
/// its top-level knobs from dynamic_reconfigure and its regions from handles in rviz. It
/// converts and wires; the sampling is the core library's.
///
/// Threads: sampling calls run on the global callback queue (the caller spins it with
/// threads() threads); goals of ~sample run on threads of their own (sample_action.hpp);
/// ~reload, ~ping, the action's and dynamic_reconfigure's messages and the diagnostics timer
/// have a queue and thread of their own, so they answer while every sampling thread is busy,
/// and every change of configuration runs there, one at a time; one more thread sends frames,
/// markers and the scene and re-sends the frames on /tf at tf_rate; one more watches the
/// master; the region handles' server has one of its own.
/// Niceness added to the threads that sample (and those they start), so that ~ping, ~reload,
/// the publishing thread and roscpp's network threads get a core at once during a heavy call.
constexpr int kSamplingNiceness = 10;

/// A batch whose first this many scenes all failed stops there and answers at once.
constexpr std::uint64_t kGiveUpProbeScenes = 32;

/// Scenes are shown (frames, markers, ~scene, ~poses rendered) at most this often; a call's scene
/// that a later call supersedes within it is not shown.
constexpr std::chrono::milliseconds kShowInterval{20};

/// A validation of this many poses or more gives its memory back to the system afterwards.
constexpr std::size_t kTrimAfterValidatedPoses = 10000;

class PlacementServer {
 public:
  /// @param privateHandle the node's private namespace, where the configuration lives
  explicit PlacementServer(const ros::NodeHandle& privateHandle);
  ~PlacementServer();

  /// Reads and builds the configuration, advertises the services and topics, and starts the
  /// light services' thread, the publishing thread and the master watch (checked every
  /// @p masterPeriod).
  /// @throw ConfigError naming the full parameter path when the configuration is invalid
  void start(const ros::WallDuration& masterPeriod = ros::WallDuration(1.0));

  /// Sampling calls served at once (the configuration's `threads`, read at start-up).
  unsigned threads() const { return threads_; }

  /// ~sample_placements: answer() as a service call.
  bool sample(SamplePlacements::Request& request, SamplePlacements::Response& response);
  /// The one path that samples a request, for the service, the ~sample action and the region
  /// handles' "sample now": the same request and seed give the same answer. Never throws:
  /// every error is in @p response.
  void answer(const SamplePlacements::Request& request, SamplePlacements::Response& response,
              CallOptions& options);
  /// The configuration being served.
  std::shared_ptr<const SceneGenerator> generator() const;
  /// Builds a configuration from @p tree (the private namespace's parameters, maybe changed)
  /// and serves it from the next call on, as ~reload does; what is shown of the old one goes,
  /// and the knobs and region handles show the new one. Changes of configuration run on the
  /// light services' thread, one at a time.
  /// @param reload a ~reload (its failure is the ERROR of /diagnostics until one succeeds)
  /// @return false with the configuration's error in @p message: the old one keeps serving
  bool serveTree(XmlRpc::XmlRpcValue& tree, bool reload, std::string& message);
  /// ~validate_placements: the verdict on given poses (validation_service.hpp).
  bool validate(ValidatePlacements::Request& request, ValidatePlacements::Response& response);
  bool reload(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  /// For tests: runs in sample() after sampling and before the scene is queued for showing.
  void setBeforeShowHook(std::function<void()> hook) { beforeShowHook_ = std::move(hook); }

  /// Does nothing: a baseline for measuring the cost of a service call.
  bool ping(std_srvs::Empty::Request&, std_srvs::Empty::Response&) { return true; }

 private:
  /// A successful scene, as the publishing thread shows it.
  struct ShownScene {
    std::shared_ptr<const SceneGenerator> generator;  // keeps the configuration alive
    PreparedRequest request;
    SceneResult scene;
    std::uint64_t seed = 0;
    std::string sampler;
  };
  /// What the publishing thread sends: the frames of the current scene, which it re-stamps.
  struct Shown {
    std::vector<geometry_msgs::TransformStamped> frames;
    visualization_msgs::MarkerArray markers;
    std::optional<PlacedScene> scene;
    geometry_msgs::PoseArray poses;  // ~poses; an empty frame_id before the first scene
  };

  std::uint64_t nextSeed();
  /// Queues @p scene of a successful call for the publishing thread, unless the configuration
  /// changed during the call (then @p response's message says it is not shown).
  void show(const std::shared_ptr<const SceneGenerator>& generator, PreparedRequest prepared,
            SceneResult scene, std::uint64_t seed, const std::string& sampler,
            SamplePlacements::Response& response);
  /// Starts the diagnostics' timer, the knobs, the region handles and the ~sample action
  /// (placement_server_live.cpp).
  void startLive(const std::shared_ptr<const SceneGenerator>& generator);
  /// Registers /diagnostics, the knobs and the region handles again, from the light thread
  /// (their callbacks run there). The ~sample action is not: its goals hold its server.
  void advertiseLive();
  void scheduleTrim(std::uint64_t placements);
  void advertise();
  void publishLoop();
  Shown render(const ShownScene& shown) const;
  void sendFrames(bool restamp);
  void watchLoop(ros::WallDuration period);

  ros::NodeHandle privateHandle_;
  ros::CallbackQueue lightQueue_;  // ~reload and ~ping
  ros::NodeHandle lightHandle_;    // the private namespace on lightQueue_
  std::unique_ptr<ros::AsyncSpinner> lightSpinner_;
  unsigned threads_ = 1;
  std::string defaultTfPrefix_;  // "<namespace>/<node name>/": used when tf_prefix is unset

  mutable std::mutex generatorMutex_;  // guards generator_: a reload swaps it whole
  std::shared_ptr<const SceneGenerator> generator_;
  std::mutex seedMutex_;  // guards seedStream_
  std::mt19937_64 seedStream_;

  // Guarded by publishMutex_: the handles and what the current scene shows.
  std::mutex publishMutex_;
  ros::ServiceServer sampleService_;
  ros::ServiceServer validateService_;
  ros::ServiceServer reloadService_;
  ros::ServiceServer pingService_;
  ros::Publisher markerPublisher_;
  ros::Publisher scenePublisher_;
  ros::Publisher posesPublisher_;
  LoggerServices loggerServices_;  // ~get_loggers that does not crash the node
  ros::Publisher tfPublisher_;
  ros::Publisher tfStaticPublisher_;
  Shown shown_;
  bool tfStatic_ = false;
  double tfRate_ = 10.0;

  // The publishing thread: only the latest scene waits; an older one not yet sent is
  // superseded. A reload clears what is shown.
  std::mutex pendingMutex_;
  std::condition_variable pendingReady_;
  std::optional<ShownScene> pending_;
  bool clearPending_ = false;
  // Freed memory of a large answer is returned to the kernel once roscpp has sent and freed it.
  std::uint64_t trimPlacements_ = 0;
  std::chrono::steady_clock::time_point trimAt_;
  bool stopping_ = false;
  std::thread publisher_;
  std::thread watcher_;
  std::function<void()> beforeShowHook_;

  // One change of configuration at a time (recursive: start() holds it while a component may
  // ask for one).
  std::recursive_mutex serveMutex_;
  std::unique_ptr<NodeDiagnostics> diagnostics_;
  std::unique_ptr<Reconfigure> reconfigure_;
  std::unique_ptr<RegionHandles> handles_;
  std::unique_ptr<SampleAction> action_;
};

}  // namespace ros_interface
}  // namespace placement_samplers
