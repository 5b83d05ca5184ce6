// placement_benchmark: fixed configurations and seeds, timed on one core (and on two for the
// batch), printed as plain tables. Not a test: it asserts nothing about time. See
// docs/benchmarks.md for the figures and how to read them.

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
#include "physics_bench.hpp"

#ifndef PLACEMENT_SAMPLERS_CONFIG_DIR
#define PLACEMENT_SAMPLERS_CONFIG_DIR "config"
#endif

namespace ps = placement_samplers;

namespace {

using Clock = std::chrono::steady_clock;

constexpr std::uint64_t kSeed = 20240605;  // every figure uses this request seed
constexpr std::size_t kCandidatePool = 1 << 16;

/// The package's config/ as ROS_PACKAGE_PATH finds it (the install space's share directory
/// once installed, the source tree in a devel space), else the source tree it was built from.
std::string defaultConfigDir() {
  const std::string package = ps::findPackageInRosPackagePath("placement_samplers");
  if (!package.empty() && std::filesystem::is_directory(package + "/config")) {
    return package + "/config";
  }
  return PLACEMENT_SAMPLERS_CONFIG_DIR;
}

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
volatile double gSink = 0.0;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

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

SceneStats collectStats(SceneLoop& loop, std::uint64_t scenes) {
  SceneStats stats;
  for (std::uint64_t i = 0; i < scenes; ++i) {
    loop.seedScene(i);
    const bool ok = loop.scene();
    ++stats.scenes;
    for (const ps::ObjectPlacement& p : loop.context().placements()) {
      ++stats.objects;
      stats.attempts += p.attempts;
      stats.checksum += p.position.x() + p.position.y() + p.position.z();
    }
    if (!ok) {
      ++stats.failed;
      if (loop.context().failure()) {
        ++stats.objects;
        stats.attempts += loop.context().failure()->attempts;
      }
    }
  }
  return stats;
}

/// A loaded configuration with the default request prepared.
struct Setup {
  std::unique_ptr<ps::SceneGenerator> generator;
  ps::PreparedRequest request;
};

Setup makeSetup(const ps::ConfigNode& tree, std::optional<ps::CollisionMode> mode = std::nullopt) {
  Setup setup;
  setup.generator = std::make_unique<ps::SceneGenerator>(ps::buildSceneConfig(tree));
  ps::SampleRequest request;
  request.collisionCheck = mode;
  setup.request = setup.generator->prepare(request);
  return setup;
}

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
double batchNs(const Options& options, const Setup& setup, unsigned threads) {
  return nsPerOp(options, [&](std::uint64_t n) {
    sampleInBlocks(setup, n, threads, [](const std::vector<ps::SceneResult>& results) {
      gSink = gSink + static_cast<double>(results.back().placements.size());
    });
  });
}

/// The clutter scene: @p n cylinders (radius 0.03 m, height 0.1 m) in one sampler over a
/// square region of half width @p half [m] (0.6 m x 0.6 m by default),
/// ensure_object_boundary_in_range and ensure_valid_placement on. Built from YAML text through
/// the same builder as the files in config/.
std::string clutterYaml(int n, double half = 0.3) {
  std::ostringstream y;
  y << "collision_check: radius\nmax_attempts: 5000\nobjects:\n";
  for (int i = 0; i < n; ++i) {
    y << "  cyl" << i << ": {shape: cylinder, radius: 0.03, length: 0.1}\n";
  }
  y << "samplers:\n  - name: ClutterSampler\n    objects: [";
  for (int i = 0; i < n; ++i) {
    y << (i ? ", " : "") << "cyl" << i;
  }
  y << "]\n    x_range: [" << -half << ", " << half << "]\n    y_range: [" << -half << ", " << half
    << "]\n"
       "    rotation_axis: z\n    ensure_object_boundary_in_range: true\n"
       "    ensure_valid_placement: true\n    reference_pos: [0.0, 0.0, 0.8]\n    z_offset: 0.0\n";
  return y.str();
}

bool fclAvailable() {
  try {
    ps::makeCollisionChecker(ps::CollisionMode::Fcl, 0.0);
    return true;
  } catch (const ps::ConfigError&) {
    return false;
  }
}

/// Least-squares slope of log(y) against log(x).
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]);
    const double ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

