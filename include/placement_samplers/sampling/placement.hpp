#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "placement_samplers/geometry/object_model.hpp"
#include "placement_samplers/physics/physics_settings.hpp"

namespace placement_samplers {

/// One sampled object pose.
///
/// The names are views of strings owned by the configuration (as @ref object is), so that
/// placing an object copies no string. The aligned quaternion comes right after them, so
/// that no member needs padding.
struct ObjectPlacement {
  ObjectPlacement() = default;
  /// Every member, so that std::vector::emplace_back builds a placement in place.
  ObjectPlacement(std::string_view name, std::string_view sampler,
                  const Eigen::Quaterniond& orientation, const Eigen::Vector3d& position,
                  const ObjectModel* object, std::uint32_t attempts, bool hidden,
                  std::int16_t restPose = kUpright)
      : name(name),
        sampler(sampler),
        orientation(orientation),
        position(position),
        object(object),
        attempts(attempts),
        hidden(hidden),
        restPose(restPose) {}

  /// restPose of an object placed as configured (resting: upright, or no resting pose found).
  static constexpr std::int16_t kUpright = -1;

  std::string_view name;     ///< object name: `object->name`
  std::string_view sampler;  ///< name of the uniform sampler that placed it
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< object origin [m]
  const ObjectModel* object = nullptr;                 ///< geometry
  std::uint32_t attempts = 0;                          ///< samples drawn, the accepted one included
  bool hidden = false;  ///< placed by hide(): far away, not to be drawn
  /// Under resting: stable, the index of its resting pose as --describe lists them; @p object
  /// is then the object in that pose (its bounds). kUpright otherwise.
  std::int16_t restPose = kUpright;
};

/// Why a scene could not be completed.
struct Failure {
  std::string object;          ///< the object that could not be placed ("" when none)
  std::string sampler;         ///< the sampler that was running
  std::uint32_t attempts = 0;  ///< samples drawn for that object
  std::string blocker;         ///< the object or fixture that most often rejected it ("" when none)
  std::uint32_t blockerCount = 0;  ///< rejections by it
  std::string message;             ///< the full sentence
};

/// The outcome of one scene. Its placements point into the configuration that sampled them
/// (`name`, `sampler`, `object`): keep the SceneGenerator, or its configPtr(), as long as the
/// result.
struct SceneResult {
  std::uint64_t seed = 0;   ///< the request seed
  std::uint64_t index = 0;  ///< the scene index within the request
  bool success = false;
  // Physics (README, "Physics"), in success's padding; ObjectPlacement stays as it was.
  PhysicsMode physicsMode = PhysicsMode::None;  ///< the request's mode
  bool simulated = false;  ///< the scene was simulated (placed, and a mode other than none)
  bool stable = false;     ///< simulated, and no object moved, turned or fell too far
  std::string message;     ///< empty on success
  std::vector<ObjectPlacement> placements;  ///< new placements in sampling order (no fixtures)
  /// One per placement when simulated, else empty. With PhysicsMode::Settle the placements
  /// hold the settled poses and these the sampled ones. Hidden objects: 0, 0, not fallen.
  std::vector<PhysicsOutcome> physics;
};

}  // namespace placement_samplers
