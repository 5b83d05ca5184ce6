#pragma once

// Internal to the core library: the validator's list of what an overlapping pose overlaps.
// Not installed.

#include <cstddef>
#include <memory>
#include <string>
#include <unordered_set>
#include <vector>

#include "placement_samplers/collision/collision_checker.hpp"
#include "placement_samplers/collision/make_collision_checker.hpp"
#include "placement_samplers/validation/scene_validator.hpp"

namespace placement_samplers {
namespace detail {

/// Lists the fixtures and objects a pose overlaps, one pair test each, within a scene's
/// budget of tests (ValidationOptions::maxOverlapTests).
class OverlapSearch {
 public:
  OverlapSearch(CollisionMode mode, double margin, const ValidationOptions& options);

  /// The entries of @p entries that @p candidate overlaps (@p hit, the scene checker's find, is
  /// one of them), as Overlap reasons of @p verdict: the first options.maxOverlapsListed, the
  /// number of the others in the last reason's message (a pile of n objects would otherwise
  /// give n^2 / 2 reasons). @p name and @p sampler name the object and its sampler.
  void list(ObjectVerdict& verdict, const Candidate& candidate, const std::string& name,
            const std::string& sampler, std::ptrdiff_t hit,
            const std::vector<PlacedEntry>& entries);

 private:
  /// @p entry alone against @p candidate (@p entries: the scene, for the candidate's support).
  bool pairCollides(const PlacedEntry& entry, const Candidate& candidate,
                    const std::vector<PlacedEntry>& entries);

  CollisionMode mode_;
  double margin_;
  ValidationOptions options_;
  std::unique_ptr<CollisionChecker> checker_;
  std::unordered_set<const ObjectModel*> seen_;  ///< what checker_ has seen
  std::vector<PlacedEntry> one_ = std::vector<PlacedEntry>(1);
  std::size_t tests_ = 0;  ///< pair tests of the scene so far
};

}  // namespace detail
}  // namespace placement_samplers
