#pragma once
// SceneGenerator's per-thread worker: engines, checker, context and the physics step, reused
// from scene to scene. Private to the core (scene_generator.cpp).

#include <array>
#include <chrono>
#include <memory>
#include <optional>

#include "placement_samplers/collision/make_collision_checker.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "placement_samplers/text.hpp"
#include "sampling/scene_physics.hpp"

namespace placement_samplers {

/// Per-thread state, reused from scene to scene: engines, checker and buffers.
class SceneGenerator::Worker {
 public:
  /// Scenes per chunk: a thread takes this many at a time.
  static constexpr std::size_t kChunk = 16;

  /// @param simulatingThreads workers that simulate at once: each takes its share of the
  ///        request's physics memory (ScenePhysics::threadShare)
  Worker(const PreparedRequest& request, double margin, unsigned simulatingThreads = 1)
      : request_(request),
        checker_(makeCollisionChecker(request.collisionCheck, margin)),
        context_(engine_, *checker_, request.maxAttempts),
        objects_(request.sampler->objects().size()) {
    context_.setRequestSurfaces(&request.surfaces);
    if (request.physicsModel) {
      // Compiles the model once, whichever worker comes first.
      physics_ = std::make_unique<PhysicsStep>(
          *request.physicsModel, request.physicsModel->threadShare(simulatingThreads));
    }
  }

  void setDeadline(std::optional<std::chrono::steady_clock::time_point> deadline) {
    context_.setDeadline(deadline);
    context_.setSceneSeconds(request_.maxSceneSeconds);
  }
  /// The request's deadline (a scene's own limit fails that scene only).
  bool expired() const { return context_.requestExpired(); }

  /// Scene @p index of request seed @p seed (numpy's default_rng([seed, index])) into
  /// @p result, whose buffers are reused.
  void run(std::uint64_t seed, std::uint64_t index, SceneResult& result) {
    engine_ = sceneEngine(seed, index);
    context_.setScene(seed, index);
    sample(result);
    result.seed = seed;
    result.index = index;
  }

  /// Counts finished scenes into @p progress and stops when it is cancelled (nullptr: neither).
  void setProgress(SampleProgress* progress) { progress_ = progress; }

  /// Scenes @p index .. @p index + @p count - 1 (count <= kChunk) into @p results, as run()
  /// would give them; once the time limit has passed, the rest come back "not sampled", and
  /// once the progress is cancelled, kCancelledMessage.
  void runChunk(std::uint64_t seed, std::uint64_t index, std::size_t count, SceneResult* results) {
    // Seeded together: each seeding is a chain of dependent multiplications that the CPU
    // overlaps with the others' (Pcg64::forScenes).
    Engine::forScenes(seed, index, count, chunkEngines_.data());
    // Counted per chunk (one atomic add per thread and chunk); per scene when each takes
    // milliseconds of simulation.
    std::uint64_t done = 0;
    std::uint64_t failed = 0;
    const bool countEach = request_.physicsModel != nullptr;
    for (std::size_t k = 0; k < count; ++k) {
      SceneResult& result = results[k];
      result.seed = seed;
      result.index = index + k;
      const bool cancelled =
          progress_ != nullptr && progress_->cancel.load(std::memory_order_relaxed);
      if (cancelled || expired()) {
        notSampled(result,
                   cancelled ? kCancelledMessage : "not sampled: the request ran out of time");
        done += cancelled ? 0 : 1;
        failed += cancelled ? 0 : 1;
        continue;
      }
      engine_ = chunkEngines_[k];
      context_.setScene(seed, index + k);
      sample(result);
      ++done;
      failed += result.success ? 0 : 1;
      if (countEach) {
        flush(done, failed);
      }
    }
    flush(done, failed);
  }

 private:
  void notSampled(SceneResult& result, const char* message) const {
    result.success = false;
    result.message = message;
    result.placements.clear();
    result.physicsMode = request_.physics.mode;
    result.simulated = result.stable = false;
    result.physics.clear();
  }

  /// Adds @p done and @p failed to the progress and zeroes them.
  void flush(std::uint64_t& done, std::uint64_t& failed) {
    if (progress_ != nullptr && done != 0) {
      progress_->done.fetch_add(done, std::memory_order_relaxed);
      progress_->failed.fetch_add(failed, std::memory_order_relaxed);
    }
    done = failed = 0;
  }

  /// Samples the scene, then simulates it when the request asks; with physics_retry an
  /// unstable scene is drawn again from where the engine stopped, up to physics_max_draws.
  void sample(SceneResult& result) {
    result.physicsMode = request_.physics.mode;
    result.simulated = result.stable = false;
    result.physics.clear();
    draw(result);
    if (!physics_) {
      return;
    }
    for (std::uint32_t draws = 1; result.success; ++draws) {
      const PhysicsStatus status = physics_->run(result, context_.sceneDeadline());
      if (status == PhysicsStatus::TimedOut && result.message.rfind("not finished:", 0) == 0 &&
          !expired()) {
        result.message = "not finished: " + context_.outOfTimeReason() + " while simulating it";
      }
      if (status == PhysicsStatus::Stable || status == PhysicsStatus::TimedOut ||
          !request_.physics.retry) {
        return;
      }
      if (draws >= request_.physics.maxDraws) {
        result.success = false;
        result.message = PhysicsStep::unstableMessage(result, draws);
        return;
      }
      result.simulated = result.stable = false;
      result.physics.clear();
      draw(result);
    }
  }

  void draw(SceneResult& result) {
    context_.clear();
    result.success = false;
    result.message.clear();
    const std::vector<FixtureSpec>& fixtures = request_.fixtures;
    for (std::size_t i = 0; i < fixtures.size(); ++i) {
      // Adding thousands of fixtures to FCL's broadphase takes long too: the clock covers it.
      if ((i & 63u) == 63u && expired()) {
        result.message = "not sampled: the request ran out of time while adding its " +
                         countText(fixtures.size(), "fixture");
        result.placements.clear();
        return;
      }
      const FixtureSpec& f = fixtures[i];
      context_.addFixture(f.name, f.object.get(), f.position, f.orientation);
    }
    // The placements are built in the buffer the previous swap gave the context: a result's
    // from the caller's previous block, or a fresh one (one allocation of the right size).
    context_.placements().reserve(objects_);
    result.success = request_.sampler->sample(context_, request_.reference, request_.onTop);
    if (!result.success) {
      result.message = context_.failure() ? context_.failure()->message : "sampling failed";
    }
    // The result takes the placements and gives the context its old buffer: no copy, and no
    // allocation once the caller's results have been filled before.
    result.placements.swap(context_.placements());
  }

  const PreparedRequest& request_;
  Engine engine_;  ///< the scene's stream, which context_ draws from
  std::array<Engine, kChunk> chunkEngines_;
  std::unique_ptr<CollisionChecker> checker_;
  SampleContext context_;
  std::size_t objects_;                   ///< objects the sampler places
  std::unique_ptr<PhysicsStep> physics_;  ///< none when the request's physics is none
  SampleProgress* progress_ = nullptr;
};

}  // namespace placement_samplers