std::string fmt(const char* format, double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, v);
  return buffer;
}

void rule() { std::printf("%s\n", std::string(100, '-').c_str()); }

/// xoshiro256** (Blackman and Vigna), seeded through SplitMix64: not used by the library, only
/// timed here as what a small-state engine would cost per scene.
class Xoshiro256 {
 public:
  void seed(std::uint64_t s) {
    for (std::uint64_t& word : state_) {
      s += 0x9e3779b97f4a7c15ULL;
      std::uint64_t z = s;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      word = z ^ (z >> 31);
    }
  }
  std::uint64_t operator()() {
    const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t state_[4] = {1, 2, 3, 4};
};

/// seed(kSeed + i) and one draw per operation, for engine type @p E.
template <class E>
double seedAndDrawNs(const Options& options) {
  E engine;
  return nsPerOp(options, [&](std::uint64_t n) {
    std::uint64_t sum = 0;
    for (std::uint64_t i = 0; i < n; ++i) {
      engine.seed(kSeed + i);
      sum += engine();
    }
    gSink = gSink + static_cast<double>(sum);
  });
}

/// The building blocks of a scene's cost: seeding the engine per scene (numpy's SeedSequence
/// of [seed, i] and PCG64's seeding), a draw from a running engine, the orientation of a
/// placed object, and one radius query in a filled clutter scene.
void benchBlocks(const Options& options) {
  ps::Engine engine(kSeed);
  const double seedAndDraw = nsPerOp(options, [&](std::uint64_t n) {
    std::uint64_t sum = 0;
    for (std::uint64_t i = 0; i < n; ++i) {
      engine = ps::sceneEngine(kSeed, i);
      sum += engine();
    }
    gSink = gSink + static_cast<double>(sum);
  });
  const double hiddenSeed = nsPerOp(options, [&](std::uint64_t n) {
    std::uint64_t sum = 0;
    for (std::uint64_t i = 0; i < n; ++i) {
      engine = ps::hiddenEngine(kSeed, i);
      sum += engine();
    }
    gSink = gSink + static_cast<double>(sum);
  });
  const double draw = nsPerOp(options, [&](std::uint64_t n) {
    double sum = 0;
    for (std::uint64_t i = 0; i < n; ++i) {
      sum += ps::uniform01(engine);
    }
    gSink = gSink + sum;
  });
  const Eigen::Quaterniond init = Eigen::Quaterniond::Identity();
  const double orientation = nsPerOp(options, [&](std::uint64_t n) {
    double sum = 0;
    for (std::uint64_t i = 0; i < n; ++i) {
      const double angle = 1e-7 * static_cast<double>(i);
      const Eigen::Quaterniond q =
          Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())) * init;
      sum += q.w() + q.z();
    }
    gSink = gSink + sum;
  });

  std::printf("\nBuilding blocks (one core)\n");
  rule();
  std::printf("%-64s %12s\n", "operation", "ns");
  rule();
  std::printf("%-64s %12.1f\n", "sceneEngine(seed, i) + first draw (default_rng([seed, i]))",
              seedAndDraw);
  std::printf("%-64s %12.1f\n", "hiddenEngine(seed, i) + first draw (a spawned SeedSequence)",
              hiddenSeed);
  std::printf("%-64s %12.2f\n", "one uniform01 draw from a running engine", draw);
  std::printf("%-64s %12.1f\n", "orientation: Quaterniond(AngleAxisd(angle, z)) * init",
              orientation);
  Xoshiro256 small;
  const double smallDraw = nsPerOp(options, [&](std::uint64_t n) {
    double sum = 0;
    for (std::uint64_t i = 0; i < n; ++i) {
      sum += static_cast<double>(small() >> 11) * 0x1.0p-53;
    }
    gSink = gSink + sum;
  });
  std::printf("%-64s %12.1f\n", "for comparison: std::mt19937 (32 bit) seed + first draw",
              seedAndDrawNs<std::mt19937>(options));
  std::printf("%-64s %12.1f\n", "for comparison: xoshiro256** seed (SplitMix64) + first draw",
              seedAndDrawNs<Xoshiro256>(options));
  std::printf("%-64s %12.2f\n", "for comparison: xoshiro256** draw", smallDraw);
  std::printf(
      "\nOne radius query against a filled clutter scene (cylinders r = 0.03 m, about 110 per "
      "m^2;\n"
      "candidates from a pool of %zu, too many for the branch predictor to learn)\n",
      kCandidatePool);
  rule();
  std::printf("%-10s %14s %14s %14s %14s\n", "entries", "scan [ns]", "grid [ns]", "default [ns]",
              "robosuite [ns]");
  const std::string standard =
      "(scan <= " + std::to_string(ps::RadiusChecker::kDefaultScanLimit) + ")";
  std::printf("%-10s %14s %14s %14s %14s\n", "", "(packed)", "", standard.c_str(), "style scan");
  rule();
  for (const int n : {8, 16, 24, 32, 48, 64, 128, 400}) {
    // The region grows with N so that the density, and so the attempts, stay the same.
    const double half = 0.3 * std::sqrt(n / 40.0);
    const Setup setup = makeSetup(ps::parseYaml(clutterYaml(n, half), "clutter"));
    const ps::ObjectModel* object = setup.generator->config().objects.front().get();
    std::vector<Eigen::Vector3d> positions(kCandidatePool);
    ps::Engine engine(kSeed);
    for (Eigen::Vector3d& position : positions) {
      position = Eigen::Vector3d(ps::uniform(engine, -half + 0.03, half - 0.03),
                                 ps::uniform(engine, -half + 0.03, half - 0.03), 0.85);
    }
    double ns[4];
    std::size_t entries = 0;
    for (int k = 0; k < 4; ++k) {
      std::unique_ptr<ps::CollisionChecker> checker;
      if (k == 0) {
        checker = std::make_unique<ps::RadiusChecker>(std::numeric_limits<std::size_t>::max());
      } else if (k == 1) {
        checker = std::make_unique<ps::RadiusChecker>(0);
      } else if (k == 2) {
        checker = std::make_unique<ps::RadiusChecker>();
      } else {
        checker = std::make_unique<ScanChecker>();
      }
      SceneLoop loop(setup.request, std::move(checker));
      loop.engine() = ps::Engine(kSeed);
      loop.scene();  // as far as it goes
      entries = loop.context().entries().size();
      ps::Candidate candidate;
      candidate.object = object;
      ns[k] = nsPerOp(options, [&](std::uint64_t count) {
        std::ptrdiff_t sum = 0;
        for (std::uint64_t i = 0; i < count; ++i) {
          candidate.position = positions[i % kCandidatePool];
          sum += loop.context().firstCollision(candidate);
        }
        gSink = gSink + static_cast<double>(sum);
      });
    }
    std::printf("%-10zu %14.1f %14.1f %14.1f %14.1f\n", entries, ns[0], ns[1], ns[2], ns[3]);
  }
}

