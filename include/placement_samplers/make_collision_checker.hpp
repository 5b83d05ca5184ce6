#pragma once

#include <memory>

#include "placement_samplers/collision_checker.hpp"

namespace placement_samplers {

/// A checker for @p mode with clearance @p margin [m] in the exact modes.
/// @throw ConfigError when @p margin is negative or not finite in an exact mode
std::unique_ptr<CollisionChecker> makeCollisionChecker(CollisionMode mode, double margin);

}  // namespace placement_samplers
