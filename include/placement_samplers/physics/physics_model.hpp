#pragma once

#include <Eigen/Geometry>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "placement_samplers/geometry/object_model.hpp"
#include "placement_samplers/physics/physics_settings.hpp"

namespace placement_samplers {

/// A static part of the simulated scene: a fixture at its pose.
struct PhysicsFixture {
  const ObjectModel* object = nullptr;                 ///< its geometry
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

/// A free body of the simulated scene: an object the request's sampler places.
struct PhysicsBody {
  const ObjectModel* object = nullptr;  ///< its geometry (every shape of it)
  /// The clearance it is sampled with on purpose [m]: its sampler's z_offset, plus the positive
  /// gaps between the offsets it is placed by and the geometry (ObjectModel::bottomGap, its
  /// reference's topGap), plus, for an object stacked on a placed one, that one's clearance; it
  /// is released that much lower, and "moved" does not count it.
  double zOffset = 0.0;
  double density = 500.0;  ///< [kg/m^3]
};

/// A pose of a body's frame (the object's origin) [m].
struct BodyPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

/// A MuJoCo model of one request's scene: the fixtures as static geoms of the world, the ground
/// plane when the settings have one, and one free body per placed object, its mass from its
/// density. Built once, read-only afterwards: every thread simulates it with a PhysicsWorld of
/// its own. MuJoCo collides a mesh by its convex hull (README, "Physics").
class PhysicsModel {
 public:
  /// Generates the model's MJCF text and compiles it with MuJoCo. Its contact buffers are
  /// sized for the bodies resting (PhysicsWorld grows them when a scene needs more).
  /// @throw RequestError with MuJoCo's reason when it refuses the model (a flat mesh, a body
  ///        too light, named by its object), or when one simulation's MuJoCo data would take
  ///        more than settings.maxMemoryMb, with the numbers
  PhysicsModel(const std::vector<PhysicsFixture>& fixtures, const std::vector<PhysicsBody>& bodies,
               const PhysicsSettings& settings);
  ~PhysicsModel();
  PhysicsModel(const PhysicsModel&) = delete;
  PhysicsModel& operator=(const PhysicsModel&) = delete;

  const PhysicsSettings& settings() const;
  std::size_t bodyCount() const;
  /// The MJCF text the model was compiled from.
  const std::string& mjcf() const;
  /// Mass of free body @p body as MuJoCo computed it [kg].
  double mass(std::size_t body) const;
  /// Bytes of a new PhysicsWorld's MuJoCo data (its buffers, arrays and stack).
  std::uint64_t worldBytes() const;

 private:
  friend class PhysicsWorld;
  /// Throws RequestError when @p bytes of MuJoCo data exceed the settings' maxMemoryMb, or
  /// when MuJoCo cannot allocate them (@p fitsMujoco false).
  void checkBytes(std::uint64_t bytes, bool fitsMujoco) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// How a simulation ended.
enum class PhysicsStatus {
  Stable,    ///< every object moved and turned less than the tolerances, none fell
  Unstable,  ///< some object moved, turned or fell too far
  Diverged,  ///< MuJoCo reset the state (a bad acceleration): no settled poses
  TimedOut,  ///< the deadline passed during the simulation
  TooLarge   ///< the scene's contacts need larger buffers than the world's maxBytes allow
};

/// One thread's simulation state of a PhysicsModel (MuJoCo's mjData), reused scene after scene.
/// Each simulation starts from reset data, so its result depends on the model and the poses
/// alone, whatever ran before on this thread or on others. A scene with more contacts than
/// its buffers hold is simulated again with buffers twice as large (kept for the next scenes),
/// as long as they take at most maxBytes: the result is the one of buffers large enough.
class PhysicsWorld {
 public:
  /// @param maxBytes the most its MuJoCo data may grow to [bytes]
  explicit PhysicsWorld(std::shared_ptr<const PhysicsModel> model,
                        std::uint64_t maxBytes = std::uint64_t{1} << 31);
  ~PhysicsWorld();
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;

  /// Simulates the bodies released at rest at @p poses (one per body, in the model's order),
  /// each lowered by its clearance (PhysicsBody::zOffset),
  /// for the settings' seconds; @p poses become the settled poses and @p outcomes (resized) say
  /// how far each moved and turned and whether it fell.
  /// @param deadline the simulation stops when it passes (checked every few steps)
  /// @throw std::runtime_error when MuJoCo reports an error
  PhysicsStatus simulate(std::vector<BodyPose>& poses, std::vector<PhysicsOutcome>& outcomes,
                         std::optional<std::chrono::steady_clock::time_point> deadline = {});

  std::uint64_t bytes() const;            ///< its MuJoCo data now [bytes]
  std::uint64_t maxBytes() const;         ///< the most it may take [bytes]
  std::uint64_t contactCapacity() const;  ///< contacts its buffers hold now

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace placement_samplers