void benchEnvironments(const Options& options) {
  struct Env {
    const char* name;
    const char* file;
    double robosuiteUs;  ///< [us/scene], from issue 5
  };
  const Env envs[] = {{"Lift", "lift.yaml", 8.8},
                      {"Stack", "stack.yaml", 26.0},
                      {"NutAssembly", "nut_assembly.yaml", 28.0},
                      {"PickPlace", "pick_place.yaml", 105.0}};
  std::printf("\nrobosuite environments, time per scene, one thread (median of %d)\n",
              options.repetitions);
  rule();
  std::printf("%-12s %10s %10s %10s %10s %10s %9s %9s\n", "config", "sample", "+seed", "batch1t",
              "old+seed", "robosuite", "x faster", "x faster");
  std::printf("%-12s %10s %10s %10s %10s %10s %9s %9s\n", "", "[ns]", "[ns]", "[ns]", "[ns]",
              "[us]", "(+seed)", "(batch1t)");
  rule();
  for (const Env& env : envs) {
    const Setup setup = makeSetup(ps::loadYamlFile(options.configDir + "/" + env.file));
    SceneLoop loop(setup.request, ps::makeCollisionChecker(setup.request.collisionCheck, 0.0));
    SceneLoop scan(setup.request, std::make_unique<ScanChecker>());
    const double reused = nsPerOp(options, [&](std::uint64_t n) { loop.runReused(n); });
    const double seeded = nsPerOp(options, [&](std::uint64_t n) { loop.runSeeded(n); });
    const double scanSeeded = nsPerOp(options, [&](std::uint64_t n) { scan.runSeeded(n); });
    const double batch = batchNs(options, setup, 1);
    std::printf("%-12s %10.1f %10.1f %10.1f %10.1f %10.1f %9.0f %9.0f\n", env.name, reused, seeded,
                batch, scanSeeded, env.robosuiteUs, env.robosuiteUs * 1000.0 / seeded,
                env.robosuiteUs * 1000.0 / batch);
  }
  std::printf(
      "sample: engine seeded once and reused; +seed: engine = sceneEngine(seed, i) per "
      "scene (one scene alone);\nbatch1t: many scenes, as the service and sample_scenes "
      "take them (blocks of 8192 through sampleSceneRange,\n1 thread, results built); old: "
      "robosuite's scan of every entry, unpacked\n(the radius test "
      "before issue 5).\n");
}

