#include "placement_samplers/ros/sample_action.hpp"

#include <algorithm>
#include <vector>

#include "ros/thread_priority.hpp"

namespace placement_samplers {
namespace ros_interface {

SamplePlacements::Request toServiceRequest(const SampleScenesGoal& goal) {
  SamplePlacements::Request r;
  r.sampler = goal.sampler;
  r.seed = goal.seed;
  r.num_scenes = goal.num_scenes;
  r.first_scene = goal.first_scene;
  r.fixtures = goal.fixtures;
  r.reference = goal.reference;
  r.reference_point = goal.reference_point;
  r.use_reference_point = goal.use_reference_point;
  r.on_top = goal.on_top;
  r.collision_check = goal.collision_check;
  r.max_attempts = goal.max_attempts;
  r.dry_run = goal.dry_run;
  r.physics = goal.physics;
  return r;
}

SampleScenesResult toResult(const SamplePlacements::Response& response) {
  SampleScenesResult r;
  r.success = response.success;
  r.message = response.message;
  r.seed = response.seed;
  r.frame_id = response.frame_id;
  r.scenes = response.scenes;
  return r;
}

/// A goal from its acceptance until its thread is joined.
struct SampleAction::Goal {
  GoalHandle handle;
  SamplePlacements::Request request;
  std::uint64_t total = 1;  // scenes asked for
  SampleProgress progress;
  // Guarded by SampleAction::mutex_.
  bool preempted = false;  // cancelled by a newer goal (threads 1)
  bool done = false;       // its result is sent: the thread may be joined
  std::thread thread;
  // Guarded by feedbackMutex: feedback goes only while the goal samples, never after its result.
  std::mutex feedbackMutex;
  bool sampling = false;
  std::chrono::steady_clock::time_point started;
  std::chrono::steady_clock::time_point lastSent;
};

SampleAction::SampleAction(const ros::NodeHandle& handle, unsigned threads, Sampler sampler)
    : handle_(handle), threads_(std::max(1u, threads)), sampler_(std::move(sampler)) {}

SampleAction::~SampleAction() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    restartTimer_.stop();
    for (const auto& goal : goals_) {
      goal->progress.cancel = true;
    }
  }
  changed_.notify_all();
  if (feedback_.joinable()) {
    feedback_.join();
  }
  for (const auto& goal : goals_) {  // no thread adds goals any more
    if (goal->thread.joinable()) {
      goal->thread.join();
    }
  }
  server_.reset();
}

void SampleAction::start() {
  makeServer();
  feedback_ = std::thread(&SampleAction::feedbackLoop, this);
}

void SampleAction::makeServer() {
  server_.reset();  // unregisters its topics, so that the new ones register afresh
  server_ = std::make_unique<Server>(
      handle_, "sample", [this](GoalHandle h) { onGoal(h); }, [this](GoalHandle h) { onCancel(h); },
      false);
  server_->start();
}

void SampleAction::restart() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const bool active = std::any_of(goals_.begin(), goals_.end(),
                                    [](const std::shared_ptr<Goal>& g) { return !g->done; });
    restartPending_ = active;
    if (stopping_ || active) {
      return;
    }
    const auto since = std::chrono::steady_clock::now() - lastResult_;
    if (since < kResultGrace) {
      scheduleRestart(kResultGrace - since);
      return;
    }
  }
  // No goal is active and none can arrive meanwhile: goals arrive on this queue.
  makeServer();
}

void SampleAction::scheduleRestart(std::chrono::steady_clock::duration delay) {
  restartTimer_ = handle_.createWallTimer(
      ros::WallDuration(std::chrono::duration<double>(delay).count()),
      [this](const ros::WallTimerEvent&) { restart(); }, true);
}

void SampleAction::onGoal(GoalHandle handle) {
  auto goal = std::make_shared<Goal>();
  goal->handle = handle;
  goal->request = toServiceRequest(*handle.getGoal());
  goal->total = std::max<std::uint64_t>(goal->request.num_scenes, 1);
  std::lock_guard<std::mutex> lock(mutex_);
  if (stopping_) {
    handle.setRejected(SampleScenesResult(), "the node is shutting down");
    return;
  }
  handle.setAccepted();
  if (threads_ == 1) {
    for (const auto& other : goals_) {
      if (!other->done) {
        other->preempted = true;
        other->progress.cancel = true;
      }
    }
  }
  goals_.push_back(goal);
  goal->thread = std::thread(&SampleAction::run, this, goal);
  changed_.notify_all();
}

