#pragma once

// Shared by the tables of placement_benchmark: options, timing, the scene loop without results,
// statistics, configuration set-up and the table functions. Not installed.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Geometry>

#include "placement_samplers/collision/collision_checker.hpp"
#include "placement_samplers/collision/make_collision_checker.hpp"
#include "placement_samplers/collision/radius_checker.hpp"
#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/process/malloc_tuning.hpp"
#include "placement_samplers/geometry/mesh_loader.hpp"
#include "placement_samplers/sampling/random.hpp"
#include "placement_samplers/sampling/sample_context.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "placement_samplers/output/scene_json.hpp"
#include "../clutter_scene.hpp"

namespace ps = placement_samplers;

namespace bench {

using Clock = std::chrono::steady_clock;

constexpr std::uint64_t kSeed = 20240605;  // every figure uses this request seed
constexpr std::size_t kCandidatePool = 1 << 16;

/// The package's config/ as ROS_PACKAGE_PATH finds it, else the source tree's.
std::string defaultConfigDir();

/// Options of one run.
struct Options {
  std::string configDir = defaultConfigDir();
  int repetitions = 5;         ///< timed repetitions per figure; the median is printed
  double secondsPerRep = 0.1;  ///< [s] target length of one repetition
  std::uint64_t batchScenes = 10000;
  std::uint64_t statScenes = 2000;       ///< scenes behind attempts per object and failure rate
  std::vector<std::string> configFiles;  ///< --config: time these files only
  bool defaultMalloc = false;            ///< --default-malloc: glibc's defaults
};

/// Keeps results observable so the optimiser cannot drop the work.
extern volatile double gSink;

double median(std::vector<double> v);

/// Median over repetitions of the time per operation [ns]. @p body(n) performs n operations.
/// The operation count is calibrated so that one repetition lasts about secondsPerRep.
template <class Body>
double nsPerOp(const Options& options, Body&& body) {
  std::uint64_t n = 1;
  double elapsed = 0.0;
  for (;;) {
    const Clock::time_point start = Clock::now();
    body(n);
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    if (elapsed >= 0.02 || n >= (1ull << 32)) {
      break;
    }
    n *= 4;
  }
  n = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(n * options.secondsPerRep / elapsed));
  std::vector<double> samples;
  for (int r = 0; r < options.repetitions; ++r) {
    const Clock::time_point start = Clock::now();
    body(n);
    samples.push_back(std::chrono::duration<double, std::nano>(Clock::now() - start).count() /
                      static_cast<double>(n));
  }
  return median(samples);
}

/// robosuite's brute-force radius test: every entry, in order. The reference the grid of
/// RadiusChecker is compared against, in time and in results.
class ScanChecker : public ps::CollisionChecker {
 public:
  void clear() override {}
  void added(const std::vector<ps::PlacedEntry>&, std::size_t) override {}
  std::ptrdiff_t firstCollision(const std::vector<ps::PlacedEntry>& entries,
                                const ps::Candidate& candidate) override {
    for (std::size_t i = 0; i < entries.size(); ++i) {
      if (ps::radiusOverlap(entries[i], candidate)) {
        return static_cast<std::ptrdiff_t>(i);
      }
    }
    return kNone;
  }
  bool needsOrientation() const override { return false; }
};

/// The scene loop of SceneGenerator's worker without building results: an engine, a checker
/// and a context kept from scene to scene.
class SceneLoop {
 public:
  SceneLoop(const ps::PreparedRequest& request, std::unique_ptr<ps::CollisionChecker> checker)
      : request_(request), checker_(std::move(checker)), context_(engine_, *checker_, 0) {}

  /// Samples one scene with the engine as it is; false when the scene failed.
  bool scene() {
    context_.clear();
    for (const ps::FixtureSpec& f : request_.fixtures) {
      context_.addFixture(f.name, f.object.get(), f.position, f.orientation);
    }
    return request_.sampler->sample(context_, request_.reference, request_.onTop);
  }

