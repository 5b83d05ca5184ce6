#include "placement_samplers/collision_checker.hpp"

namespace placement_samplers {

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

}  // namespace placement_samplers
