#include "placement_samplers/collision/combined_checker.hpp"

#include <stdexcept>
#include <utility>

namespace placement_samplers {

CombinedChecker::CombinedChecker(std::unique_ptr<CollisionChecker> first,
                                 std::unique_ptr<CollisionChecker> second)
    : first_(std::move(first)), second_(std::move(second)) {
  if (!first_ || !second_) {
    throw std::invalid_argument("CombinedChecker needs two checkers");
  }
}

void CombinedChecker::clear() {
  first_->clear();
  second_->clear();
}

void CombinedChecker::added(const std::vector<PlacedEntry>& entries, std::size_t index) {
  first_->added(entries, index);
  second_->added(entries, index);
}

std::ptrdiff_t CombinedChecker::firstCollision(const std::vector<PlacedEntry>& entries,
                                               const Candidate& candidate) {
  const std::ptrdiff_t hit = first_->firstCollision(entries, candidate);
  return hit != kNone ? hit : second_->firstCollision(entries, candidate);
}

bool CombinedChecker::exactDistance(const std::vector<PlacedEntry>& entries, std::size_t index,
                                    const Candidate& candidate, double& distance) {
  return first_->exactDistance(entries, index, candidate, distance) ||
         second_->exactDistance(entries, index, candidate, distance);
}

bool CombinedChecker::includesRadiusTest() const {
  return first_->includesRadiusTest() || second_->includesRadiusTest();
}

bool CombinedChecker::needsOrientation() const {
  return first_->needsOrientation() || second_->needsOrientation();
}

}  // namespace placement_samplers
