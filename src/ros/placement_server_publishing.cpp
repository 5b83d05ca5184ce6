// What the node shows and where it is registered: advertising its services and topics, the
// publishing thread (the current scene's frames, markers, ~scene and ~poses) and the master
// watch. Part of PlacementServer (placement_server.cpp holds the service callbacks).
#include <tf2_msgs/TFMessage.h>

#include <chrono>

#include "placement_samplers/process/malloc_tuning.hpp"
#include "placement_samplers/ros/conversions.hpp"
#include "placement_samplers/ros/node_diagnostics.hpp"
#include "placement_samplers/ros/placement_server.hpp"
#include "placement_samplers/ros/scene_markers.hpp"
#include "ros/thread_priority.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

tf2_msgs::TFMessage tfMessage(const std::vector<geometry_msgs::TransformStamped>& frames) {
  tf2_msgs::TFMessage message;
  message.transforms = frames;
  return message;
}

/// The master's identity: roscore sets /run_id anew each time it starts.
std::string masterRunId() {
  std::string id;
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = "/run_id";
  if (ros::master::execute("getParam", args, result, payload, false) &&
      payload.getType() == XmlRpc::XmlRpcValue::TypeString) {
    id = static_cast<std::string>(payload);
  }
  return id;
}

}  // namespace

void PlacementServer::advertise() {
  std::lock_guard<std::mutex> lock(publishMutex_);
  // Dropping the old handles first unregisters them, so the new ones register afresh.
  sampleService_.shutdown();
  validateService_.shutdown();
  reloadService_.shutdown();
  pingService_.shutdown();
  markerPublisher_.shutdown();
  scenePublisher_.shutdown();
  posesPublisher_.shutdown();
  tfPublisher_.shutdown();
  tfStaticPublisher_.shutdown();
  ros::NodeHandle global;
  tfPublisher_ = global.advertise<tf2_msgs::TFMessage>("/tf", 100);
  tfStaticPublisher_ = global.advertise<tf2_msgs::TFMessage>("/tf_static", 100, true);
  markerPublisher_ = privateHandle_.advertise<visualization_msgs::MarkerArray>("markers", 1, true);
  scenePublisher_ = privateHandle_.advertise<PlacedScene>("scene", 1, true);
  posesPublisher_ = privateHandle_.advertise<geometry_msgs::PoseArray>("poses", 1, true);
  sampleService_ =
      privateHandle_.advertiseService("sample_placements", &PlacementServer::sample, this);
  validateService_ =
      privateHandle_.advertiseService("validate_placements", &PlacementServer::validate, this);
  reloadService_ = lightHandle_.advertiseService("reload", &PlacementServer::reload, this);
  pingService_ = lightHandle_.advertiseService("ping", &PlacementServer::ping, this);
  loggerServices_.advertise(lightHandle_);
  // Latched topics carry the current scene to whoever subscribes after a master restart.
  if (!shown_.markers.markers.empty()) {
    markerPublisher_.publish(shown_.markers);
  }
  if (shown_.scene) {
    scenePublisher_.publish(*shown_.scene);
  }
  if (!shown_.poses.header.frame_id.empty()) {
    posesPublisher_.publish(shown_.poses);
  }
  if (tfStatic_ && !shown_.frames.empty()) {
    tfStaticPublisher_.publish(tfMessage(shown_.frames));
  }
}

void PlacementServer::watchLoop(ros::WallDuration period) {
  // A thread of its own: the check must run while every service thread is busy. A master that
  // restarted between two checks is up both times: its /run_id tells it is a new one.
  bool up = true;
  std::string runId = masterRunId();
  const auto step = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(period.toSec()));
  std::unique_lock<std::mutex> lock(pendingMutex_);
  while (!stopping_) {
    // Shares the condition with the publishing thread: the predicate ignores its wake-ups.
    if (pendingReady_.wait_until(lock, std::chrono::steady_clock::now() + step,
                                 [this] { return stopping_; })) {
      return;
    }
    lock.unlock();
    const bool now = ros::master::check();
    const std::string id = now ? masterRunId() : std::string();
    const bool restarted = now && up && !id.empty() && !runId.empty() && id != runId;
    if (now && !id.empty()) {
      runId = id;
    }
    if (restarted) {
      ROS_WARN_STREAM(ros::this_node::getName()
                      << ": the master restarted (new run_id); registering services and topics "
                         "again");
      advertise();
      advertiseLive();
    } else if (now && !up) {
      ROS_WARN_STREAM(ros::this_node::getName()
                      << ": the master is back; registering services and topics again");
      advertise();
      advertiseLive();
    } else if (!now && up) {
      ROS_WARN_STREAM(ros::this_node::getName()
                      << ": lost the master; waiting for it to come back");
    }
    up = now;
    if (diagnostics_) {
      diagnostics_->setMasterUp(up);
    }
    lock.lock();
  }
}