void benchClutter(const Options& options) {
  struct Point {
    int n;
    double robosuiteMs;  ///< [ms/scene] from issue 5, 0 = not given
  };
  const Point points[] = {{5, 0.06}, {10, 0.19}, {20, 0.76}, {40, 5.0}, {50, 0.0}};
  std::printf(
      "\nClutter: N cylinders r=0.03 h=0.1 in 0.6 x 0.6 m, both flags on, one thread (median "
      "of %d;\nattempts and failures over %llu seeded scenes)\n",
      options.repetitions, static_cast<unsigned long long>(options.statScenes));
  rule();
  std::printf("%3s %10s %10s %10s %10s %10s %8s %8s %5s %9s %8s\n", "N", "+seed", "sample",
              "grid only", "scan only", "robosuite", "att/obj", "fail", "same", "robosuite",
              "x faster");
  std::printf("%3s %10s %10s %10s %10s %10s %8s %8s %5s %9s %8s\n", "", "[ns]", "[ns]", "[ns]",
              "[ns]", "scan [ns]", "", "rate", "", "[ms]", "(+seed)");
  rule();
  std::vector<double> ns, seeded, reused, attempts;
  for (const Point& point : points) {
    const Setup setup = makeSetup(ps::parseYaml(clutterYaml(point.n), "clutter"));
    SceneLoop radius(setup.request, ps::makeCollisionChecker(ps::CollisionMode::Radius, 0.0));
    SceneLoop grid(setup.request, std::make_unique<ps::RadiusChecker>(0));
    SceneLoop scan(setup.request,
                   std::make_unique<ps::RadiusChecker>(std::numeric_limits<std::size_t>::max()));
    SceneLoop old(setup.request, std::make_unique<ScanChecker>());
    const double rs = nsPerOp(options, [&](std::uint64_t n) { radius.runSeeded(n); });
    const double rr = nsPerOp(options, [&](std::uint64_t n) { radius.runReused(n); });
    const double gr = nsPerOp(options, [&](std::uint64_t n) { grid.runReused(n); });
    const double sr = nsPerOp(options, [&](std::uint64_t n) { scan.runReused(n); });
    const double orr = nsPerOp(options, [&](std::uint64_t n) { old.runReused(n); });
    const SceneStats a = collectStats(radius, options.statScenes);
    bool same = true;
    for (SceneLoop* other : {&grid, &scan, &old}) {
      const SceneStats b = collectStats(*other, options.statScenes);
      same = same && a.attempts == b.attempts && a.failed == b.failed && a.checksum == b.checksum;
    }
    std::printf("%3d %10.0f %10.0f %10.0f %10.0f %10.0f %8.2f %8.4f %5s %9s %8s\n", point.n, rs, rr,
                gr, sr, orr, a.attemptsPerObject(), a.failureRate(), same ? "yes" : "NO",
                point.robosuiteMs > 0 ? fmt("%.2f", point.robosuiteMs).c_str() : "-",
                point.robosuiteMs > 0 ? fmt("%.0f", point.robosuiteMs * 1e6 / rs).c_str() : "-");
    ns.push_back(point.n);
    seeded.push_back(rs);
    reused.push_back(rr);
    attempts.push_back(a.attemptsPerObject() * point.n);
  }
  std::printf(
      "+seed: the default RadiusChecker with engine = sceneEngine(seed, i) per scene; "
      "sample: the same, engine\nreused; grid only / scan only: RadiusChecker(0) / "
      "RadiusChecker(max); robosuite scan: every entry, unpacked.\nsame: all four give the "
      "same attempts, failures and placements.\n");
  std::printf(
      "log-log slope over N = 5..50: time per scene %.2f with seeding, %.2f without; "
      "attempts per scene %.2f\n(robosuite's time: about 2.1)\n",
      logLogSlope(ns, seeded), logLogSlope(ns, reused), logLogSlope(ns, attempts));
}

