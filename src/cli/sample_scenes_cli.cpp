#include "cli/sample_scenes_cli.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "placement_samplers/collision/make_collision_checker.hpp"
#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/sampling/failure_summary.hpp"
#include "placement_samplers/sampling/random.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "placement_samplers/output/npz_writer.hpp"
#include "placement_samplers/output/scene_arrays.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/output/scene_json.hpp"
#include "placement_samplers/text.hpp"
#include "cli/progress_line.hpp"
#include "cli/validate_scenes.hpp"
#include "sampling/parallel.hpp"

namespace placement_samplers {
namespace {

constexpr const char* kUsage =
    "usage: sample_scenes --config FILE [--seed S] [--scenes K] [--first-scene N]\n"
    "                     [--sampler NAME] [--collision-check radius|fcl|radius_and_fcl]\n"
    "                     [--max-attempts N] [--threads T] [--output FILE.npz]\n"
    "                     [--physics none|check|settle] [--max-scene-seconds S]\n"
    "                     [--progress | --no-progress]\n"
    "       sample_scenes --config FILE --describe\n"
    "       sample_scenes --config FILE --validate SCENES.jsonl|- [--height-tolerance M]\n"
    "                     [--sampler NAME] [--collision-check MODE]\n"
    "Samples scenes N .. N+K-1 (default N = 0, K = 1) from the YAML configuration FILE and\n"
    "prints one JSON object per scene and line. S defaults to the configuration's seed (0 =\n"
    "random); scene i of seed S is the same whatever N, K and T are (numpy's\n"
    "default_rng([S, i])), so processes given pieces of N .. N+K-1 together print the scenes\n"
    "of one process. T = 0 (default) uses every core. --describe prints the built\n"
    "configuration as JSON instead (derived radii and offsets, the sampler tree).\n"
    "--output writes the scenes into FILE.npz (numpy.load reads it: names, position,\n"
    "orientation, attempts, success, scene, seed) instead of printing them.\n"
    "--physics simulates each placed scene in MuJoCo (default: the configuration's physics):\n"
    "check adds stable, moved, turned and fallen; settle also gives the settled poses.\n"
    "--max-scene-seconds fails a scene that takes longer than S seconds to sample and\n"
    "simulate (default: the configuration's max_request_seconds; 0 = no limit).\n"
    "--progress shows a progress line on stderr (scenes done, scenes/s, failures, ETA);\n"
    "by default it is shown when stderr is a terminal the scenes do not go to and the run\n"
    "takes over a second; --no-progress never shows it. stdout and FILE.npz are the same.\n"
    "--validate reads scenes in this tool's JSON lines (- = stdin) and prints one verdict\n"
    "per scene and line: each object inside its sampler's region, at its height (within M,\n"
    "default 0.005 m) and overlapping nothing under the check; exit 0 when all are valid.\n"
    "Exit status: 0 all scenes placed, 1 some scene failed, 2 usage, configuration or output\n"
    "error.\n";

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::uint64_t parseUnsigned(const std::string& flag, const std::string& text, std::uint64_t max) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
    throw UsageError(flag + ": expected a non-negative integer, got " + quoteText(text));
  }
  try {
    const unsigned long long v = std::stoull(text);
    if (v > max) {
      throw std::out_of_range("too large");
    }
    return v;
  } catch (const std::out_of_range&) {
    throw UsageError(flag + ": " + text + " is out of range (at most " + std::to_string(max) + ")");
  }
}

/// A finite number >= 0 and <= @p max, in @p unit ("metres", "seconds").
double parseAmount(const std::string& flag, const std::string& text, const char* unit, double max) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v) || v < 0.0 ||
      v > max) {
    std::ostringstream out;
    out << flag << ": expected a non-negative number of " << unit;
    if (max < std::numeric_limits<double>::max()) {
      out << " (at most " << max << ")";
    }
    out << ", got " << quoteText(text);
    throw UsageError(out.str());
  }
  return v;
}

