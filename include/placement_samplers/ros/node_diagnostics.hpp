#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace placement_samplers {
namespace ros_interface {

/// The failure rate above which /diagnostics warns, over the last kRecentScenes scenes.
constexpr double kWarnFailureRate = 0.10;
constexpr std::size_t kRecentScenes = 100;
/// Calls whose latency the percentiles are taken over (the latest ones).
constexpr std::size_t kLatencyCalls = 1000;
/// A request refused for its size warns for this long [s].
constexpr double kRefusalWarnSeconds = 60.0;

/// What one sampling call (service, goal or "sample now") did, for /diagnostics.
struct CallRecord {
  double seconds = 0.0;  ///< from the callback's start to the answer [s]
  /// Per scene answered, in order: true when it failed (scenes a cancel left out are not here).
  std::vector<bool> sceneFailed;
  bool refusedForSize = false;  ///< num_scenes or placements over the configured limits
  std::string error;            ///< the answer's message when the request itself was refused
};

/// The node's health on /diagnostics (diagnostic_updater), one status named
/// "<node name>: placement server": OK; WARN when more than kWarnFailureRate of the last
/// kRecentScenes scenes failed or a request was refused for its size in the last
/// kRefusalWarnSeconds; ERROR when the last ~reload failed or the master is lost. Values:
/// calls, scenes, failure rate, p50 and p99 latency, threads busy, the configuration's digest,
/// the last error. Thread-safe.
class NodeDiagnostics {
 public:
  /// @param threads the node's sampling threads (threads busy is counted against them)
  explicit NodeDiagnostics(unsigned threads);
  ~NodeDiagnostics();

  /// Publishes on /diagnostics every ~diagnostic_period (1 s), from a timer on the callback
  /// queue of @p queueHandle (a private handle).
  void start(const ros::NodeHandle& queueHandle);
  /// Advertises /diagnostics again (a new master knows nothing of the old one's topics). From
  /// the thread of start()'s queue.
  void restart();

  void callStarted();
  void callFinished(const CallRecord& call);
  /// The configuration now served (its parameters' digest); a ~reload's success ends its ERROR.
  void served(const std::string& digest, bool reload);
  /// A ~reload refused with @p error: ERROR until one succeeds.
  void reloadFailed(const std::string& error);
  /// Something refused that leaves the node serving as before (a knob, a region handle).
  void refused(const std::string& error);
  /// The master watch's view: ERROR while it is lost.
  void setMasterUp(bool up);

  /// The status as it is published now.
  void fill(diagnostic_updater::DiagnosticStatusWrapper& status) const;

 private:
  using Clock = std::chrono::steady_clock;

  mutable std::mutex mutex_;
  unsigned threads_;
  unsigned busy_ = 0;
  std::uint64_t calls_ = 0;
  std::uint64_t scenes_ = 0;
  std::deque<bool> recentFailed_;  // the last kRecentScenes scenes
  std::deque<double> latencies_;   // the last kLatencyCalls calls [s]
  std::optional<Clock::time_point> lastRefusal_;
  std::string digest_;
  std::string reloadError_;  // the last ~reload's error, "" after a successful one
  std::string lastError_;
  bool masterUp_ = true;

  std::unique_ptr<diagnostic_updater::Updater> updater_;
  std::optional<ros::NodeHandle> queueHandle_;  // set by start(): a handle needs ros::init()
  ros::WallTimer timer_;
};

}  // namespace ros_interface
}  // namespace placement_samplers
