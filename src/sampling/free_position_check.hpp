#pragma once

// Internal to the core library: proof that no position is left for an object. Not installed.

#include <Eigen/Core>
#include <vector>

#include "placement_samplers/collision/collision_checker.hpp"

namespace placement_samplers::detail {

/// Attempts after which a rejection loop asks whether any position is left at all: far above
/// any usual max_attempts (robosuite's 5000), so only absurd attempt limits meet it, and the
/// draws of every scene that can be placed stay robosuite's.
constexpr std::uint32_t kNoRoomProbeAttempts = 1u << 17;

/// True when robosuite's radius test rejects every centre in the box [@p lo, @p hi] for
/// @p object at height @p z: each part of the box lies inside the disk of one entry at an
/// overlapping height (a quadtree down to a fixed depth; a bounded number of cells, and
/// "false" when the proof would take longer). Never true while a free position exists.
bool noFreePosition(const std::vector<PlacedEntry>& entries, const ObjectModel& object, double z,
                    const Eigen::Vector2d& lo, const Eigen::Vector2d& hi);

}  // namespace placement_samplers::detail
