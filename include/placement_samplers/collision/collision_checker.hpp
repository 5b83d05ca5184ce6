#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "placement_samplers/geometry/object_model.hpp"

namespace placement_samplers {

/// Something already in the scene: a fixture or an object placed earlier in the scene.
struct PlacedEntry {
  PlacedEntry() = default;
  /// Every member, so that std::vector::emplace_back builds an entry in place.
  PlacedEntry(std::string_view name, const ObjectModel* object, const Eigen::Vector3d& position,
              const Eigen::Quaterniond& orientation, bool fixture)
      : name(name),
        object(object),
        position(position),
        orientation(orientation),
        fixture(fixture) {}

  /// The object's or fixture's name, owned by the configuration or the request: a view, so
  /// that placing an object copies no string.
  std::string_view name;
  const ObjectModel* object = nullptr;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  bool fixture = false;
};

/// A pose under test for @p object.
struct Candidate {
  const ObjectModel* object = nullptr;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  /// The entry the candidate stands on (a surface region's target), which the radius test
  /// skips (its circle would cover the surface) and the exact tests check; -1: none.
  std::ptrdiff_t support = -1;
};

/// Decides whether a candidate collides with what is placed. One implementation per test
/// (RadiusChecker, FclChecker, CombinedChecker; makeCollisionChecker() picks one for a
/// CollisionMode); the samplers only see this interface. Implementations may keep acceleration
/// structures, so a checker belongs to one scene at a time (one per thread).
class CollisionChecker {
 public:
  static constexpr std::ptrdiff_t kNone = -1;

  virtual ~CollisionChecker() = default;

  /// Forget every entry (start of a scene).
  virtual void clear() = 0;
  /// Entry @p index of @p entries was just added.
  virtual void added(const std::vector<PlacedEntry>& entries, std::size_t index) = 0;
  /// Not const: a checker may update its own scratch state (FclChecker moves the candidate's
  /// FCL objects to the pose under test).
  /// @return the index of an entry that @p candidate collides with, or kNone
  virtual std::ptrdiff_t firstCollision(const std::vector<PlacedEntry>& entries,
                                        const Candidate& candidate) = 0;
  /// True when the candidate's orientation matters (then it is drawn before the test).
  virtual bool needsOrientation() const = 0;
  /// The exact distance between @p candidate's geometry and entry @p index's [m] (negative: by
  /// how much they penetrate), in @p distance; false when this checker has no exact geometry
  /// (the radius test). Relations' gaps in the fcl modes.
  virtual bool exactDistance(const std::vector<PlacedEntry>& /*entries*/, std::size_t /*index*/,
                             const Candidate& /*candidate*/, double& /*distance*/) {
    return false;
  }
  /// True when every candidate this checker accepts also passes robosuite's radius test
  /// (strategy free_space may then prune with it).
  virtual bool includesRadiusTest() const { return false; }
};

/// Collision modes of the configuration and of requests.
enum class CollisionMode { Radius, Fcl, RadiusAndFcl };

}  // namespace placement_samplers
