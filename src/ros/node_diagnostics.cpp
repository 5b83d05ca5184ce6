#include "placement_samplers/ros/node_diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace placement_samplers {
namespace ros_interface {
namespace {

/// The @p q quantile (0..1) of @p values, nearest rank; 0 for none.
double quantile(std::vector<double> values, double q) {
  if (values.empty()) {
    return 0.0;
  }
  const std::size_t rank =
      static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
  const std::size_t index = std::min(values.size() - 1, rank == 0 ? 0 : rank - 1);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index),
                   values.end());
  return values[index];
}

std::string fixed(double value, int digits) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << value;
  return out.str();
}

}  // namespace

NodeDiagnostics::NodeDiagnostics(unsigned threads) : threads_(threads) {}

NodeDiagnostics::~NodeDiagnostics() { timer_.stop(); }

void NodeDiagnostics::start(const ros::NodeHandle& queueHandle) {
  queueHandle_ = queueHandle;
  restart();
  // The updater publishes when its period has passed; the timer asks more often than that.
  timer_ = queueHandle_->createWallTimer(
      ros::WallDuration(0.1), [this](const ros::WallTimerEvent&) { updater_->update(); });
}

void NodeDiagnostics::restart() {
  // Publishes on the global /diagnostics; reads ~diagnostic_period from the private namespace.
  updater_.reset();
  updater_ = std::make_unique<diagnostic_updater::Updater>(ros::NodeHandle(), *queueHandle_);
  updater_->setHardwareID(ros::this_node::getName());
  updater_->add("placement server",
                [this](diagnostic_updater::DiagnosticStatusWrapper& status) { fill(status); });
}

void NodeDiagnostics::callStarted() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++busy_;
}

void NodeDiagnostics::callFinished(const CallRecord& call) {
  std::lock_guard<std::mutex> lock(mutex_);
  busy_ = busy_ > 0 ? busy_ - 1 : 0;
  ++calls_;
  scenes_ += call.sceneFailed.size();
  const std::size_t from =
      call.sceneFailed.size() > kRecentScenes ? call.sceneFailed.size() - kRecentScenes : 0;
  recentFailed_.insert(recentFailed_.end(),
                       call.sceneFailed.begin() + static_cast<std::ptrdiff_t>(from),
                       call.sceneFailed.end());
  while (recentFailed_.size() > kRecentScenes) {
    recentFailed_.pop_front();
  }
  latencies_.push_back(call.seconds);
  if (latencies_.size() > kLatencyCalls) {
    latencies_.pop_front();
  }
  if (call.refusedForSize) {
    lastRefusal_ = Clock::now();
  }
  if (!call.error.empty()) {
    lastError_ = call.error;
  }
}

void NodeDiagnostics::served(const std::string& digest, bool reload) {
  std::lock_guard<std::mutex> lock(mutex_);
  digest_ = digest;
  if (reload) {
    reloadError_.clear();
  }
}

void NodeDiagnostics::reloadFailed(const std::string& error) {
  std::lock_guard<std::mutex> lock(mutex_);
  reloadError_ = error;
  lastError_ = error;
}

void NodeDiagnostics::refused(const std::string& error) {
  std::lock_guard<std::mutex> lock(mutex_);
  lastError_ = error;
}

void NodeDiagnostics::setMasterUp(bool up) {
  std::lock_guard<std::mutex> lock(mutex_);
  masterUp_ = up;
}

void NodeDiagnostics::fill(diagnostic_updater::DiagnosticStatusWrapper& status) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::size_t failed =
      static_cast<std::size_t>(std::count(recentFailed_.begin(), recentFailed_.end(), true));
  const double rate =
      recentFailed_.empty() ? 0.0 : static_cast<double>(failed) / recentFailed_.size();
  const std::vector<double> latencies(latencies_.begin(), latencies_.end());

  using Status = diagnostic_msgs::DiagnosticStatus;
  status.summary(Status::OK, "serving");
  if (rate > kWarnFailureRate) {
    status.mergeSummary(Status::WARN, std::to_string(failed) + " of the last " +
                                          std::to_string(recentFailed_.size()) + " scenes failed");
  }
  if (lastRefusal_) {
    const double ago = std::chrono::duration<double>(Clock::now() - *lastRefusal_).count();
    if (ago < kRefusalWarnSeconds) {
      status.mergeSummary(Status::WARN,
                          "a request was refused for its size " + fixed(ago, 0) + " s ago");
    }
  }
  if (!reloadError_.empty()) {
    status.mergeSummary(Status::ERROR, "the last reload failed: " + reloadError_);
  }
  if (!masterUp_) {
    status.mergeSummary(Status::ERROR, "lost the master");
  }
  status.add("calls", calls_);
  status.add("scenes", scenes_);
  status.add("failure rate (last " + std::to_string(kRecentScenes) + " scenes)", fixed(rate, 3));
  status.add("latency p50 [s]", fixed(quantile(latencies, 0.50), 6));
  status.add("latency p99 [s]", fixed(quantile(latencies, 0.99), 6));
  status.add("threads busy", std::to_string(busy_) + " of " + std::to_string(threads_));
  status.add("configuration digest", digest_);
  status.add("last error", lastError_);
}

}  // namespace ros_interface
}  // namespace placement_samplers
