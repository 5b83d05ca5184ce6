#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "placement_samplers/physics/physics_settings.hpp"
#include "placement_samplers/sampling/placement.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {

/// Rows of the .npz layout (README, "Data sets for numpy") for a block of k scenes of n
/// objects, in buffers the caller owns (NpzWriter's, or numpy arrays). C order; bools are
/// one byte, 0 or 1.
struct SceneArrayRows {
  double* position = nullptr;            ///< [k, n, 3] [m]
  double* orientation = nullptr;         ///< [k, n, 4] (x, y, z, w)
  std::uint32_t* attempts = nullptr;     ///< [k, n]
  std::uint8_t* success = nullptr;       ///< [k]
  std::uint64_t* scene = nullptr;        ///< [k] scene indices
  std::uint8_t* stable = nullptr;        ///< [k], physics check or settle
  double* moved = nullptr;               ///< [k, n] [m], physics check or settle
  double* turned = nullptr;              ///< [k, n] [rad], physics check or settle
  std::uint8_t* fallen = nullptr;        ///< [k, n], physics check or settle
  double* sampledPosition = nullptr;     ///< [k, n, 3] [m], physics settle
  double* sampledOrientation = nullptr;  ///< [k, n, 4], physics settle
  std::int16_t* restPose = nullptr;      ///< [k, n], when not null (-1: as configured)
};

/// True when a sampler of @p request draws resting poses (`resting: stable`): the .npz layout
/// then has rest_pose.
bool drawsRestPoses(const PreparedRequest& request);

/// Puts scenes into the columns of the .npz layout: one column per object name, in the order
/// given; an object a scene did not place is NaN in position and orientation and 0 in
/// attempts; the physics members where the mode has them (NaN and false where a scene was not
/// simulated).
class SceneColumns {
 public:
  SceneColumns(std::vector<std::string> names, PhysicsMode physics);

  const std::vector<std::string>& names() const { return names_; }
  PhysicsMode physics() const { return physics_; }

  /// Writes rows 0 .. scenes.size() - 1 of @p rows (every member of the mode; the others may
  /// be null).
  /// @throw std::invalid_argument when a scene places an object not among the names
  void fill(const std::vector<SceneResult>& scenes, const SceneArrayRows& rows) const;

 private:
  std::size_t column(const ObjectPlacement& p, std::size_t i) const;

  std::vector<std::string> names_;
  std::unordered_map<std::string, std::size_t> columns_;
  PhysicsMode physics_;
};

}  // namespace placement_samplers
