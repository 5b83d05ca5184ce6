#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "placement_samplers/object_model.hpp"

namespace placement_samplers {

/// Something already in the scene: a fixture or an object placed earlier in the scene.
struct PlacedEntry {
  std::string name;
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
};

/// Decides whether a candidate collides with what is placed. One implementation per test; the
/// samplers only see this interface. Implementations may keep acceleration structures, so a
/// checker belongs to one scene at a time (one per thread).
class CollisionChecker {
 public:
  static constexpr std::ptrdiff_t kNone = -1;

  virtual ~CollisionChecker() = default;

  /// Forget every entry (start of a scene).
  virtual void clear() = 0;
  /// Entry @p index of @p entries was just added.
  virtual void added(const std::vector<PlacedEntry>& entries, std::size_t index) = 0;
  /// @return the index of an entry that @p candidate collides with, or kNone
  virtual std::ptrdiff_t firstCollision(const std::vector<PlacedEntry>& entries,
                                        const Candidate& candidate) const = 0;
  /// True when the candidate's orientation matters (then it is drawn before the test).
  virtual bool needsOrientation() const = 0;
};

/// robosuite's test: the x-y circles overlap (touching counts) and the candidate's bottom is
/// below the other's top: `z - z_o <= top_o - bottom`. One-sided in z, so stacking passes.
/// Scans every entry: robosuite's cost, but no allocation and no branches beyond the test.
class RadiusChecker : public CollisionChecker {
 public:
  void clear() override {}
  void added(const std::vector<PlacedEntry>&, std::size_t) override {}
  std::ptrdiff_t firstCollision(const std::vector<PlacedEntry>& entries,
                                const Candidate& candidate) const override;
  bool needsOrientation() const override { return false; }
};

/// True when robosuite's test says @p candidate overlaps @p other.
bool radiusOverlap(const PlacedEntry& other, const Candidate& candidate);

/// Collision modes of the configuration and of requests.
enum class CollisionMode { Radius, Fcl, RadiusAndFcl };

/// "radius", "fcl" or "radius_and_fcl".
const char* collisionModeName(CollisionMode mode);

/// A checker for @p mode with clearance @p margin [m] in the exact modes.
/// @throw ConfigError when the mode is not available in this build
std::unique_ptr<CollisionChecker> makeCollisionChecker(CollisionMode mode, double margin);

}  // namespace placement_samplers
