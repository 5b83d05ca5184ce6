#include "placement_samplers/physics/physics_settings.hpp"

#include <algorithm>
#include <cmath>

namespace placement_samplers {

const char* physicsModeName(PhysicsMode mode) {
  switch (mode) {
    case PhysicsMode::Check:
      return "check";
    case PhysicsMode::Settle:
      return "settle";
    case PhysicsMode::None:
      break;
  }
  return "none";
}

std::optional<PhysicsMode> physicsModeFromName(std::string_view name) {
  for (const PhysicsMode mode : {PhysicsMode::None, PhysicsMode::Check, PhysicsMode::Settle}) {
    if (name == physicsModeName(mode)) {
      return mode;
    }
  }
  return std::nullopt;
}

std::uint64_t PhysicsSettings::steps() const {
  return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(seconds / timestep)));
}

}  // namespace placement_samplers
