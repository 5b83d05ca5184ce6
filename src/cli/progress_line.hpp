#pragma once
// sample_scenes' progress line on stderr (progress_line.cpp). Private to the CLI.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <ostream>
#include <string>
#include <thread>

#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {

/// "sample_scenes: 1234/10000 scenes (12.3 %), 5678 scenes/s, 3 failed, ETA 0:00:02" after
/// @p seconds of sampling; "ETA ?" before the first scene is done.
std::string progressText(std::uint64_t done, std::uint64_t total, std::uint64_t failed,
                         double seconds);

/// Shows the progress of a run on @p err from a thread of its own while the scenes are sampled:
/// on a terminal one line rewritten in place four times a second, elsewhere one line a second.
class ProgressLine {
 public:
  /// @param total the run's scenes
  /// @param forced shown from the start, and its final counts in any case; otherwise nothing
  ///        is shown during the first second (a short run shows nothing)
  ProgressLine(std::ostream& err, const SampleProgress& progress, std::uint64_t total,
               bool terminal, bool forced);
  /// Stops the thread and ends the line.
  ~ProgressLine();

  /// As the destructor: call it before anything else is written to @p err.
  void finish();

 private:
  void run();
  void print(bool last);

  std::ostream& err_;
  const SampleProgress& progress_;
  std::uint64_t total_;
  bool terminal_;
  bool forced_;
  std::chrono::steady_clock::time_point start_;
  bool shown_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace placement_samplers
