#pragma once

#include <memory>

#include "placement_samplers/collision/collision_checker.hpp"

namespace placement_samplers {

/// Checks that makeCollisionChecker() accepts @p mode and @p margin [m], without building a
/// checker (the builder and request preparation use it).
/// @throw ConfigError when @p margin is negative or not finite in an exact mode
void checkCollisionMode(CollisionMode mode, double margin);

/// A checker for @p mode with clearance @p margin [m] in the exact modes.
/// @throw ConfigError when @p margin is negative or not finite in an exact mode
std::unique_ptr<CollisionChecker> makeCollisionChecker(CollisionMode mode, double margin);

}  // namespace placement_samplers
