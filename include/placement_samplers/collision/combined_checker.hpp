#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "placement_samplers/collision/collision_checker.hpp"

namespace placement_samplers {

/// Both tests must pass (`radius_and_fcl`): the first checker's blocker is reported first.
class CombinedChecker : public CollisionChecker {
 public:
  /// @throw std::invalid_argument when either checker is null
  CombinedChecker(std::unique_ptr<CollisionChecker> first,
                  std::unique_ptr<CollisionChecker> second);

  void clear() override;
  void added(const std::vector<PlacedEntry>& entries, std::size_t index) override;
  std::ptrdiff_t firstCollision(const std::vector<PlacedEntry>& entries,
                                const Candidate& candidate) override;
  bool needsOrientation() const override;
  bool includesRadiusTest() const override;

  /// The first checker's exact distance, else the second's.
  bool exactDistance(const std::vector<PlacedEntry>& entries, std::size_t index,
                     const Candidate& candidate, double& distance) override;

 private:
  std::unique_ptr<CollisionChecker> first_;
  std::unique_ptr<CollisionChecker> second_;
};

}  // namespace placement_samplers
