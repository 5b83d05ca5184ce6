// placement_benchmark: the building blocks of a scene's cost (--only blocks).

#include "bench_support.hpp"

namespace bench {

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

}  // namespace bench
