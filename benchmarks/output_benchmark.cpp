// output_benchmark: the cost of writing sampled scenes, JSON lines (sample_scenes' default)
// against the .npz writer (--output FILE.npz), for the clutter scene of placement_benchmark
// (N cylinders r = 0.03 m in 0.6 m x 0.6 m, radius check). One thread; prints a table. Not a
// test: it asserts nothing about time. Figures and command: docs/benchmarks.md.
//
//   output_benchmark [--objects N] [--scenes K] [--repeat R] [--dir DIRECTORY]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/output/npz_writer.hpp"
#include "placement_samplers/output/scene_json.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "clutter_scene.hpp"

namespace ps = placement_samplers;

namespace {

double seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int objects = 40;
  std::uint64_t scenes = 8192;
  int repeat = 5;
  std::string dir = std::filesystem::temp_directory_path().string();
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--objects") {
      objects = std::atoi(argv[i + 1]);
    } else if (flag == "--scenes") {
      scenes = std::strtoull(argv[i + 1], nullptr, 10);
    } else if (flag == "--repeat") {
      repeat = std::max(1, std::atoi(argv[i + 1]));
    } else if (flag == "--dir") {
      dir = argv[i + 1];
    } else {
      std::fprintf(stderr, "unknown argument %s\n", argv[i]);
      return 2;
    }
  }
  const ps::SceneGenerator generator(
      ps::buildSceneConfig(ps::parseYaml(bench::clutterYaml(objects), "clutter")));
  const ps::PreparedRequest request = generator.prepare(ps::SampleRequest());
  std::vector<std::string> names;
  for (const ps::ObjectPtr& object : request.sampler->objects()) {
    names.push_back(object->name);
  }

  std::vector<double> sampleTimes, jsonTimes, npzTimes;
  std::vector<ps::SceneResult> results;
  std::uint64_t jsonBytes = 0;
  const std::string path = dir + "/output_benchmark_" + std::to_string(::getpid()) + ".npz";
  for (int r = 0; r < repeat; ++r) {
    auto start = std::chrono::steady_clock::now();
    results = generator.sampleSceneRange(request, 1, r * scenes, scenes, 1);
    sampleTimes.push_back(seconds(start));

    // JSON: formatting and writing to /dev/null, as sample_scenes > FILE does.
    std::FILE* devnull = std::fopen("/dev/null", "w");
    start = std::chrono::steady_clock::now();
    std::string text;
    for (const ps::SceneResult& scene : results) {
      ps::appendSceneJson(text, scene);
      text += '\n';
    }
    std::fwrite(text.data(), 1, text.size(), devnull);
    jsonTimes.push_back(seconds(start));
    jsonBytes = text.size();
    std::fclose(devnull);

    // npz: the whole file (layout, rows, CRCs, directory) on disk.
    start = std::chrono::steady_clock::now();
    {
      ps::NpzWriter writer(path, names, scenes, 1);
      writer.write(results);
      writer.finish();
    }
    npzTimes.push_back(seconds(start));
    std::filesystem::remove(path);
  }
  const double k = static_cast<double>(scenes);
  const double sample = k / median(sampleTimes);
  const double json = k / median(jsonTimes);
  const double npz = k / median(npzTimes);
  std::printf("Clutter N=%d, %llu scenes, median of %d, one thread (scenes/s)\n", objects,
              static_cast<unsigned long long>(scenes), repeat);
  std::printf("%-28s %12.0f\n", "sampling", sample);
  std::printf("%-28s %12.0f  (%.0f bytes/scene)\n", "JSON lines output", json,
              static_cast<double>(jsonBytes) / k);
  std::printf("%-28s %12.0f  (%.1fx JSON)\n", ".npz output", npz, npz / json);
  std::printf("%-28s %12.0f\n", "sampling + JSON", 1.0 / (1.0 / sample + 1.0 / json));
  std::printf("%-28s %12.0f  (%.1fx)\n", "sampling + .npz", 1.0 / (1.0 / sample + 1.0 / npz),
              (1.0 / sample + 1.0 / json) / (1.0 / sample + 1.0 / npz));
  return 0;
}