/// Scenes per block: the output is written block by block, so memory stays bounded for any K.
constexpr std::uint64_t kBlock = 8192;
/// Placements per block, at most (unless one scene has more): about 70 MB of results and text.
constexpr std::uint64_t kBlockPlacements = 1 << 20;

/// Samples and prints scenes firstScene .. firstScene + count - 1 in blocks; formatting is spread
/// over the threads too, since printing a scene costs more than sampling it; with @p npz, the
/// scenes go there instead. @return what failed
FailureSummary writeScenes(const SceneGenerator& generator, const PreparedRequest& prepared,
                           std::uint64_t seed, std::uint64_t firstScene, std::uint64_t count,
                           unsigned threads, std::ostream& out, NpzWriter* npz,
                           SampleProgress* progress) {
  const unsigned workers =
      threads != 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::string> texts(workers);
  FailureSummary failures;
  const std::uint64_t perScene = std::max<std::uint64_t>(generator.placementsPerScene(prepared), 1);
  const std::uint64_t block = std::clamp<std::uint64_t>(kBlockPlacements / perScene, 1, kBlock);
  // One vector for every block: its scenes' buffers are reused, no allocation per scene.
  std::vector<SceneResult> results;
  for (std::uint64_t first = 0; first < count; first += block) {
    const std::uint64_t n = std::min(block, count - first);
    generator.sampleSceneRange(prepared, seed, firstScene + first, n, threads, results, progress);
    for (const SceneResult& scene : results) {
      failures.add(scene);
    }
    if (npz != nullptr) {
      npz->write(results);
      continue;
    }
    const std::size_t slices = static_cast<std::size_t>(std::min<std::uint64_t>(workers, n));
    auto format = [&](std::size_t slice) {
      // A string of this thread's own (texts' buffers are kept): neighbouring std::string
      // objects share a cache line, and appending to them from two threads halved the speed.
      std::string text;
      text.swap(texts[slice]);
      text.clear();
      for (std::size_t i = slice * n / slices; i < (slice + 1) * n / slices; ++i) {
        appendSceneJson(text, results[i]);
        text += '\n';
      }
      texts[slice].swap(text);
    };
    std::atomic<std::size_t> nextSlice{0};
    detail::runOnThreads(static_cast<unsigned>(slices), [&] {
      for (std::size_t slice = nextSlice++; slice < slices; slice = nextSlice++) {
        format(slice);
      }
    });
    for (std::size_t slice = 0; slice < slices; ++slice) {
      out.write(texts[slice].data(), static_cast<std::streamsize>(texts[slice].size()));
    }
  }
  if (npz != nullptr) {
    npz->finish();
  }
  out.flush();
  return failures;
}

}  // namespace