PlacementServer::Shown PlacementServer::render(const ShownScene& shown) const {
  const SceneConfig& config = shown.generator->config();
  const std::string prefix = config.tfPrefix.value_or(defaultTfPrefix_);
  const ros::Time now = ros::Time::now();
  Shown out;
  out.frames = toTransforms(shown.scene, shown.request.fixtures, config.frameId, prefix, now);
  out.markers = makeSceneMarkers(shown.request, shown.scene, config.frameId, now);
  out.poses = makeScenePoses(shown.scene, config.frameId, now);
  PlacedScene scene;
  scene.header.frame_id = config.frameId;
  scene.header.stamp = now;
  scene.seed = shown.seed;
  scene.sampler = shown.sampler;
  scene.tf_prefix = prefix;
  scene.placements = toSceneMsg(shown.scene).placements;
  for (const FixtureSpec& f : shown.request.fixtures) {
    scene.fixtures.push_back(toFixtureMsg(f));
  }
  out.scene = std::move(scene);
  return out;
}

void PlacementServer::sendFrames(bool restamp) {
  // Called with publishMutex_ held.
  if (shown_.frames.empty()) {
    return;
  }
  if (tfStatic_) {
    tfStaticPublisher_.publish(tfMessage(shown_.frames));
    return;
  }
  if (restamp) {
    const ros::Time now = ros::Time::now();
    for (auto& frame : shown_.frames) {
      frame.header.stamp = now;
    }
  }
  tfPublisher_.publish(tfMessage(shown_.frames));
}

void PlacementServer::publishLoop() {
  // Rendering a scene competes with the next call, not with ~ping.
  lowerThreadPriority();
  using Clock = std::chrono::steady_clock;
  Clock::time_point nextTick = Clock::now();
  Clock::time_point showNotBefore = nextTick;
  std::unique_lock<std::mutex> lock(pendingMutex_);
  for (;;) {
    pendingReady_.wait_until(lock, nextTick,
                             [this] { return stopping_ || pending_ || clearPending_; });
    if (stopping_) {
      return;
    }
    // Calls in quick succession: only the latest scene is shown, at most every kShowInterval,
    // so rendering does not take the cores from the calls (a reload's clearing does not wait).
    if (pending_ && !clearPending_ && Clock::now() < showNotBefore) {
      pendingReady_.wait_until(lock, showNotBefore, [this] { return stopping_ || clearPending_; });
      if (stopping_) {
        return;
      }
    }
    std::optional<ShownScene> next = std::move(pending_);
    pending_.reset();
    const bool clear = clearPending_;
    clearPending_ = false;
    std::uint64_t trim = 0;
    if (trimPlacements_ > 0 && Clock::now() >= trimAt_) {
      trim = trimPlacements_;
      trimPlacements_ = 0;
    }
    lock.unlock();
    if (trim > 0) {
      trimAfterBatch(trim);
    }

    std::optional<Shown> rendered;
    if (next) {
      rendered = render(*next);
      showNotBefore = Clock::now() + kShowInterval;
    }
    {
      std::lock_guard<std::mutex> publishLock(publishMutex_);
      if (rendered) {
        // Only the current scene's frames are held: frames of an older one are not re-sent.
        shown_ = std::move(*rendered);
        sendFrames(false);
        markerPublisher_.publish(shown_.markers);
        scenePublisher_.publish(*shown_.scene);
        posesPublisher_.publish(shown_.poses);
      } else if (clear) {
        shown_.frames.clear();
        shown_.markers = makeClearMarkers();
        markerPublisher_.publish(shown_.markers);
        shown_.poses =
            makeScenePoses(SceneResult(), generator()->config().frameId, ros::Time::now());
        posesPublisher_.publish(shown_.poses);
        // ~scene too: a late subscriber must not take the old configuration's scene for current.
        PlacedScene empty;
        empty.header.frame_id = shown_.poses.header.frame_id;
        empty.header.stamp = shown_.poses.header.stamp;
        empty.tf_prefix = generator()->config().tfPrefix.value_or(defaultTfPrefix_);
        shown_.scene = empty;
        scenePublisher_.publish(empty);
        if (tfStatic_) {
          tfStaticPublisher_.publish(tf2_msgs::TFMessage());
        }
      } else if (!tfStatic_) {
        sendFrames(true);
      }
    }
    const Clock::time_point now = Clock::now();
    if (now >= nextTick) {
      double rate = 10.0;
      {
        std::lock_guard<std::mutex> publishLock(publishMutex_);
        rate = tfRate_;
      }
      nextTick = now + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double>(1.0 / rate));
    }
    lock.lock();
  }
}

}  // namespace ros_interface
}  // namespace placement_samplers
