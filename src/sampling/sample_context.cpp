#include "placement_samplers/sampling/sample_context.hpp"

#include <algorithm>
#include <sstream>

namespace placement_samplers {

SampleContext::SampleContext(Engine& engine, CollisionChecker& checker, std::uint32_t maxAttempts)
    : engine_(&engine), checker_(checker), maxAttempts_(maxAttempts) {}

void SampleContext::clear() {
  entries_.clear();
  placements_.clear();
  failure_.reset();
  checker_.clear();
}

void SampleContext::addFixture(std::string_view name, const ObjectModel* object,
                               const Eigen::Vector3d& position,
                               const Eigen::Quaterniond& orientation) {
  entries_.emplace_back(name, object, position, orientation, true);
  checker_.added(entries_, entries_.size() - 1);
}

void SampleContext::addPlacement(std::string_view sampler, const Candidate& candidate,
                                 std::uint32_t attempts, bool hidden, std::int16_t restPose) {
  // Built in place: a temporary, as g++ 12 builds it, is stored in 8-byte parts and copied in
  // 16-byte parts, and each such copy waits for the stores (about a tenth of a Lift scene).
  const ObjectModel* object = candidate.object;
  placements_.emplace_back(object->name, sampler, candidate.orientation, candidate.position, object,
                           attempts, hidden, restPose);
  entries_.emplace_back(object->name, object, candidate.position, candidate.orientation, false);
  checker_.added(entries_, entries_.size() - 1);
}

const PlacedEntry* SampleContext::find(const std::string& name) const {
  for (const PlacedEntry& entry : entries_) {
    if (entry.name == name) {
      return &entry;
    }
  }
  return nullptr;
}

void SampleContext::setSceneSeconds(double seconds) {
  sceneSeconds_ = seconds;
  sceneLimit_ = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(seconds));
  sceneStarted_ = false;
}

std::optional<std::chrono::steady_clock::time_point> SampleContext::sceneDeadline() {
  if (!(sceneSeconds_ > 0.0)) {
    return deadline_;
  }
  if (!sceneStarted_) {
    sceneEnd_ = std::chrono::steady_clock::now() + sceneLimit_;
    sceneStarted_ = true;
  }
  return deadline_ ? std::min(*deadline_, sceneEnd_) : sceneEnd_;
}

bool SampleContext::expired() {
  if (!(sceneSeconds_ > 0.0)) {
    return requestExpired();
  }
  const auto now = std::chrono::steady_clock::now();
  if (!sceneStarted_) {
    sceneEnd_ = now + sceneLimit_;
    sceneStarted_ = true;
  }
  return now > sceneEnd_ || (deadline_ && now > *deadline_);
}

std::string SampleContext::outOfTimeReason() const {
  if (requestExpired() || !(sceneSeconds_ > 0.0)) {
    return "the request ran out of time";
  }
  std::ostringstream out;
  out << "the scene ran out of time (its limit is " << sceneSeconds_ << " s)";
  return out.str();
}

std::vector<std::uint32_t>& SampleContext::blockerCounts() {
  blockerCounts_.assign(entries_.size(), 0);
  return blockerCounts_;
}

}  // namespace placement_samplers