/// Strategies rejection and free_space (issue 16) on the clutter scene, N = 5..60: time per
/// scene with its seeding, failures over statScenes seeded scenes.
void benchStrategies(const Options& options) {
  const int points[] = {5, 10, 20, 30, 40, 50, 60};
  std::printf(
      "\nStrategies: clutter (N cylinders r=0.03 in 0.6 x 0.6 m, boundary in range), one thread, "
      "median of %d;\nfailures and attempts over %llu seeded scenes\n",
      options.repetitions, static_cast<unsigned long long>(options.statScenes));
  rule();
  std::printf("%3s %14s %10s %10s %14s %10s %10s\n", "N", "rejection[ns]", "fail", "att/obj",
              "free_space[ns]", "fail", "att/obj");
  rule();
  std::vector<double> ns;
  std::vector<double> times;
  for (const int n : points) {
    double t[2] = {0.0, 0.0};
    SceneStats stats[2];
    for (int k = 0; k < 2; ++k) {
      const std::string yaml =
          clutterYaml(n) + (k == 0 ? "    strategy: rejection\n" : "    strategy: free_space\n");
      const Setup setup = makeSetup(ps::parseYaml(yaml, "clutter"));
      SceneLoop loop(setup.request, ps::makeCollisionChecker(ps::CollisionMode::Radius, 0.0));
      t[k] = nsPerOp(options, [&](std::uint64_t i) { loop.runSeeded(i); });
      stats[k] = collectStats(loop, options.statScenes);
    }
    std::printf("%3d %14.0f %10.4f %10.2f %14.0f %10.4f %10.2f\n", n, t[0], stats[0].failureRate(),
                stats[0].attemptsPerObject(), t[1], stats[1].failureRate(),
                stats[1].attemptsPerObject());
    ns.push_back(n);
    times.push_back(t[1]);
  }
  std::printf("log-log slope of free_space's time per scene over N = 5..60: %.2f\n",
              logLogSlope(ns, times));
  // strategy dense past the jamming limit: 80 of them.
  const Setup dense = makeSetup(ps::parseYaml(clutterYaml(80) + "    strategy: dense\n", "dense"));
  SceneLoop loop(dense.request, ps::makeCollisionChecker(ps::CollisionMode::Radius, 0.0));
  const double t = nsPerOp(options, [&](std::uint64_t i) { loop.runSeeded(i); });
  const SceneStats stats = collectStats(loop, options.statScenes);
  std::printf("dense, N = 80: %.0f ns per scene, failure rate %.4f, sites tried per object %.2f\n",
              t, stats.failureRate(), stats.attemptsPerObject());
}

void benchFcl(const Options& options) {
  std::printf(
      "\nfcl against radius, time per scene, one thread, per-scene seeding (median of %d)\n",
      options.repetitions);
  rule();
  std::printf("%-14s %14s %14s %10s\n", "config", "radius[ns]", "fcl[ns]", "fcl/radius");
  rule();
  const bool available = fclAvailable();
  struct Case {
    const char* name;
    ps::ConfigNode tree;
  };
  std::vector<Case> cases;
  cases.push_back({"PickPlace", ps::loadYamlFile(options.configDir + "/pick_place.yaml")});
  cases.push_back({"Clutter N=20", ps::parseYaml(clutterYaml(20), "clutter")});
  cases.push_back({"Clutter N=40", ps::parseYaml(clutterYaml(40), "clutter")});
  for (const Case& c : cases) {
    const Setup radius = makeSetup(c.tree, ps::CollisionMode::Radius);
    SceneLoop radiusLoop(radius.request, ps::makeCollisionChecker(ps::CollisionMode::Radius, 0.0));
    const double r = nsPerOp(options, [&](std::uint64_t n) { radiusLoop.runSeeded(n); });
    if (!available) {
      std::printf("%-14s %14.0f %14s %10s\n", c.name, r, "n/a", "n/a");
      continue;
    }
    const Setup fcl = makeSetup(c.tree, ps::CollisionMode::Fcl);
    SceneLoop fclLoop(
        fcl.request,
        ps::makeCollisionChecker(ps::CollisionMode::Fcl, fcl.generator->config().collisionMargin));
    const double f = nsPerOp(options, [&](std::uint64_t n) { fclLoop.runSeeded(n); });
    std::printf("%-14s %14.0f %14.0f %10.2f\n", c.name, r, f, f / r);
  }
  if (!available) {
    std::printf("n/a: makeCollisionChecker does not offer 'fcl' in this build.\n");
  }
}

