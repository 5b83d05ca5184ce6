#pragma once

#include <cstdint>
#include <string>

#include "placement_samplers/sampling/placement.hpp"

namespace placement_samplers {

/// What went wrong in a batch of scenes, in one line: the first failed scene's message and how
/// many failed. The node answers with it; the CLI prints it on stderr. Feed the scenes in order.
class FailureSummary {
 public:
  /// Counts @p scene; keeps its message when it is the first failure.
  void add(const SceneResult& scene);

  /// Scenes that failed so far.
  std::uint64_t failed() const { return failed_; }

  /// "" when no scene failed; otherwise the first failure's message, prefixed with
  /// "scene <index>: " when @p total > 1, and followed by " (<k> of <total> scenes failed)"
  /// when more than one failed.
  std::string message(std::uint64_t total) const;

 private:
  std::uint64_t failed_ = 0;
  std::uint64_t firstIndex_ = 0;
  std::string firstMessage_;
};

}  // namespace placement_samplers
