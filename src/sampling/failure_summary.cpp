#include "placement_samplers/sampling/failure_summary.hpp"

namespace placement_samplers {

void FailureSummary::add(const SceneResult& scene) {
  if (scene.success) {
    return;
  }
  if (failed_ == 0) {
    firstIndex_ = scene.index;
    firstMessage_ = scene.message;
  }
  ++failed_;
}

std::string FailureSummary::message(std::uint64_t total) const {
  if (failed_ == 0) {
    return "";
  }
  std::string text =
      total == 1 ? firstMessage_ : "scene " + std::to_string(firstIndex_) + ": " + firstMessage_;
  if (failed_ > 1) {
    text += " (" + std::to_string(failed_) + " of " + std::to_string(total) + " scenes failed)";
  }
  return text;
}

}  // namespace placement_samplers