void SampleAction::onCancel(GoalHandle handle) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& goal : goals_) {
    if (goal->handle == handle) {
      goal->progress.cancel = true;
    }
  }
  changed_.notify_all();
}

void SampleAction::run(const std::shared_ptr<Goal>& goal) {
  lowerThreadPriority();
  SampleScenesResult result;
  bool preempted = false;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return goal->progress.cancel || running_ < threads_; });
    preempted = goal->preempted;
    if (!goal->progress.cancel) {
      ++running_;
    }
  }
  if (goal->progress.cancel) {
    // Cancelled while waiting for a thread: nothing sampled.
    result.success = false;
    result.message =
        std::string(preempted ? "preempted by a newer goal (threads is 1)" : "cancelled") +
        " before it started: no scene was sampled";
    goal->handle.setCanceled(result, result.message);
  } else {
    {
      std::lock_guard<std::mutex> lock(goal->feedbackMutex);
      goal->sampling = true;
      goal->started = std::chrono::steady_clock::now();
    }
    SamplePlacements::Response response;
    CallOptions options;
    options.progress = &goal->progress;
    options.goal = true;
    sampler_(goal->request, response, options);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      --running_;
      preempted = goal->preempted;
    }
    changed_.notify_all();
    sendFeedback(*goal, true);  // the final counts, before the result
    {
      std::lock_guard<std::mutex> lock(goal->feedbackMutex);
      goal->sampling = false;
    }
    result = toResult(response);
    if (options.cancelled) {
      if (preempted) {
        result.message = "preempted by a newer goal (threads is 1); " + result.message;
      }
      goal->handle.setCanceled(result, result.message);
    } else if (result.success) {
      goal->handle.setSucceeded(result);
    } else {
      goal->handle.setAborted(result, result.message);
    }
  }
  std::lock_guard<std::mutex> lock(mutex_);
  goal->done = true;
  lastResult_ = std::chrono::steady_clock::now();
  if (restartPending_ && !stopping_ &&
      std::none_of(goals_.begin(), goals_.end(),
                   [](const std::shared_ptr<Goal>& g) { return !g->done; })) {
    restartPending_ = false;
    scheduleRestart(kResultGrace);
  }
}

void SampleAction::sendFeedback(Goal& goal, bool last) {
  std::lock_guard<std::mutex> lock(goal.feedbackMutex);
  const auto now = std::chrono::steady_clock::now();
  // The last feedback keeps to the rate too: the result holds the same counts anyway.
  if (!goal.sampling || (last && now - goal.lastSent < kFeedbackInterval)) {
    return;
  }
  goal.lastSent = now;
  SampleScenesFeedback feedback;
  feedback.scenes_done = goal.progress.done.load();
  feedback.scenes_failed = goal.progress.failed.load();
  feedback.elapsed = std::chrono::duration<double>(now - goal.started).count();
  feedback.remaining = -1.0;
  if (feedback.scenes_done > 0) {
    const std::uint64_t left = goal.total - std::min(goal.total, feedback.scenes_done);
    feedback.remaining =
        feedback.elapsed * static_cast<double>(left) / static_cast<double>(feedback.scenes_done);
  }
  goal.handle.publishFeedback(feedback);
}

void SampleAction::feedbackLoop() {
  auto next = std::chrono::steady_clock::now();
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stopping_) {
    next += kFeedbackInterval;
    changed_.wait_until(lock, next, [this] { return stopping_; });
    if (stopping_) {
      return;
    }
    // Outside mutex_: actionlib calls onGoal() with its own lock held, and publishing takes it.
    std::vector<std::shared_ptr<Goal>> active;
    std::vector<std::shared_ptr<Goal>> finished;
    for (auto it = goals_.begin(); it != goals_.end();) {
      if ((*it)->done) {
        finished.push_back(*it);
        it = goals_.erase(it);
      } else {
        active.push_back(*it);
        ++it;
      }
    }
    lock.unlock();
    for (const auto& goal : active) {
      sendFeedback(*goal, false);
    }
    for (const auto& goal : finished) {
      goal->thread.join();
    }
    lock.lock();
  }
}

}  // namespace ros_interface
}  // namespace placement_samplers
