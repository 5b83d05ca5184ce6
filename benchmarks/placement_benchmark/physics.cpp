#include "physics.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <thread>
#include <vector>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/physics/physics_model.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"

namespace placement_samplers::benchmark {
namespace {

using Clock = std::chrono::steady_clock;

double medianOf(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

void benchPhysics(const std::string& configDir, int repetitions) {
  const SceneGenerator generator(buildSceneConfig(loadYamlFile(configDir + "/pick_place.yaml")));
  SampleRequest request;
  request.sampler = "CollisionObjectSampler";  // robosuite's four objects in bin 1
  request.physics = PhysicsMode::Settle;
  const PhysicsSettings& settings = generator.config().physics;

  // The model alone, as a request builds it once: four free bodies and the ground plane.
  std::vector<PhysicsBody> bodies;
  for (const ObjectPtr& object : generator.config().objects) {
    if (bodies.size() < 4) {
      bodies.push_back(PhysicsBody{object.get(), 0.0, settings.density});
    }
  }
  std::vector<double> build;
  for (int r = 0; r < 4 * repetitions; ++r) {
    const Clock::time_point start = Clock::now();
    const PhysicsModel model({}, bodies, settings);
    build.push_back(msSince(start));
  }

  constexpr std::uint64_t kScenes = 200;
  constexpr std::uint64_t kSeed = 20240605;
  std::vector<double> one;
  std::vector<double> batch[2];
  std::size_t stable = 0;
  std::size_t simulated = 0;
  for (int r = 0; r < repetitions + 1; ++r) {  // the first round warms up
    const PreparedRequest prepared = generator.prepare(request);
    // One scene at a time on one thread, the model already built.
    generator.sampleScene(prepared, kSeed, 0);
    Clock::time_point start = Clock::now();
    for (std::uint64_t i = 0; i < kScenes / 4; ++i) {
      generator.sampleScene(prepared, kSeed, i);
    }
    if (r > 0) {
      one.push_back(msSince(start) / static_cast<double>(kScenes / 4));
    }
    for (unsigned threads : {1u, 2u}) {
      start = Clock::now();
      const std::vector<SceneResult> results =
          generator.sampleScenes(prepared, kSeed, kScenes, threads);
      if (r > 0) {
        batch[threads - 1].push_back(msSince(start) / static_cast<double>(kScenes));
      }
      if (r == 0 && threads == 1) {
        for (const SceneResult& s : results) {
          simulated += s.simulated ? 1 : 0;
          stable += s.stable ? 1 : 0;
        }
      }
    }
  }
  std::printf(
      "\nPhysics: PickPlace's CollisionObjectSampler (4 objects), settle, %.2f s simulated in "
      "steps of %.4f s, ground_z\n(median of %d; hardware_concurrency %u)\n",
      settings.seconds, settings.timestep, repetitions, std::thread::hardware_concurrency());
  std::printf("%s\n", std::string(100, '-').c_str());
  std::printf("model build (MJCF text + MuJoCo compile) [ms]   %10.3f\n", medianOf(build));
  std::printf(
      "one scene, sampled and settled, 1 thread [ms]   %10.3f  (sampleScene: model reused)\n",
      medianOf(one));
  std::printf("batch of %llu, 1 thread [ms per scene]          %10.3f  (model built in the call)\n",
              static_cast<unsigned long long>(kScenes), medianOf(batch[0]));
  std::printf("batch of %llu, 2 threads [ms per scene]         %10.3f  speed-up %.2f\n",
              static_cast<unsigned long long>(kScenes), medianOf(batch[1]),
              medianOf(batch[0]) / medianOf(batch[1]));
  std::printf("stable scenes: %zu of %zu simulated\n", stable, simulated);
}

}  // namespace placement_samplers::benchmark
