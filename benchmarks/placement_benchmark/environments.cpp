// placement_benchmark: robosuite's environments (--only envs), batches on one and two threads
// (--only batch) and any configuration file (--config).

#include "bench_support.hpp"

namespace bench {

void benchEnvironments(const Options& options) {
  struct Env {
    const char* name;
    const char* file;
    double robosuiteUs;  ///< [us/scene], robosuite's own sampler
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
      "robosuite's scan of every entry, unpacked\n(as robosuite's "
      "own loop tests them).\n");
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

}  // namespace bench