int runSampleScenes(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
                    Terminals terminals) {
  std::string configPath;
  std::string sampler;
  std::string mode;
  std::string physics;
  bool haveSeed = false;
  std::uint64_t seed = 0;
  std::uint64_t scenes = 1;
  std::uint64_t firstScene = 0;
  std::uint32_t maxAttempts = 0;
  unsigned threads = 0;
  bool describe = false;
  std::string outputPath;
  std::string validatePath;
  double heightTolerance = ValidationOptions().heightTolerance;
  std::optional<double> maxSceneSeconds;
  std::optional<bool> progress;  // --progress, --no-progress
  // Flags that only change how scenes are sampled: --validate reads its poses instead.
  std::vector<std::string> samplingFlags;
  try {
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& flag = args[i];
      if (flag == "--help" || flag == "-h") {
        out << kUsage;
        return 0;
      }
      if (flag == "--describe") {
        describe = true;
        continue;
      }
      if (flag == "--progress" || flag == "--no-progress") {
        if (progress && *progress != (flag == "--progress")) {
          throw UsageError("--progress and --no-progress: choose one");
        }
        progress = flag == "--progress";
        continue;
      }
      if (i + 1 >= args.size()) {
        throw UsageError(flag == "--config" || flag == "--seed" || flag == "--scenes" ||
                                 flag == "--first-scene" || flag == "--sampler" ||
                                 flag == "--collision-check" || flag == "--max-attempts" ||
                                 flag == "--threads" || flag == "--output" ||
                                 flag == "--validate" || flag == "--height-tolerance" ||
                                 flag == "--physics" || flag == "--max-scene-seconds"
                             ? flag + ": missing value"
                             : "unknown argument " + quoteText(flag));
      }
      const std::string& value = args[++i];
      if (flag == "--seed" || flag == "--scenes" || flag == "--first-scene" ||
          flag == "--max-attempts" || flag == "--physics" || flag == "--threads" ||
          flag == "--max-scene-seconds") {
        samplingFlags.push_back(flag);
      }
      if (flag == "--config") {
        configPath = value;
      } else if (flag == "--seed") {
        haveSeed = true;
        seed = parseUnsigned(flag, value, std::numeric_limits<std::uint64_t>::max());
      } else if (flag == "--scenes") {
        scenes = parseUnsigned(flag, value, 100000000);
      } else if (flag == "--first-scene") {
        firstScene = parseUnsigned(flag, value, std::numeric_limits<std::uint64_t>::max());
      } else if (flag == "--sampler") {
        sampler = value;
      } else if (flag == "--collision-check") {
        mode = value;
      } else if (flag == "--max-attempts") {
        maxAttempts = static_cast<std::uint32_t>(
            parseUnsigned(flag, value, std::numeric_limits<std::uint32_t>::max()));
      } else if (flag == "--physics") {
        physics = value;
      } else if (flag == "--validate") {
        validatePath = value;
      } else if (flag == "--height-tolerance") {
        heightTolerance = parseAmount(flag, value, "metres", std::numeric_limits<double>::max());
      } else if (flag == "--max-scene-seconds") {
        maxSceneSeconds = parseAmount(flag, value, "seconds", limits::kRequestSeconds);
      } else if (flag == "--output") {
        outputPath = value;
      } else if (flag == "--threads") {
        threads = static_cast<unsigned>(parseUnsigned(flag, value, 1024));
      } else {
        throw UsageError("unknown argument " + quoteText(flag));
      }
    }
    if (configPath.empty()) {
      throw UsageError("--config FILE is required");
    }
    if (!outputPath.empty() && (describe || !validatePath.empty())) {
      throw UsageError(std::string("--output writes sampled scenes; ") +
                       (describe ? "--describe" : "--validate") +
                       " prints JSON to stdout instead (drop --output)");
    }
    if (describe && !validatePath.empty()) {
      throw UsageError("--describe and --validate: choose one");
    }
    if (!validatePath.empty() && !samplingFlags.empty()) {
      throw UsageError(samplingFlags.front() +
                       " changes how scenes are sampled; --validate checks the poses it reads "
                       "(drop " +
                       samplingFlags.front() + ")");
    }
    if (!outputPath.empty() &&
        (outputPath.size() < 5 || outputPath.compare(outputPath.size() - 4, 4, ".npz") != 0)) {
      throw UsageError("--output: expected a file name ending in .npz, got " +
                       quoteText(outputPath));
    }
  } catch (const UsageError& e) {
    err << "sample_scenes: " << e.what() << "\n" << kUsage;
    return 2;
  }

  const std::string shownPath = escapeText(configPath);
  // Memory is bounded by the limits on configurations and answers; should it run out anyway
  // (a tight ulimit), the user gets a message and status 2 rather than an abort.
  try {
    ConfigNode tree;
    try {
      tree = loadYamlFile(configPath);
    } catch (const ConfigError& e) {
      err << "sample_scenes: " << e.what() << "\n";
      return 2;
    }
    BuildOptions options;
    // Relative mesh and URDF paths are relative to the configuration file.
    options.baseDirectory = std::filesystem::path(configPath).parent_path().string();
    const SceneGenerator generator(buildSceneConfig(tree, options));
    for (const std::string& warning : generator.config().warnings) {
      err << "sample_scenes: " << shownPath << ": warning: " << warning << "\n";
    }
    if (describe) {
      out << configToJson(generator.config()) << "\n";
      return 0;
    }
    SampleRequest request;
    request.sampler = sampler;
    request.maxAttempts = maxAttempts;
    // A scene may take as long as a whole request of the node, unless the flag says otherwise.
    request.maxSceneSeconds = maxSceneSeconds.value_or(generator.config().maxRequestSeconds);
    if (!mode.empty()) {
      request.collisionCheck = collisionModeFromName(mode);
      if (!request.collisionCheck) {
        err << "sample_scenes: --collision-check: expected radius, fcl or radius_and_fcl, got "
            << quoteText(mode) << "\n";
        return 2;
      }
    }
    if (!physics.empty()) {
      request.physics = physicsModeFromName(physics);
      if (!request.physics) {
        err << "sample_scenes: --physics: expected none, check or settle, got "
            << quoteText(physics) << "\n";
        return 2;
      }
    }
    const PreparedRequest prepared = generator.prepare(request);
    if (!haveSeed) {
      seed = generator.config().seed;
    }
    if (seed == 0) {
      seed = randomSeed();  // a fresh seed, printed with every scene
    }
    if (!validatePath.empty()) {
      ValidationOptions validation;
      validation.heightTolerance = heightTolerance;
      if (validatePath == "-") {
        return validateSceneLines(generator, prepared, validation, std::cin, validatePath, out,
                                  err);
      }
      std::ifstream in(validatePath);
      if (!in) {
        err << "sample_scenes: --validate " << escapeText(validatePath) << ": cannot open\n";
        return 2;
      }
      std::error_code ignored;
      if (std::filesystem::is_directory(validatePath, ignored)) {
        err << "sample_scenes: --validate " << escapeText(validatePath) << ": is a directory\n";
        return 2;
      }
      return validateSceneLines(generator, prepared, validation, in, validatePath, out, err);
    }
    checkSceneRange(firstScene, scenes);  // before the first block is written
    std::unique_ptr<NpzWriter> npz;
    if (!outputPath.empty()) {
      std::vector<std::string> names;
      for (const ObjectPtr& object : prepared.sampler->objects()) {
        names.push_back(object->name);
      }
      NpzOptions npzOptions;
      npzOptions.physics = prepared.physics.mode;
      npzOptions.restPoses = drawsRestPoses(prepared);
      npz = std::make_unique<NpzWriter>(outputPath, names, scenes, seed, npzOptions);
    }
    // The line goes to a terminal the scenes do not go to (--output, or stdout redirected).
    SampleProgress counts;
    std::optional<ProgressLine> line;
    if (progress.value_or(terminals.err && (npz || !terminals.out))) {
      line.emplace(err, counts, scenes, terminals.err, progress.value_or(false));
    }
    const FailureSummary failures = writeScenes(generator, prepared, seed, firstScene, scenes,
                                                threads, out, npz.get(), line ? &counts : nullptr);
    if (line) {
      line->finish();
    }
    if (failures.failed() != 0) {
      err << "sample_scenes: " << failures.message(scenes) << "\n";
      return 1;
    }
    return 0;
  } catch (const OutputError& e) {
    err << "sample_scenes: " << e.what() << "\n";
  } catch (const ConfigError& e) {
    err << "sample_scenes: " << shownPath << ": " << e.what() << "\n";
  } catch (const RequestError& e) {
    err << "sample_scenes: " << e.what() << "\n";
  } catch (const std::bad_alloc&) {
    err << "sample_scenes: " << shownPath << ": out of memory\n";
  } catch (const std::exception& e) {
    err << "sample_scenes: " << shownPath << ": " << escapeText(e.what()) << "\n";
  }
  return 2;
}

}  // namespace placement_samplers