void benchBatch(const Options& options) {
  const Setup setup = makeSetup(ps::loadYamlFile(options.configDir + "/pick_place.yaml"));
  const std::uint64_t k = options.batchScenes;
  // 1 and 2 threads alternate, so that other load on the machine hits both alike.
  const int repetitions = 4 * options.repetitions + 1;
  std::vector<double> samples[2];
  for (int r = 0; r < repetitions + 1; ++r) {  // the first round warms up
    for (unsigned threads : {1u, 2u}) {
      const Clock::time_point start = Clock::now();
      const auto results = setup.generator->sampleScenes(setup.request, kSeed, k, threads);
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
      gSink = gSink + results.back().placements.front().position.x();
      if (r > 0) {
        samples[threads - 1].push_back(ms);
      }
    }
  }
  std::printf(
      "\nBatch: K = %llu PickPlace scenes through SceneGenerator::sampleScenes "
      "(%d runs each, alternating; hardware_concurrency %u)\n",
      static_cast<unsigned long long>(k), repetitions, std::thread::hardware_concurrency());
  rule();
  std::printf("%8s %16s %16s %16s %12s %12s\n", "threads", "median [ms]", "fastest [ms]",
              "median ns/scene", "speed-up", "(fastest)");
  rule();
  const double median1 = median(samples[0]);
  const double fastest1 = *std::min_element(samples[0].begin(), samples[0].end());
  for (unsigned threads : {1u, 2u}) {
    const double m = median(samples[threads - 1]);
    const double f = *std::min_element(samples[threads - 1].begin(), samples[threads - 1].end());
    std::printf("%8u %16.2f %16.2f %16.1f %12.2f %12.2f\n", threads, m, f,
                m * 1e6 / static_cast<double>(k), median1 / m, fastest1 / f);
  }
}

/// Any configuration files (--config): the figures a side-by-side comparison needs.
void benchConfigFiles(const Options& options) {
  std::printf(
      "\nConfiguration files, time per scene (median of %d; attempts and failures over "
      "%llu seeded scenes)\n",
      options.repetitions, static_cast<unsigned long long>(options.statScenes));
  rule();
  std::printf("%-28s %9s %9s %9s %9s %9s %8s %7s\n", "config", "sample", "+seed", "batch1t",
              "batch2t", "+json1t", "att/obj", "fail");
  std::printf("%-28s %9s %9s %9s %9s %9s %8s %7s\n", "", "[ns]", "[ns]", "[ns]", "[ns]", "[ns]", "",
              "rate");
  rule();
  for (const std::string& file : options.configFiles) {
    ps::BuildOptions build;
    const std::size_t slash = file.find_last_of('/');
    build.baseDirectory = slash == std::string::npos ? "" : file.substr(0, slash);
    Setup setup;
    setup.generator =
        std::make_unique<ps::SceneGenerator>(ps::buildSceneConfig(ps::loadYamlFile(file), build));
    setup.request = setup.generator->prepare(ps::SampleRequest{});
    SceneLoop loop(setup.request,
                   ps::makeCollisionChecker(setup.request.collisionCheck,
                                            setup.generator->config().collisionMargin));
    const double reused = nsPerOp(options, [&](std::uint64_t n) { loop.runReused(n); });
    const double seeded = nsPerOp(options, [&](std::uint64_t n) { loop.runSeeded(n); });
    double batch[2] = {0.0, 0.0};
    for (unsigned threads : {1u, 2u}) {
      batch[threads - 1] = batchNs(options, setup, threads);
    }
    std::string text;
    const double json = nsPerOp(options, [&](std::uint64_t n) {
      sampleInBlocks(setup, n, 1, [&](const std::vector<ps::SceneResult>& results) {
        text.clear();
        for (const ps::SceneResult& r : results) {
          ps::appendSceneJson(text, r);
          text += '\n';
        }
        gSink = gSink + static_cast<double>(text.size());
      });
    });
    const SceneStats stats = collectStats(loop, options.statScenes);
    const std::string name = file.substr(slash == std::string::npos ? 0 : slash + 1);
    std::printf("%-28s %9.1f %9.1f %9.1f %9.1f %9.1f %8.2f %7.4f\n", name.c_str(), reused, seeded,
                batch[0], batch[1], json, stats.attemptsPerObject(), stats.failureRate());
  }
  std::printf(
      "sample: engine seeded once and reused; +seed: engine = sceneEngine(seed, i) per scene; "
      "batch1t/2t:\nSceneGenerator::sampleScenes on 1/2 threads (wall time per scene, results "
      "built); +json1t: batch1t plus\nthe JSON lines of sample_scenes.\n");
}