  /// Scenes with one engine seeded once: the cost of sampling alone [ns/scene].
  void runReused(std::uint64_t n) {
    engine_ = ps::Engine(kSeed);
    double sum = 0.0;
    for (std::uint64_t i = 0; i < n; ++i) {
      scene();
      sum += lastX();
    }
    gSink = gSink + sum;
  }

  /// Scenes seeded from (seed, i) as the service and the CLI do.
  void runSeeded(std::uint64_t n) {
    double sum = 0.0;
    for (std::uint64_t i = 0; i < n; ++i) {
      seedScene(i);
      scene();
      sum += lastX();
    }
    gSink = gSink + sum;
  }

  /// Scene @p i of kSeed: numpy's default_rng([kSeed, i]), as SceneGenerator does.
  void seedScene(std::uint64_t i) {
    engine_ = ps::sceneEngine(kSeed, i);
    context_.setScene(kSeed, i);
  }

  const ps::SampleContext& context() const { return context_; }
  ps::SampleContext& context() { return context_; }
  ps::Engine& engine() { return engine_; }

 private:
  double lastX() const {
    const auto& p = context_.placements();
    return p.empty() ? 0.0 : p.back().position.x();
  }

  const ps::PreparedRequest& request_;
  ps::Engine engine_;
  std::unique_ptr<ps::CollisionChecker> checker_;
  ps::SampleContext context_;
};

/// Attempts and failures over a fixed set of seeded scenes.
struct SceneStats {
  std::uint64_t scenes = 0;
  std::uint64_t failed = 0;
  std::uint64_t objects = 0;   ///< objects tried (placed, or the one that failed)
  std::uint64_t attempts = 0;  ///< samples drawn for them
  double checksum = 0.0;       ///< sum of every placed coordinate: equal runs, equal sums

  double attemptsPerObject() const { return objects ? double(attempts) / double(objects) : 0.0; }
  double failureRate() const { return scenes ? double(failed) / double(scenes) : 0.0; }
};
SceneStats collectStats(SceneLoop& loop, std::uint64_t scenes);

/// A loaded configuration with the default request prepared.
struct Setup {
  std::unique_ptr<ps::SceneGenerator> generator;
  ps::PreparedRequest request;
};
Setup makeSetup(const ps::ConfigNode& tree, std::optional<ps::CollisionMode> mode = std::nullopt);

/// Scenes 0 .. n - 1 in blocks of 8192 through SceneGenerator::sampleSceneRange, as
/// sample_scenes takes them; @p onBlock sees each block's results.
template <class OnBlock>
void sampleInBlocks(const Setup& setup, std::uint64_t n, unsigned threads, OnBlock&& onBlock) {
  constexpr std::uint64_t kBlock = 8192;
  std::vector<ps::SceneResult> results;  // reused from block to block, as sample_scenes does
  for (std::uint64_t first = 0; first < n; first += kBlock) {
    setup.generator->sampleSceneRange(setup.request, kSeed, first, std::min(kBlock, n - first),
                                      threads, results);
    onBlock(results);
  }
}

/// Time per scene [ns] of sampleInBlocks on @p threads threads (results built, then freed).
double batchNs(const Options& options, const Setup& setup, unsigned threads);

/// True when this build offers collision_check fcl.
bool fclAvailable();

/// Least-squares slope of log(y) against log(x).
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y);

/// @p v printed with the printf @p format.
std::string fmt(const char* format, double v);
/// A table's horizontal rule.
void rule();

// The tables, one function each (blocks.cpp, environments.cpp, clutter.cpp).
void benchBlocks(const Options& options);
void benchEnvironments(const Options& options);
void benchClutter(const Options& options);
void benchStrategies(const Options& options);
void benchFcl(const Options& options);
void benchBatch(const Options& options);
void benchConfigFiles(const Options& options);
void benchSurfaces(const Options& options);

}  // namespace bench
