#pragma once

#include <memory>
#include <optional>
#include <string_view>

#include "placement_samplers/collision/collision_checker.hpp"

namespace placement_samplers {

/// The mode's name in configurations and outputs: "radius", "fcl" or "radius_and_fcl".
const char* collisionModeName(CollisionMode mode);

/// The mode called @p name (collisionModeName()'s inverse), or nothing.
std::optional<CollisionMode> collisionModeFromName(std::string_view name);

/// The one rule for `collision_margin` [m]: finite, non-negative, at most limits::kCoordinate.
/// @throw ConfigError saying what was expected (the caller adds where the value came from)
void checkCollisionMargin(double margin);

/// A checker for @p mode with clearance @p margin [m] in the exact modes.
/// @throw ConfigError when @p margin breaks checkCollisionMargin()'s rule
std::unique_ptr<CollisionChecker> makeCollisionChecker(CollisionMode mode, double margin);

}  // namespace placement_samplers
