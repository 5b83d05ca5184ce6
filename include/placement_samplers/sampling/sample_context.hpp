#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "placement_samplers/collision/collision_checker.hpp"
#include "placement_samplers/sampling/placement.hpp"
#include "placement_samplers/sampling/random.hpp"
#include "placement_samplers/sampling/surface_region.hpp"
#include "placement_samplers/sampling/uniform_source.hpp"

namespace placement_samplers {

/// Everything that varies within one scene, handed down the sampler tree. Samplers keep no
/// per-call state, so one tree serves every thread; each thread owns its context.
class SampleContext {
 public:
  /// @param checker the collision test of this scene (owned by the caller)
  /// @param maxAttempts overrides every sampler's limit when non-zero
  SampleContext(Engine& engine, CollisionChecker& checker, std::uint32_t maxAttempts = 0);

  /// Forget every entry and placement, keep the buffers (start of a scene).
  void clear();
  /// Adds a fixture: checked against, never moved, not part of the placements.
  /// @p name must outlive the scene (failure messages read it).
  void addFixture(std::string_view name, const ObjectModel* object, const Eigen::Vector3d& position,
                  const Eigen::Quaterniond& orientation);
  /// Records @p candidate, accepted by sampler @p sampler after @p attempts samples, as a
  /// placement and makes it an obstacle for the following ones.
  void addPlacement(std::string_view sampler, const Candidate& candidate, std::uint32_t attempts,
                    bool hidden, std::int16_t restPose = ObjectPlacement::kUpright);

  /// The fixture or placed object called @p name, or nullptr.
  const PlacedEntry* find(const std::string& name) const;

  /// @return the index of an entry that @p candidate collides with, or CollisionChecker::kNone
  /// Not const: the checker may move its scratch objects (CollisionChecker::firstCollision).
  std::ptrdiff_t firstCollision(const Candidate& candidate) {
    return checker_.firstCollision(entries_, candidate);
  }
  bool needsOrientation() const { return checker_.needsOrientation(); }
  /// The exact distance between @p candidate and entry @p index [m] (CollisionChecker::
  /// exactDistance()); false under the radius test.
  bool exactDistance(std::size_t index, const Candidate& candidate, double& distance) {
    return checker_.exactDistance(entries_, index, candidate, distance);
  }
  bool includesRadiusTest() const { return checker_.includesRadiusTest(); }

  /// Per-entry rejection counters, zeroed, sized for the current entries.
  std::vector<std::uint32_t>& blockerCounts();

  /// Records why the scene failed; the sampling stops.
  void fail(Failure failure) { failure_ = std::move(failure); }

  /// Sampling stops with a failure once @p deadline has passed (checked every 1024 attempts,
  /// and at a similar cost in the other loops of the strategies).
  void setDeadline(std::optional<std::chrono::steady_clock::time_point> deadline) {
    deadline_ = deadline;
  }
  /// Each scene stops with a failure once it has run for @p seconds (0 = no limit) [s]. Its
  /// clock starts at the scene's first check of the time (within its first 1024 attempts), so
  /// that a quick scene never reads the clock.
  void setSceneSeconds(double seconds);
  /// True once the request's deadline has passed.
  bool requestExpired() const { return deadline_ && std::chrono::steady_clock::now() > *deadline_; }
  /// True once the request's deadline or the scene's limit has passed (the first call of a
  /// scene starts its clock).
  bool expired();
  /// The earlier of the request's deadline and the scene's (whose clock this starts), or none.
  std::optional<std::chrono::steady_clock::time_point> sceneDeadline();
  /// Why expired() is true: "the request ran out of time" or "the scene ran out of time (its
  /// limit is N s)".
  std::string outOfTimeReason() const;

  /// The scene's stream: every draw of the samplers, hidden objects excepted.
  Engine& engine() { return *engine_; }
  /// Draws from @p engine from now on.
  void setEngine(Engine& engine) { engine_ = &engine; }
  /// Makes this scene @p index of request seed @p seed for hiddenEngine() (the scene's own
  /// engine is the caller's: setEngine()).
  void setScene(std::uint64_t seed, std::uint64_t index) {
    seed_ = seed;
    index_ = index;
    hiddenSeeded_ = false;
    sceneStarted_ = false;
  }
  /// The hidden objects' stream (random.hpp's hiddenEngine(seed, index)), seeded on first use:
  /// hidden objects draw nothing from engine(), as robosuite's hide sampler has a generator of
  /// its own.
  Engine& hiddenEngine() {
    if (!hiddenSeeded_) {
      hiddenEngine_ = placement_samplers::hiddenEngine(seed_, index_);
      hiddenSeeded_ = true;
    }
    return hiddenEngine_;
  }
  std::uint32_t maxAttempts() const { return maxAttempts_; }
  /// Uniform samplers draw from @p source (owned by the caller) instead of engine() and
  /// hiddenEngine(); nullptr = from the engines again.
  void setUniformSource(UniformSource* source) { uniformSource_ = source; }
  UniformSource* uniformSource() const { return uniformSource_; }
  /// The surfaces of the request's fixtures that surface regions stand on (or nullptr).
  void setRequestSurfaces(const RequestSurfaces* surfaces) { requestSurfaces_ = surfaces; }
  const RequestSurfaces* requestSurfaces() const { return requestSurfaces_; }
  /// This thread's draws on surfaces known only in a scene; kept across scenes.
  SurfaceDrawCache& surfaceCache() {
    if (!surfaceCache_) {
      surfaceCache_ = std::make_unique<SurfaceDrawCache>();
    }
    return *surfaceCache_;
  }
  const std::vector<PlacedEntry>& entries() const { return entries_; }
  const std::vector<ObjectPlacement>& placements() const { return placements_; }
  std::vector<ObjectPlacement>& placements() { return placements_; }
  const std::optional<Failure>& failure() const { return failure_; }

 private:
  Engine* engine_;
  Engine hiddenEngine_;
  std::uint64_t seed_ = 0;
  std::uint64_t index_ = 0;
  bool hiddenSeeded_ = false;
  CollisionChecker& checker_;
  std::uint32_t maxAttempts_;
  const RequestSurfaces* requestSurfaces_ = nullptr;
  UniformSource* uniformSource_ = nullptr;
  std::unique_ptr<SurfaceDrawCache> surfaceCache_;
  std::vector<PlacedEntry> entries_;
  std::vector<ObjectPlacement> placements_;
  std::vector<std::uint32_t> blockerCounts_;
  std::optional<Failure> failure_;
  std::optional<std::chrono::steady_clock::time_point> deadline_;
  double sceneSeconds_ = 0.0;
  std::chrono::steady_clock::duration sceneLimit_{};
  bool sceneStarted_ = false;  ///< sceneEnd_ holds this scene's end
  std::chrono::steady_clock::time_point sceneEnd_;
};

}  // namespace placement_samplers