int usage(const char* self) {
  std::fprintf(stderr,
               "usage: %s [--config-dir DIR] [--quick] [--default-malloc] [--only "
               "envs|blocks|clutter|strategies|fcl|batch|physics]\n"
               "       %s [--quick] --config FILE [--config FILE ...]\n"
               "Times the samplers on fixed configurations and seeds and prints tables.\n"
               "DIR holds lift.yaml, stack.yaml, nut_assembly.yaml and pick_place.yaml\n"
               "(default: %s, the package's config/ as ROS_PACKAGE_PATH finds it). --quick:\n"
               "fewer, shorter repetitions. --config: time these\n"
               "configuration files only (any sampler setup, relative paths from the file).\n"
               "--default-malloc: do not tune malloc as sample_scenes and placement_server do.\n",
               self, self, defaultConfigDir().c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  std::string only;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--config-dir" && i + 1 < argc) {
      options.configDir = argv[++i];
    } else if (arg == "--default-malloc") {
      options.defaultMalloc = true;
    } else if (arg == "--config" && i + 1 < argc) {
      options.configFiles.push_back(argv[++i]);
    } else if (arg == "--quick") {
      options.repetitions = 3;
      options.secondsPerRep = 0.03;
      options.statScenes = 500;
    } else if (arg == "--only" && i + 1 < argc) {
      only = argv[++i];
      if (only != "envs" && only != "blocks" && only != "clutter" && only != "strategies" &&
          only != "fcl" && only != "batch" && only != "physics") {
        return usage(argv[0]);
      }
    } else {
      return usage(argv[0]);
    }
  }
  // As sample_scenes and placement_server do: batches reuse the memory of the previous one.
  const bool tuned = !options.defaultMalloc && ps::keepFreedMemoryForBatches();
  std::printf("malloc: %s\n", tuned ? "keeps freed memory for the next batch, as sample_scenes and "
                                      "placement_server (--default-malloc: glibc's defaults)"
                                    : "glibc's defaults");
  try {
    if (!options.configFiles.empty()) {
      std::printf("placement_benchmark: request seed %llu\n",
                  static_cast<unsigned long long>(kSeed));
      benchConfigFiles(options);
      return 0;
    }
    std::printf("placement_benchmark: request seed %llu, configurations from %s\n",
                static_cast<unsigned long long>(kSeed), options.configDir.c_str());
    if (only.empty() || only == "envs") {
      benchEnvironments(options);
    }
    if (only.empty() || only == "blocks") {
      benchBlocks(options);
    }
    if (only.empty() || only == "clutter") {
      benchClutter(options);
    }
    if (only.empty() || only == "strategies") {
      benchStrategies(options);
    }
    if (only.empty() || only == "fcl") {
      benchFcl(options);
    }
    if (only.empty() || only == "batch") {
      benchBatch(options);
    }
    if (only.empty() || only == "physics") {
      ps::benchmark::benchPhysics(options.configDir, options.repetitions);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "placement_benchmark: %s\n", e.what());
    return 1;
  }
  return 0;
}
