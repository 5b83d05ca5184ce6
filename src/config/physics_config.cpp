#include <cmath>
#include <sstream>

#include "config/builder_parts.hpp"
#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {

PhysicsMode parsePhysicsMode(const ConfigNode& node) {
  const std::string& mode = node.asString();
  if (const std::optional<PhysicsMode> parsed = physicsModeFromName(mode)) {
    return *parsed;
  }
  node.fail("expected none, check or settle, got " + quoteText(mode));
}

namespace detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A number in (0, @p max] (asDouble() already refuses NaN and infinities).
double positiveAtMost(const ConfigNode& node, double max, const char* what) {
  const double v = node.asDouble();
  if (!(v > 0.0 && v <= max)) {
    std::ostringstream out;
    out << "expected a positive " << what << " of at most " << max << ", got " << v;
    node.fail(out.str());
  }
  return v;
}

}  // namespace

double parseDensity(const ConfigNode& node) {
  const double v = node.asDouble();
  if (!(v >= kMinDensity && v <= kMaxDensity)) {
    std::ostringstream out;
    out << "expected a density [kg/m^3] in [" << kMinDensity << ", " << kMaxDensity << "], got "
        << v;
    node.fail(out.str());
  }
  return v;
}

void readPhysicsSettings(const ConfigNode& root, PhysicsSettings& physics) {
  if (const ConfigNode* n = root.get("physics")) {
    physics.mode = parsePhysicsMode(*n);
  }
  if (const ConfigNode* n = root.get("physics_seconds")) {
    physics.seconds = positiveAtMost(*n, kMaxPhysicsSeconds, "duration [s]");
  }
  if (const ConfigNode* n = root.get("physics_timestep")) {
    physics.timestep = positiveAtMost(*n, kMaxPhysicsTimestep, "time step [s]");
    // MuJoCo's steps: below 0.1 ms a second is 10,000 steps per scene.
    if (physics.timestep < kMinPhysicsTimestep) {
      std::ostringstream out;
      out << "expected a time step [s] of at least " << kMinPhysicsTimestep << ", got "
          << physics.timestep;
      n->fail(out.str());
    }
  }
  if (const ConfigNode* n = root.get("physics_position_tolerance")) {
    physics.positionTolerance = positiveAtMost(*n, limits::kCoordinate, "distance [m]");
  }
  if (const ConfigNode* n = root.get("physics_rotation_tolerance")) {
    physics.rotationTolerance = positiveAtMost(*n, kPi, "angle [rad]");
  }
  if (const ConfigNode* n = root.get("physics_retry")) {
    physics.retry = n->asBool();
  }
  if (const ConfigNode* n = root.get("physics_max_draws")) {
    physics.maxDraws = static_cast<std::uint32_t>(n->asInt(1, 1000));
  }
  if (const ConfigNode* n = root.get("physics_max_memory_mb")) {
    physics.maxMemoryMb =
        static_cast<std::uint32_t>(n->asInt(kMinPhysicsMemoryMb, kMaxPhysicsMemoryMb));
  }
  if (const ConfigNode* n = root.get("ground_z")) {
    const double z = n->asDouble();
    if (!(std::abs(z) <= limits::kCoordinate)) {
      std::ostringstream out;
      out << "expected a height [m] within [-" << limits::kCoordinate << ", " << limits::kCoordinate
          << "], got " << z;
      n->fail(out.str());
    }
    physics.groundZ = z;
  }
  if (const ConfigNode* n = root.get("density")) {
    physics.density = parseDensity(*n);
  }
  if (physics.timestep > physics.seconds) {
    const ConfigNode* n = root.get("physics_timestep");
    std::ostringstream out;
    out << "expected a time step [s] no longer than physics_seconds (" << physics.seconds
        << "), got " << physics.timestep;
    (n != nullptr ? *n : root).fail(out.str());
  }
}

}  // namespace detail
}  // namespace placement_samplers
