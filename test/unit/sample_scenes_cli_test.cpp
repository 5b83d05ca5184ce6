// The sample_scenes tool run in-process: JSON lines, exit codes, flags and reproducibility.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/config/config_node.hpp"
#include "cli/sample_scenes_cli.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "placement_samplers/output/scene_json.hpp"

namespace placement_samplers {
namespace {

const std::string kDefaultConfig =
    std::string(PLACEMENT_SAMPLERS_SOURCE_DIR) + "/config/default.yaml";

// A slab over the whole table: the plate never fits.
const std::string kBlockedConfig = R"(
objects:
  slab_top: {shape: box, size: [2, 2, 0.5]}
  plate: {shape: cylinder, radius: 0.09, length: 0.02}
fixtures:
  - {name: slab, object: slab_top, position: [0, 0, 0]}
max_attempts: 20
samplers:
  - {name: PlateSampler, objects: [plate], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3]}
)";

struct CliRun {
  int status = -1;
  std::string out;
  std::string err;
  std::vector<std::string> lines;
};

CliRun run(const std::vector<std::string>& args) {
  std::ostringstream out;
  std::ostringstream err;
  CliRun r;
  r.status = runSampleScenes(args, out, err);
  r.out = out.str();
  r.err = err.str();
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);) {
    r.lines.push_back(line);
  }
  return r;
}

/// A configuration file in the test temporary directory, removed when the test ends.
struct TempConfig {
  TempConfig(const std::string& name, const std::string& text)
      : path(testing::TempDir() + "sample_scenes_cli_" + std::to_string(getpid()) + "_" + name) {
    std::ofstream file(path);
    file << text;
  }
  ~TempConfig() { std::remove(path.c_str()); }
  std::string path;
};

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

