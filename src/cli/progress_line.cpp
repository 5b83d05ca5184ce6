#include "cli/progress_line.hpp"

#include <cmath>
#include <cstdio>

namespace placement_samplers {
namespace {

std::string clock(double seconds) {
  const auto s = static_cast<std::uint64_t>(std::llround(std::max(0.0, seconds)));
  char text[32];
  std::snprintf(text, sizeof(text), "%llu:%02llu:%02llu", static_cast<unsigned long long>(s / 3600),
                static_cast<unsigned long long>(s / 60 % 60),
                static_cast<unsigned long long>(s % 60));
  return text;
}

}  // namespace

std::string progressText(std::uint64_t done, std::uint64_t total, std::uint64_t failed,
                         double seconds) {
  char head[96];
  const double percent = total == 0 ? 100.0 : 100.0 * static_cast<double>(done) / total;
  const double rate = seconds > 0.0 ? static_cast<double>(done) / seconds : 0.0;
  std::snprintf(head, sizeof(head), "%.1f %%), %.0f scenes/s, ", percent, rate);
  std::string text = "sample_scenes: " + std::to_string(done) + "/" + std::to_string(total) +
                     " scenes (" + head + std::to_string(failed) + " failed, ETA ";
  if (done == 0) {
    return text + "?";
  }
  return text + clock(seconds * static_cast<double>(total - std::min(done, total)) / done);
}

ProgressLine::ProgressLine(std::ostream& err, const SampleProgress& progress, std::uint64_t total,
                           bool terminal, bool forced)
    : err_(err),
      progress_(progress),
      total_(total),
      terminal_(terminal),
      forced_(forced),
      start_(std::chrono::steady_clock::now()),
      thread_(&ProgressLine::run, this) {}

ProgressLine::~ProgressLine() { finish(); }

void ProgressLine::finish() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_) {
      return;
    }
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
  if (shown_ || forced_) {
    print(true);
  }
}

void ProgressLine::run() {
  const auto interval = terminal_ ? std::chrono::milliseconds(250) : std::chrono::seconds(1);
  // Unforced, the first line after a second: a shorter run shows none.
  auto next = start_ + (forced_ ? std::chrono::milliseconds(0) : std::chrono::milliseconds(1000));
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_until(lock, next, [this] { return stopping_; })) {
    print(false);
    shown_ = true;
    next += interval;
  }
}

void ProgressLine::print(bool last) {
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::string text =
      progressText(progress_.done.load(), total_, progress_.failed.load(), seconds);
  if (terminal_) {
    // Back to the line's start, the text, the rest of the old line erased.
    err_ << '\r' << text << "\x1b[K" << (last ? "\n" : "") << std::flush;
  } else {
    err_ << text << '\n' << std::flush;
  }
}

}  // namespace placement_samplers
