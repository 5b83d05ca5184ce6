#pragma once
// The physics of a prepared request: which objects are free bodies, the lazily compiled MuJoCo
// model, and the per-thread step that simulates a sampled scene. Private to the core.

#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "placement_samplers/physics/physics_model.hpp"
#include "placement_samplers/sampling/placement.hpp"
#include "placement_samplers/sampling/scene_config.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {

/// The scene of one PreparedRequest as MuJoCo sees it: every fixture (configured and the
/// request's) static, every object the request's sampler places a free body, except hidden
/// ones (far away, out of the scene).
class ScenePhysics {
 public:
  ScenePhysics(const SceneConfig& config, const PreparedRequest& request);

  const PhysicsSettings& settings() const { return settings_; }
  /// The compiled model, built by the first caller (once, whatever the threads).
  /// @throw RequestError when MuJoCo refuses the model
  std::shared_ptr<const PhysicsModel> model() const;
  /// The body of @p object, or -1 (a hidden object, or not in the scene).
  int bodyOf(const ObjectModel* object) const;
  /// How many of @p threads simulate at once: as many as fit in physics_max_memory_mb with a
  /// new simulation's MuJoCo data each (they share it equally; the results do not depend on
  /// it). Compiles the model.
  /// @throw RequestError as model(), and when not even one fits, with the numbers
  unsigned simulatingThreads(unsigned threads) const;
  /// The share of physics_max_memory_mb of each of @p threads simulating threads [bytes].
  std::uint64_t threadShare(unsigned threads) const;

 private:
  PhysicsSettings settings_;
  std::vector<ObjectPtr> keep_;  ///< the fixtures' geometry, alive as long as the model
  std::vector<PhysicsFixture> fixtures_;
  std::vector<PhysicsBody> bodies_;
  std::unordered_map<const ObjectModel*, int> bodyIndex_;
  mutable std::once_flag once_;
  mutable std::shared_ptr<const PhysicsModel> model_;
};

/// One thread's simulation of sampled scenes.
class PhysicsStep {
 public:
  /// @param maxBytes the most this thread's MuJoCo data may take (ScenePhysics::threadShare)
  PhysicsStep(const ScenePhysics& physics, std::uint64_t maxBytes);

  /// Simulates the placed scene @p result: fills its physics outcomes, `simulated` and
  /// `stable`, and with PhysicsMode::Settle puts the settled poses into its placements.
  /// A MuJoCo error, the deadline or contacts beyond maxBytes fail the scene with a message.
  /// @return the status (TimedOut also for an error or TooLarge: the scene failed)
  PhysicsStatus run(SceneResult& result,
                    std::optional<std::chrono::steady_clock::time_point> deadline);

  /// "physics: no stable scene in N draws; in the last, 'cube' moved 0.03 m (fell)".
  static std::string unstableMessage(const SceneResult& result, std::uint32_t draws);

 private:
  const ScenePhysics& physics_;
  PhysicsWorld world_;
  std::vector<BodyPose> poses_;
  std::vector<PhysicsOutcome> outcomes_;
};

}  // namespace placement_samplers