TEST(SampleScenesCli, OneJsonLinePerScene) {
  const CliRun r =
      run({"--config", kDefaultConfig, "--seed", "7", "--scenes", "5", "--threads", "1"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  ASSERT_EQ(r.lines.size(), 5u);
  for (std::size_t i = 0; i < r.lines.size(); ++i) {
    const std::string& line = r.lines[i];
    EXPECT_EQ(line.rfind("{\"scene\": " + std::to_string(i) +
                             ", \"seed\": 7, \"success\": true, "
                             "\"message\": \"\", \"placements\": [",
                         0),
              0u)
        << line;
    EXPECT_EQ(line.substr(line.size() - 2), "]}");
    // plate, cup, cube, can, ball and the hidden pill.
    EXPECT_EQ(count(line, "\"name\": "), 6u) << line;
  }
}

TEST(SampleScenesCli, SameSeedSameOutput) {
  const std::vector<std::string> args = {"--config", kDefaultConfig, "--seed",
                                         "11",       "--scenes",     "4"};
  const CliRun a = run(args);
  const CliRun b = run(args);
  EXPECT_EQ(a.status, 0);
  EXPECT_EQ(a.out, b.out);
  const CliRun c = run({"--config", kDefaultConfig, "--seed", "12", "--scenes", "4"});
  EXPECT_NE(a.out, c.out);
}

TEST(SampleScenesCli, SceneIndependentOfScenesAndThreads) {
  const CliRun few =
      run({"--config", kDefaultConfig, "--seed", "5", "--scenes", "3", "--threads", "1"});
  const CliRun many =
      run({"--config", kDefaultConfig, "--seed", "5", "--scenes", "40", "--threads", "2"});
  ASSERT_EQ(few.lines.size(), 3u);
  ASSERT_EQ(many.lines.size(), 40u);
  for (std::size_t i = 0; i < few.lines.size(); ++i) {
    EXPECT_EQ(few.lines[i], many.lines[i]);
  }
}

// Output goes out in blocks of 8192 scenes, formatted on every thread: the lines across a
// block boundary are the scenes sampleScenes() gives, in order, and the numbers read back as
// the same doubles.
TEST(SampleScenesCli, BlocksAndThreadsGiveTheScenesOfSampleScenes) {
  const std::uint64_t scenes = 8192 + 37;
  const CliRun r = run({"--config", kDefaultConfig, "--seed", "9", "--scenes",
                        std::to_string(scenes), "--threads", "2"});
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(r.lines.size(), scenes);
  const SceneGenerator generator(buildSceneConfig(loadYamlFile(kDefaultConfig)));
  const PreparedRequest request = generator.prepare(SampleRequest{});
  const std::vector<SceneResult> expected = generator.sampleScenes(request, 9, scenes, 1);
  for (const std::uint64_t i : {std::uint64_t{0}, std::uint64_t{8190}, std::uint64_t{8191},
                                std::uint64_t{8192}, std::uint64_t{8193}, scenes - 1}) {
    EXPECT_EQ(r.lines[i], sceneToJson(expected[i])) << "scene " << i;
  }
  // Every coordinate of a line parses back to the sampled double.
  const std::string& line = r.lines[8192];
  const ObjectPlacement& first = expected[8192].placements.front();
  const std::size_t at = line.find("\"position\": [") + 13;
  char* end = nullptr;
  const double x = std::strtod(line.c_str() + at, &end);
  const double y = std::strtod(end + 2, &end);
  const double z = std::strtod(end + 2, &end);
  EXPECT_EQ(x, first.position.x());
  EXPECT_EQ(y, first.position.y());
  EXPECT_EQ(z, first.position.z());
}

// Sharding: scenes 0 .. 999 of one process are the pieces of four processes that each take
// --first-scene N --scenes 250, concatenated in order; pieces cross a block of 8192 too.
TEST(SampleScenesCli, PiecesWithFirstSceneConcatenateToOneProcess) {
  const CliRun whole = run({"--config", kDefaultConfig, "--seed", "77", "--scenes", "1000"});
  ASSERT_EQ(whole.status, 0) << whole.err;
  ASSERT_EQ(whole.lines.size(), 1000u);
  std::string pieces;
  for (const char* first : {"0", "250", "500", "750"}) {
    const CliRun piece = run({"--config", kDefaultConfig, "--seed", "77", "--first-scene", first,
                              "--scenes", "250", "--threads", "1"});
    ASSERT_EQ(piece.status, 0) << piece.err;
    ASSERT_EQ(piece.lines.size(), 250u);
    EXPECT_EQ(piece.lines.front().rfind(std::string("{\"scene\": ") + first + ",", 0), 0u);
    pieces += piece.out;
  }
  EXPECT_EQ(pieces, whole.out);

  const CliRun across = run({"--config", kDefaultConfig, "--seed", "77", "--first-scene", "8000",
                             "--scenes", "400", "--threads", "2"});
  const CliRun late = run({"--config", kDefaultConfig, "--seed", "77", "--first-scene", "8190",
                           "--scenes", "3", "--threads", "1"});
  ASSERT_EQ(across.lines.size(), 400u);
  ASSERT_EQ(late.lines.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(late.lines[k], across.lines[190 + k]);
  }
}

TEST(SampleScenesCli, FirstSceneNearTheEndOfTheIndices) {
  const CliRun last = run({"--config", kDefaultConfig, "--seed", "3", "--first-scene",
                           "18446744073709551615", "--scenes", "1"});
  EXPECT_EQ(last.status, 0) << last.err;
  ASSERT_EQ(last.lines.size(), 1u);
  EXPECT_EQ(last.lines[0].rfind("{\"scene\": 18446744073709551615,", 0), 0u);
  const CliRun beyond = run({"--config", kDefaultConfig, "--seed", "3", "--first-scene",
                             "18446744073709551615", "--scenes", "2"});
  EXPECT_EQ(beyond.status, 2);
  EXPECT_EQ(beyond.err,
            "sample_scenes: first scene 18446744073709551615 + 2 scenes: scene indices must stay "
            "below 2^64\n");
  EXPECT_TRUE(beyond.out.empty());
}

// --describe: the values robosuite's samplers need, as derived (a 0.042 m cube: radius
// 0.021 * sqrt(2), offsets -/+0.021), and the sampler tree with its sample_args.
TEST(SampleScenesCli, DescribePrintsTheBuiltConfiguration) {
  const CliRun r = run({"--config", kDefaultConfig, "--describe"});
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(r.lines.size(), 1u);
  const std::string& d = r.lines[0];
  EXPECT_NE(d.find("\"cube\": {\"horizontal_radius\": 0.02969848480983"), std::string::npos) << d;
  EXPECT_NE(d.find("\"bottom_offset\": [0, 0, -0.021], \"top_offset\": [0, 0, 0.021], "
                   "\"bottom_gap\": 0, \"top_gap\": 0"),
            std::string::npos);
  EXPECT_NE(d.find("\"fixtures\": [{\"name\": \"table\", \"position\": [0, 0, 0.775]"),
            std::string::npos);
  EXPECT_NE(d.find("\"hidden\": [\"pill\"]"), std::string::npos);
  EXPECT_NE(d.find("{\"type\": \"uniform\", \"name\": \"TableSampler\", \"objects\": "
                   "[\"cube\", \"can\", \"ball\"], \"x_range\": [-0.35, 0.35]"),
            std::string::npos);
  EXPECT_NE(d.find("\"rotation\": [-0.785, 0.785], \"rotation_axis\": \"z\""), std::string::npos);
  EXPECT_NE(d.find("\"sample_args\": {\"reference\": \"table\", \"on_top\": true}"),
            std::string::npos);
  EXPECT_NE(d.find("\"name\": \"HideSampler\""), std::string::npos);
  EXPECT_NE(d.find("\"hides\": true"), std::string::npos);
}

// A cylinder of radius 0.03 is robosuite's CylinderObject(size=[0.03, 0.05]): horizontal
// radius 0.03 exactly, so the boundary shrink is robosuite's and so is every position. Scene 0
// of seed 7 is what robosuite's sampler gives with numpy.random.default_rng([7, 0]):
// y = 0.21449545252357077 (one bit more of radius gave 0.21449545252357072).
TEST(SampleScenesCli, CylinderPositionsAreRobosuites) {
  const TempConfig config("cylinder.yaml", R"(
objects:
  c00: {shape: cylinder, radius: 0.03, length: 0.1}
samplers:
  - {name: S, objects: [c00], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3], reference_pos: [0.5, 0.0, 0.8]}
)");
  const CliRun d = run({"--config", config.path, "--describe"});
  ASSERT_EQ(d.status, 0) << d.err;
  EXPECT_NE(d.out.find("\"c00\": {\"horizontal_radius\": 0.03, \"bottom_offset\": [0, 0, -0.05], "
                       "\"top_offset\": [0, 0, 0.05]"),
            std::string::npos)
      << d.out;
  const CliRun r = run({"--config", config.path, "--seed", "7"});
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(r.lines.size(), 1u);
  EXPECT_NE(r.lines[0].find("\"position\": [0.5675515519665202, 0.21449545252357077, "
                            "0.8500000000000001]"),
            std::string::npos)
      << r.lines[0];
}

TEST(SampleScenesCli, NumbersAreTheShortestThatReadBack) {
  SceneResult scene;
  scene.index = 3;
  scene.seed = 18446744073709551615ull;
  scene.success = true;
  ObjectPlacement p;
  p.name = "cube";
  p.sampler = "S";
  p.position = Eigen::Vector3d(0.831, -0.1, 1e-300);
  p.orientation = Eigen::Quaterniond(0.5, -0.5, 0.5, 0.1 + 0.2);  // w, x, y, z
  p.attempts = 2;
  scene.placements.push_back(p);
  EXPECT_EQ(sceneToJson(scene),
            "{\"scene\": 3, \"seed\": 18446744073709551615, \"success\": true, \"message\": \"\", "
            "\"placements\": [{\"name\": \"cube\", \"sampler\": \"S\", \"position\": [0.831, -0.1, "
            "1e-300], \"orientation\": [-0.5, 0.5, 0.30000000000000004, 0.5], \"attempts\": 2}]}");
}

TEST(SampleScenesCli, SeedFromTheConfiguration) {
  const TempConfig config("seeded.yaml", "seed: 99\n");
  const CliRun r = run({"--config", config.path});
  EXPECT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(r.lines.size(), 1u);
  EXPECT_NE(r.lines[0].find("\"seed\": 99,"), std::string::npos) << r.lines[0];
}

// Seed 0, from the flag or the configuration, is a fresh random seed, echoed with the scenes;
// sent back, it gives the same scenes.
TEST(SampleScenesCli, SeedZeroIsAFreshSeedEchoedBack) {
  const CliRun a = run({"--config", kDefaultConfig, "--seed", "0", "--scenes", "2"});
  ASSERT_EQ(a.status, 0) << a.err;
  ASSERT_EQ(a.lines.size(), 2u);
  const std::size_t at = a.lines[0].find("\"seed\": ") + 8;
  const std::string seed = a.lines[0].substr(at, a.lines[0].find(',', at) - at);
  EXPECT_NE(seed, "0");
  EXPECT_NE(a.lines[1].find("\"seed\": " + seed + ","), std::string::npos);
  const CliRun again = run({"--config", kDefaultConfig, "--seed", seed, "--scenes", "2"});
  EXPECT_EQ(again.out, a.out);
  const CliRun other = run({"--config", kDefaultConfig, "--seed", "0", "--scenes", "2"});
  EXPECT_NE(other.out, a.out);
}

TEST(SampleScenesCli, FailingSceneExitsOne) {
  const TempConfig config("blocked.yaml", kBlockedConfig);
  const CliRun r = run({"--config", config.path, "--seed", "1", "--scenes", "2"});
  EXPECT_EQ(r.status, 1);
  // The same one-line summary as the node's answer.
  EXPECT_EQ(r.err,
            "sample_scenes: scene 0: could not place object 'plate' with sampler 'PlateSampler' "
            "in 20 attempts: 20 of them overlapped fixture 'slab' (2 of 2 scenes failed)\n");
  ASSERT_EQ(r.lines.size(), 2u);
  EXPECT_NE(
      r.lines[0].find("\"success\": false, \"message\": \"could not place object 'plate' with "
                      "sampler 'PlateSampler' in 20 attempts: 20 of them overlapped fixture "
                      "'slab'\""),
      std::string::npos)
      << r.lines[0];
}

TEST(SampleScenesCli, MaxAttemptsFlagOverridesTheConfiguration) {
  const TempConfig config("blocked_attempts.yaml", kBlockedConfig);
  const CliRun r = run({"--config", config.path, "--seed", "1", "--max-attempts", "3"});
  EXPECT_EQ(r.status, 1);
  ASSERT_EQ(r.lines.size(), 1u);
  EXPECT_NE(r.lines[0].find("in 3 attempts: 3 of them overlapped fixture 'slab'"),
            std::string::npos)
      << r.lines[0];
}

TEST(SampleScenesCli, SamplerFlagRunsOneSubSampler) {
  const CliRun r = run(
      {"--config", kDefaultConfig, "--seed", "3", "--scenes", "3", "--sampler", "TableSampler"});
  EXPECT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(r.lines.size(), 3u);
  for (const std::string& line : r.lines) {
    EXPECT_EQ(count(line, "\"name\": "), 3u) << line;
    EXPECT_EQ(count(line, "\"sampler\": \"TableSampler\""), 3u) << line;
  }
  const CliRun bad = run({"--config", kDefaultConfig, "--sampler", "ShelfSampler"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_TRUE(bad.out.empty());
  EXPECT_EQ(bad.err,
            "sample_scenes: unknown sampler 'ShelfSampler' (configured: root, PlateSampler, "
            "CupSampler, TableSampler, HideSampler)\n");
}

TEST(SampleScenesCli, MissingConfigFileExitsTwo) {
  const std::string path = testing::TempDir() + "sample_scenes_cli_does_not_exist.yaml";
  const CliRun r = run({"--config", path});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(r.out.empty());
  EXPECT_EQ(r.err,
            "sample_scenes: " + path + ": cannot read the configuration file: file not found\n");
}

TEST(SampleScenesCli, BadConfigExitsTwoNamingTheFile) {
  const TempConfig typo("typo.yaml", "samplers:\n  - {name: S, x_rnage: [0, 1]}\n");
  const CliRun r = run({"--config", typo.path});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(r.out.empty());
  EXPECT_EQ(
      r.err,
      "sample_scenes: " + typo.path +
          ": samplers[0]: unknown key 'x_rnage' (expected one of: name, type, objects, "
          "x_range, y_range, rotation, rotation_axis, ensure_object_boundary_in_range, "
          "ensure_valid_placement, reference_pos, z_offset, sample_args, max_attempts, "
          "region, keep_out, strategy, resting, min_probability, allow_rolling, relations)\n");
  const TempConfig broken("broken.yaml", "samplers: [1, 2\nseed: 3\n");
  const CliRun s = run({"--config", broken.path});
  EXPECT_EQ(s.status, 2);
  EXPECT_EQ(s.err.rfind("sample_scenes: " + broken.path + ": invalid YAML at line ", 0), 0u)
      << s.err;
}

TEST(SampleScenesCli, UsageErrorsExitTwo) {
  const CliRun unknown = run({"--config", kDefaultConfig, "--bogus", "1"});
  EXPECT_EQ(unknown.status, 2);
  EXPECT_TRUE(unknown.out.empty());
  EXPECT_EQ(unknown.err.rfind("sample_scenes: unknown argument '--bogus'\nusage: sample_scenes", 0),
            0u)
      << unknown.err;
  const CliRun trailing = run({"--config", kDefaultConfig, "--bogus"});
  EXPECT_EQ(trailing.status, 2);
  EXPECT_EQ(trailing.err.rfind("sample_scenes: unknown argument '--bogus'\n", 0), 0u)
      << trailing.err;
  const CliRun noValue = run({"--config", kDefaultConfig, "--seed"});
  EXPECT_EQ(noValue.status, 2);
  EXPECT_EQ(noValue.err.rfind("sample_scenes: --seed: missing value\n", 0), 0u) << noValue.err;
  const CliRun noConfig = run({"--seed", "1"});
  EXPECT_EQ(noConfig.status, 2);
  EXPECT_EQ(noConfig.err.rfind("sample_scenes: --config FILE is required\n", 0), 0u)
      << noConfig.err;
  const CliRun badNumber = run({"--config", kDefaultConfig, "--scenes", "-3"});
  EXPECT_EQ(badNumber.status, 2);
  EXPECT_EQ(badNumber.err.rfind(
                "sample_scenes: --scenes: expected a non-negative integer, got '-3'\n", 0),
            0u)
      << badNumber.err;
  const CliRun tooLarge = run({"--config", kDefaultConfig, "--max-attempts", "4294967296"});
  EXPECT_EQ(tooLarge.status, 2);
  EXPECT_EQ(
      tooLarge.err.rfind(
          "sample_scenes: --max-attempts: 4294967296 is out of range (at most 4294967295)\n", 0),
      0u)
      << tooLarge.err;
  const CliRun badFirst = run({"--config", kDefaultConfig, "--first-scene", "1e3"});
  EXPECT_EQ(badFirst.status, 2);
  EXPECT_EQ(badFirst.err.rfind(
                "sample_scenes: --first-scene: expected a non-negative integer, got '1e3'\n", 0),
            0u)
      << badFirst.err;
  const CliRun badMode = run({"--config", kDefaultConfig, "--collision-check", "exact"});
  EXPECT_EQ(badMode.status, 2);
  EXPECT_NE(badMode.err.find("expected radius, fcl or radius_and_fcl, got 'exact'"),
            std::string::npos)
      << badMode.err;
}

TEST(SampleScenesCli, Help) {
  const CliRun r = run({"--help"});
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("usage: sample_scenes --config FILE", 0), 0u) << r.out;
}

}  // namespace
}  // namespace placement_samplers
