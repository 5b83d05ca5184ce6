// placement_benchmark: cluttered tables (--only clutter), the strategies (--only strategies) and
// fcl against radius (--only fcl).

#include "bench_support.hpp"

namespace bench {

void benchClutter(const Options& options) {
  struct Point {
    int n;
    double robosuiteMs;  ///< [ms/scene] robosuite's own sampler, 0 = not given
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

/// Strategies rejection and free_space on the clutter scene, N = 5..60: time per
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

}  // namespace bench
