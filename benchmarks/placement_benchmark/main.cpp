// placement_benchmark: fixed configurations and seeds, timed on one core (and on two for the
// batch), printed as plain tables. Not a test: it asserts nothing about time. See
// docs/benchmarks.md for the figures and how to read them.

#include <cstdio>
#include <exception>
#include <string>

#include "bench_support.hpp"
#include "physics.hpp"
#include "resting.hpp"
#include "placement_samplers/process/malloc_tuning.hpp"

using namespace bench;

namespace {

int usage(const char* self) {
  std::fprintf(stderr,
               "usage: %s [--config-dir DIR] [--quick] [--default-malloc] [--only "
               "envs|blocks|clutter|strategies|fcl|batch|physics|surfaces|resting]\n"
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
          only != "fcl" && only != "batch" && only != "physics" && only != "surfaces" &&
          only != "resting") {
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
      placement_samplers::benchmark::benchPhysics(options.configDir, options.repetitions);
    }
    if (only.empty() || only == "surfaces") {
      benchSurfaces(options);
    }
    if (only.empty() || only == "resting") {
      placement_samplers::benchmark::benchResting(4 * options.repetitions + 1);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "placement_benchmark: %s\n", e.what());
    return 1;
  }
  return 0;
}
