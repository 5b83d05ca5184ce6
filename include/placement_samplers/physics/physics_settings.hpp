#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace placement_samplers {

/// What is done with a sampled scene in MuJoCo (README, "Physics").
enum class PhysicsMode : std::uint8_t {
  None,   ///< nothing: the sampled poses, as robosuite's samplers give them
  Check,  ///< simulated under gravity; how far each object moved is reported
  Settle  ///< as Check, and the answer's poses are the settled ones
};

/// "none", "check" or "settle", as written in configurations.
const char* physicsModeName(PhysicsMode mode);

/// The mode called @p name (physicsModeName()'s inverse), or nothing.
std::optional<PhysicsMode> physicsModeFromName(std::string_view name);

/// The configuration's physics keys (top level, and `density` per object).
struct PhysicsSettings {
  PhysicsMode mode = PhysicsMode::None;
  double seconds = 1.0;             ///< simulated time per scene [s]
  double timestep = 0.002;          ///< MuJoCo's time step [s]
  double positionTolerance = 0.01;  ///< a stable object moves less [m]
  double rotationTolerance = 0.17;  ///< and turns less [rad]
  bool retry = false;               ///< an unstable scene is drawn again
  std::uint32_t maxDraws = 10;      ///< draws of a scene in all, with retry
  std::optional<double> groundZ;    ///< an infinite plane at this height [m]; unset = none
  double density = 500.0;           ///< of objects that set none [kg/m^3]
  /// MuJoCo's data of one request's simulations together [MiB]: as many threads simulate as
  /// fit, and each one's contact buffers grow within its share.
  std::uint32_t maxMemoryMb = 2048;

  /// Steps per scene: seconds / timestep, rounded, at least one.
  std::uint64_t steps() const;
};

/// What the simulation did to one placed object.
struct PhysicsOutcome {
  /// Distance between the settled position and the sampled one lowered by its sampler's
  /// z_offset (the clearance robosuite asks for on purpose), plus the z_offset of the placed
  /// object it is stacked on, if any [m].
  double moved = 0.0;
  double turned = 0.0;  ///< angle of the rotation from the sampled to the settled orientation [rad]
  bool fallen = false;  ///< its lowest point ended below the lowest support
  Eigen::Vector3d sampledPosition = Eigen::Vector3d::Zero();  ///< [m]
  Eigen::Quaterniond sampledOrientation = Eigen::Quaterniond::Identity();
};

}  // namespace placement_samplers
