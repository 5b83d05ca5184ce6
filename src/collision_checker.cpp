#include "placement_samplers/collision_checker.hpp"

#include "placement_samplers/errors.hpp"

namespace placement_samplers {

bool radiusOverlap(const PlacedEntry& other, const Candidate& candidate) {
  const double dx = candidate.position.x() - other.position.x();
  const double dy = candidate.position.y() - other.position.y();
  const double reach = other.object->horizontalRadius + candidate.object->horizontalRadius;
  return dx * dx + dy * dy <= reach * reach &&
         candidate.position.z() - other.position.z() <=
             other.object->topOffset.z() - candidate.object->bottomOffset.z();
}

std::ptrdiff_t RadiusChecker::firstCollision(const std::vector<PlacedEntry>& entries,
                                             const Candidate& candidate) const {
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (radiusOverlap(entries[i], candidate)) {
      return static_cast<std::ptrdiff_t>(i);
    }
  }
  return kNone;
}

const char* collisionModeName(CollisionMode mode) {
  switch (mode) {
    case CollisionMode::Radius:
      return "radius";
    case CollisionMode::Fcl:
      return "fcl";
    case CollisionMode::RadiusAndFcl:
      return "radius_and_fcl";
  }
  return "unknown";
}

std::unique_ptr<CollisionChecker> makeCollisionChecker(CollisionMode mode, double /*margin*/) {
  if (mode == CollisionMode::Radius) {
    return std::make_unique<RadiusChecker>();
  }
  throw ConfigError(std::string("collision_check '") + collisionModeName(mode) +
                    "' is not available in this build (only 'radius')");
}

}  // namespace placement_samplers
