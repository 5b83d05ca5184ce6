#pragma once

#include <Eigen/Geometry>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "placement_samplers/sampling/placement.hpp"
#include "placement_samplers/sampling/placement_sampler.hpp"
#include "placement_samplers/sampling/scene_config.hpp"

namespace placement_samplers {

/// A fixture given with a request: a configured object's geometry or a primitive shape.
struct RequestFixture {
  std::string name;
  std::string object;          ///< a configured object, or "" to use @ref shape
  std::optional<Shape> shape;  ///< used when @ref object is empty
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

/// What varies per call. Empty members take the configured values.
struct SampleRequest {
  std::string sampler;  ///< "" = the root composite; else any sampler by name
  std::vector<RequestFixture> fixtures;
  Reference reference;        ///< Default = as configured
  std::optional<bool> onTop;  ///< unset = true, as robosuite
  std::optional<CollisionMode> collisionCheck;
  std::uint32_t maxAttempts = 0;  ///< 0 = as configured
  /// Time limit of the whole request, from the start of SceneGenerator::prepare() [s];
  /// 0 = none; at most limits::kRequestSeconds.
  double maxSeconds = 0.0;
  /// Time limit of each scene [s] (sampling and simulation, from the scene's first check of
  /// the clock: SampleContext::setSceneSeconds); 0 = none; at most limits::kRequestSeconds.
  double maxSceneSeconds = 0.0;
  std::optional<PhysicsMode> physics;  ///< unset = as configured
};

class ScenePhysics;

/// A request checked against the configuration, ready to sample any number of scenes.
struct PreparedRequest {
  const PlacementSampler* sampler = nullptr;
  Reference reference;
  bool onTop = true;
  CollisionMode collisionCheck = CollisionMode::Radius;
  std::uint32_t maxAttempts = 0;
  double maxSeconds = 0.0;
  double maxSceneSeconds = 0.0;  ///< each scene's limit [s]; 0 = none
  /// When the request must stop: prepare()'s start + maxSeconds; unset = never.
  std::optional<std::chrono::steady_clock::time_point> deadline;
  std::vector<FixtureSpec> fixtures;  ///< configured fixtures, then the request's
  /// What the caller should know although the request is valid, e.g. a call-level reference
  /// that no sampler takes because each sets its own in sample_args.
  std::vector<std::string> notes;
  /// The configuration's physics settings with the request's mode.
  PhysicsSettings physics;
  /// The surfaces of this request's fixtures that surface regions stand on.
  RequestSurfaces surfaces;
  /// The request's MuJoCo model, built on first use (none when physics.mode is none) and
  /// shared by the threads that sample it.
  std::shared_ptr<ScenePhysics> physicsModel;
};

/// A range being sampled, watched from another thread: how many scenes are finished, and a way
/// to stop it between scenes. Neither changes any scene's result.
struct SampleProgress {
  /// Scenes finished (placed, failed, or failed unsampled after the time limit), counted as
  /// they finish: after each scene when the request simulates, else every few scenes.
  std::atomic<std::uint64_t> done{0};
  std::atomic<std::uint64_t> failed{0};  ///< of them, the failed ones
  /// Set from any thread: every scene not yet begun comes back failed with kCancelledMessage
  /// (scenes under way finish first), and counts as neither done nor failed.
  std::atomic<bool> cancel{false};
};

/// The message of a scene that was not sampled because its range was cancelled.
constexpr const char* kCancelledMessage = "not sampled: cancelled";

/// True for a scene that SampleProgress::cancel left unsampled.
bool wasCancelled(const SceneResult& scene);

/// Scenes @p first .. @p first + @p count - 1 must have indices below 2^64.
/// @throw RequestError with both numbers otherwise
void checkSceneRange(std::uint64_t first, std::uint64_t count);

/// Samples scenes from one configuration. Immutable and safe to share between threads.
class SceneGenerator {
 public:
  explicit SceneGenerator(std::shared_ptr<const SceneConfig> config);

  const SceneConfig& config() const { return *config_; }
  std::shared_ptr<const SceneConfig> configPtr() const { return config_; }

