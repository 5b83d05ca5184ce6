#include "placement_samplers/collision/make_collision_checker.hpp"

#include <cmath>
#include <string>

#include "placement_samplers/collision/combined_checker.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/collision/fcl_checker.hpp"
#include "placement_samplers/collision/radius_checker.hpp"

namespace placement_samplers {

void checkCollisionMode(CollisionMode mode, double margin) {
  if (mode != CollisionMode::Radius && (!std::isfinite(margin) || margin < 0.0)) {
    throw ConfigError("collision_margin must be finite and non-negative, got " +
                      std::to_string(margin));
  }
}

std::unique_ptr<CollisionChecker> makeCollisionChecker(CollisionMode mode, double margin) {
  checkCollisionMode(mode, margin);
  if (mode == CollisionMode::Radius) {
    return std::make_unique<RadiusChecker>();
  }
  if (mode == CollisionMode::Fcl) {
    return std::make_unique<FclChecker>(margin);
  }
  return std::make_unique<CombinedChecker>(std::make_unique<RadiusChecker>(),
                                           std::make_unique<FclChecker>(margin));
}

}  // namespace placement_samplers
