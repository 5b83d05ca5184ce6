#include "placement_samplers/collision/make_collision_checker.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "placement_samplers/collision/combined_checker.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/collision/fcl_checker.hpp"
#include "placement_samplers/collision/radius_checker.hpp"

namespace placement_samplers {

namespace {
constexpr CollisionMode kModes[] = {CollisionMode::Radius, CollisionMode::Fcl,
                                    CollisionMode::RadiusAndFcl};
}  // namespace

const char* collisionModeName(CollisionMode mode) {
  switch (mode) {
    case CollisionMode::Radius:
      return "radius";
    case CollisionMode::Fcl:
      return "fcl";
    case CollisionMode::RadiusAndFcl:
      return "radius_and_fcl";
  }
  return "radius";
}

std::optional<CollisionMode> collisionModeFromName(std::string_view name) {
  for (const CollisionMode mode : kModes) {
    if (name == collisionModeName(mode)) {
      return mode;
    }
  }
  return std::nullopt;
}

void checkCollisionMargin(double margin) {
  if (!std::isfinite(margin) || margin < 0.0 || margin > limits::kCoordinate) {
    std::ostringstream out;
    out << "expected a finite, non-negative clearance in [m] of at most " << limits::kCoordinate
        << ", got " << margin;
    throw ConfigError(out.str());
  }
}

std::unique_ptr<CollisionChecker> makeCollisionChecker(CollisionMode mode, double margin) {
  checkCollisionMargin(margin);
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
