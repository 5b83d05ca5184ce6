#pragma once

#include <actionlib/server/action_server.h>
#include <ros/ros.h>

#include <chrono>
#include <condition_variable>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "placement_samplers/SamplePlacements.h"
#include "placement_samplers/SampleScenesAction.h"
#include "placement_samplers/ros/call_options.hpp"

namespace placement_samplers {
namespace ros_interface {

/// Feedback is sent at most this often per goal.
constexpr std::chrono::milliseconds kFeedbackInterval{100};

/// The service request with a goal's fields (the same names).
SamplePlacements::Request toServiceRequest(const SampleScenesGoal& goal);
/// The result with a service response's fields.
SampleScenesResult toResult(const SamplePlacements::Response& response);

/// The ~sample action (placement_samplers/SampleScenes): a SamplePlacements request as a goal,
/// sampled by the same function as the service, with feedback (scenes done and failed, elapsed
/// and remaining seconds) at most every kFeedbackInterval, and cancel between scenes.
///
/// Each goal runs on a thread of its own; at most `threads` goals sample at once and the others
/// wait (a cancel reaches them while they wait). With threads 1 a new goal preempts the one
/// running, which answers the scenes it has done. Terminal states: SUCCEEDED when every scene
/// placed, ABORTED when the request was refused or a scene failed, PREEMPTED (or RECALLED)
/// when cancelled before the last scene; the result says which scenes it holds and why.
class SampleAction {
 public:
  /// Samples a request as PlacementServer::answer() does.
  using Sampler = std::function<void(const SamplePlacements::Request&, SamplePlacements::Response&,
                                     CallOptions&)>;

  /// @param handle the node's private namespace on the queue the action's messages run on
  /// @param threads goals sampled at once (1: a new goal preempts the running one)
  SampleAction(const ros::NodeHandle& handle, unsigned threads, Sampler sampler);
  /// Cancels every goal and waits for their threads.
  ~SampleAction();

  /// Advertises ~sample and starts sending feedback.
  void start();

  /// Registers ~sample again (a new master): when no goal is active and the last result went
  /// out kResultGrace ago (a goal's handle and its result belong to the registered server;
  /// unregistering drops a result still queued for sending). Call it on the queue of
  /// @p handle, where goals arrive.
  void restart();

  /// How long a result gets to reach its client before ~sample registers again.
  static constexpr std::chrono::milliseconds kResultGrace{1000};

 private:
  using Server = actionlib::ActionServer<SampleScenesAction>;
  using GoalHandle = Server::GoalHandle;
  struct Goal;

  /// A new server, the old one's registrations dropped; on the handle's queue.
  void makeServer();
  /// restart() on the handle's queue after @p delay; mutex_ held.
  void scheduleRestart(std::chrono::steady_clock::duration delay);
  void onGoal(GoalHandle handle);
  void onCancel(GoalHandle handle);
  void run(const std::shared_ptr<Goal>& goal);
  void feedbackLoop();
  /// Publishes @p goal's progress while it samples; the @p last one only a feedback interval
  /// after the one before.
  void sendFeedback(Goal& goal, bool last);

  ros::NodeHandle handle_;
  unsigned threads_;
  Sampler sampler_;
  std::unique_ptr<Server> server_;

  std::mutex mutex_;  // guards what follows
  std::condition_variable changed_;
  std::list<std::shared_ptr<Goal>> goals_;  // accepted and not yet finished, oldest first
  unsigned running_ = 0;                    // goals sampling now
  bool stopping_ = false;
  bool restartPending_ = false;                       // restart() waits for the active goals
  std::chrono::steady_clock::time_point lastResult_;  // when the last goal finished
  ros::WallTimer restartTimer_;  // restart() again once the last result had its time
  std::thread feedback_;
};

}  // namespace ros_interface
}  // namespace placement_samplers