  /// Checks @p request: sampler, reference, fixtures (names, objects, shapes, poses), at most
  /// SceneConfig::maxFixturesPerRequest fixtures, positions within +-limits::kCoordinate.
  /// Starts the request's clock: its time limit (SampleRequest::maxSeconds) covers this
  /// preparation, the fixtures added to each scene and the sampling, so a PreparedRequest
  /// serves one request. Near-linear in the number of fixtures.
  /// @throw RequestError saying what is wrong, or that the time ran out while checking
  PreparedRequest prepare(const SampleRequest& request) const;

  /// Placements in each scene of @p request: the objects its sampler places, hidden ones
  /// included.
  std::uint64_t placementsPerScene(const PreparedRequest& request) const;

  /// Refuses an answer of @p numScenes scenes of @p request whose placements (scenes x objects
  /// placed) would exceed SceneConfig::maxPlacementsPerRequest. sampleScenes() calls it; a
  /// caller may call it first to refuse before doing anything else.
  /// @throw RequestError with the numbers and the largest number of scenes allowed
  void checkAnswerSize(const PreparedRequest& request, std::uint64_t numScenes) const;

  /// The limits of one service request of @p numScenes scenes: at most
  /// SceneConfig::maxScenesPerRequest scenes, and checkAnswerSize(). The CLI, which streams its
  /// scenes in blocks, has neither limit.
  /// @throw RequestError naming the limit and the numbers
  void checkRequestSize(const PreparedRequest& request, std::uint64_t numScenes) const;

  /// Scene @p index of a request seeded with @p seed; the same whatever else is sampled: what
  /// robosuite's samplers give with numpy.random.default_rng([seed, index]) (README).
  SceneResult sampleScene(const PreparedRequest& request, std::uint64_t seed,
                          std::uint64_t index) const;

  /// Scenes 0 .. count-1 over @p threads threads (0 = one per core); the result does not depend
  /// on the thread count. When the request's time limit passes, the scene under way fails and
  /// the ones not started come back failed with "not sampled".
  /// @throw RequestError when the answer would be too large (checkAnswerSize)
  std::vector<SceneResult> sampleScenes(const PreparedRequest& request, std::uint64_t seed,
                                        std::uint64_t count, unsigned threads = 1) const;

  /// Scenes @p first .. first + count - 1 of the same numbering: a long request taken in
  /// blocks gives the scenes sampleScenes() would, and so do processes that each take a piece
  /// (sharding; the CLI writes its output so; no answer size limit here). The time limit counts
  /// from prepare().
  /// @throw RequestError when @p first + @p count exceeds 2^64 - 1 (scene indices are uint64)
  std::vector<SceneResult> sampleSceneRange(const PreparedRequest& request, std::uint64_t seed,
                                            std::uint64_t first, std::uint64_t count,
                                            unsigned threads = 1) const;

  /// As above, into @p results (resized to @p count). The results' buffers are reused: a
  /// caller that takes many blocks into the same vector allocates nothing per scene once the
  /// first block is done (a scene's placements otherwise cost one allocation and one free).
  /// @throw RequestError when @p first + @p count exceeds 2^64 - 1
  /// @param progress counts the finished scenes and may cancel the rest (none: nullptr)
  void sampleSceneRange(const PreparedRequest& request, std::uint64_t seed, std::uint64_t first,
                        std::uint64_t count, unsigned threads, std::vector<SceneResult>& results,
                        SampleProgress* progress = nullptr) const;

  /// As sampleSceneRange(), but when the first @p probe scenes of the range all failed the
  /// rest are not sampled: @p results then holds only those, and the request is hopeless in
  /// all likelihood (the node answers it at once instead of spending its time limit).
  /// A cancelled range never gives up: its scenes not begun come back cancelled.
  /// @param probe scenes to try first; 0 = never give up
  /// @param progress as for sampleSceneRange()
  /// @return true when it gave up
  bool sampleSceneRangeOrGiveUp(const PreparedRequest& request, std::uint64_t seed,
                                std::uint64_t first, std::uint64_t count, unsigned threads,
                                std::uint64_t probe, std::vector<SceneResult>& results,
                                SampleProgress* progress = nullptr) const;

 private:
  class Worker;
  void sampleInto(const PreparedRequest& request, std::uint64_t seed, std::uint64_t first,
                  std::uint64_t count, unsigned threads, SceneResult* results,
                  SampleProgress* progress) const;
  std::shared_ptr<const SceneConfig> config_;
};

}  // namespace placement_samplers
