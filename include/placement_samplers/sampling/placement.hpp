#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "placement_samplers/geometry/object_model.hpp"

namespace placement_samplers {

/// One sampled object pose.
struct ObjectPlacement {
  std::string name;  ///< object name
  /// Name of the uniform sampler that placed it, owned by the configuration (as @ref object):
  /// a view, so that a scene's result costs no allocation per placement.
  std::string_view sampler;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< object origin [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  std::uint32_t attempts = 0;           ///< samples drawn, the accepted one included
  const ObjectModel* object = nullptr;  ///< geometry (owned by the configuration)
  bool hidden = false;                  ///< placed by hide(): far away, not to be drawn
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
/// (`object`, `sampler`): keep the SceneGenerator, or its configPtr(), as long as the result.
struct SceneResult {
  std::uint64_t seed = 0;   ///< the request seed
  std::uint64_t index = 0;  ///< the scene index within the request
  bool success = false;
  std::string message;                      ///< empty on success
  std::vector<ObjectPlacement> placements;  ///< new placements in sampling order (no fixtures)
};

}  // namespace placement_samplers
