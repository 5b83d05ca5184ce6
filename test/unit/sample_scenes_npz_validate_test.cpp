// sample_scenes --output FILE.npz and --validate, run in-process: files, verdict lines, exit
// codes and error messages.

#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/sample_scenes_cli.hpp"

namespace placement_samplers {
namespace {

const std::string kDefaultConfig =
    std::string(PLACEMENT_SAMPLERS_SOURCE_DIR) + "/config/default.yaml";

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

/// A file in the test temporary directory, removed when the test ends.
struct TempFile {
  explicit TempFile(const std::string& name, const std::string& text = "")
      : path(testing::TempDir() + "npz_validate_" + std::to_string(getpid()) + "_" + name) {
    if (!text.empty()) {
      std::ofstream(path) << text;
    }
  }
  ~TempFile() { std::remove(path.c_str()); }
  std::string path;
};

TEST(SampleScenesNpz, WritesTheFileAndPrintsNothing) {
  const TempFile npz("scenes.npz");
  const CliRun r =
      run({"--config", kDefaultConfig, "--seed", "7", "--scenes", "20", "--output", npz.path});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "");
  std::ifstream in(npz.path, std::ios::binary);
  std::string magic(4, '\0');
  in.read(&magic[0], 4);
  EXPECT_EQ(magic, std::string("PK\x03\x04", 4));
}

TEST(SampleScenesNpz, Errors) {
  CliRun r = run({"--config", kDefaultConfig, "--output", "scenes.json"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.substr(0, r.err.find('\n')),
            "sample_scenes: --output: expected a file name ending in .npz, got 'scenes.json'");
  r = run({"--config", kDefaultConfig, "--output", "/nonexistent-dir/scenes.npz"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err,
            "sample_scenes: /nonexistent-dir/scenes.npz: cannot create: No such file or "
            "directory\n");
  r = run({"--config", kDefaultConfig, "--output"});
  EXPECT_EQ(r.err.substr(0, r.err.find('\n')), "sample_scenes: --output: missing value");
}

TEST(SampleScenesValidate, SampledScenesAreValid) {
  const CliRun sampled =
      run({"--config", kDefaultConfig, "--seed", "7", "--scenes", "30", "--first-scene", "5"});
  ASSERT_EQ(sampled.status, 0) << sampled.err;
  const TempFile scenes("scenes.jsonl", sampled.out);
  for (const char* mode : {"radius", "fcl", "radius_and_fcl"}) {
    const CliRun sampledMode = run(
        {"--config", kDefaultConfig, "--seed", "7", "--scenes", "10", "--collision-check", mode});
    const TempFile modeScenes(std::string("scenes_") + mode + ".jsonl", sampledMode.out);
    const CliRun r =
        run({"--config", kDefaultConfig, "--collision-check", mode, "--validate", modeScenes.path});
    EXPECT_EQ(r.status, 0) << mode << ": " << r.out << r.err;
    EXPECT_EQ(r.lines.size(), 10u) << mode;
  }
  const CliRun r = run({"--config", kDefaultConfig, "--validate", scenes.path});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  ASSERT_EQ(r.lines.size(), 30u);
  EXPECT_EQ(r.lines[0],
            "{\"scene\": 5, \"valid\": true, \"objects\": [{\"name\": \"plate\", \"valid\": "
            "true, \"reasons\": []}, {\"name\": \"cup\", \"valid\": true, \"reasons\": []}, "
            "{\"name\": \"cube\", \"valid\": true, \"reasons\": []}, {\"name\": \"can\", "
            "\"valid\": true, \"reasons\": []}, {\"name\": \"ball\", \"valid\": true, "
            "\"reasons\": []}, {\"name\": \"pill\", \"valid\": true, \"reasons\": []}]}");
}

TEST(SampleScenesValidate, InvalidSceneAndReasons) {
  const CliRun sampled = run({"--config", kDefaultConfig, "--seed", "7", "--scenes", "2"});
  ASSERT_EQ(sampled.lines.size(), 2u);
  // Scene 1 with the plate 1 m higher: its height, and the cup's (it stands on the plate).
  std::string line = sampled.lines[1];
  const std::size_t plate = line.find("\"position\": [");
  const std::size_t z = line.find(", ", line.find(", ", plate) + 1) + 2;
  line.replace(z, line.find(']', z) - z, "1.82");
  const TempFile scenes("edited.jsonl", sampled.lines[0] + "\n\n" + line + "\n");
  const CliRun r = run({"--config", kDefaultConfig, "--validate", scenes.path});
  EXPECT_EQ(r.status, 1) << r.err;
  ASSERT_EQ(r.lines.size(), 2u) << "the blank line is skipped";
  EXPECT_EQ(r.lines[0].rfind("{\"scene\": 0, \"valid\": true", 0), 0u);
  EXPECT_EQ(r.lines[1].rfind("{\"scene\": 1, \"valid\": false", 0), 0u) << r.lines[1];
  EXPECT_NE(r.lines[1].find("{\"name\": \"plate\", \"valid\": false, \"reasons\": [{\"kind\": "
                            "\"height\", \"sampler\": \"PlateSampler\", \"other\": \"\", "
                            "\"check\": \"\", \"distance\": "),
            std::string::npos)
      << r.lines[1];
  EXPECT_NE(r.lines[1].find("\"message\": \"object 'cup' is at z 0.875 m, off the height of "
                            "sampler 'CupSampler' (1.875 m) by 1 m\""),
            std::string::npos)
      << r.lines[1];
  // A looser tolerance does not hide a metre.
  EXPECT_EQ(
      run({"--config", kDefaultConfig, "--validate", scenes.path, "--height-tolerance", "0.5"})
          .status,
      1);
}

TEST(SampleScenesValidate, BadInput) {
  const TempFile notObject("list.jsonl", "[1, 2]\n");
  CliRun r = run({"--config", kDefaultConfig, "--validate", notObject.path});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "sample_scenes: --validate " + notObject.path +
                       ": line 1: expected a JSON object (one scene of sample_scenes)\n");
  const TempFile badPosition("position.jsonl",
                             "{\"placements\": [{\"name\": \"cube\", \"position\": [1, 2]}]}\n");
  r = run({"--config", kDefaultConfig, "--validate", badPosition.path});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "sample_scenes: --validate " + badPosition.path +
                       ": line 1: placement 0 ('cube') position: expected a list of 3 numbers\n");
  r = run({"--config", kDefaultConfig, "--validate", "/nonexistent-dir/x.jsonl"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "sample_scenes: --validate /nonexistent-dir/x.jsonl: cannot open\n");
  r = run({"--config", kDefaultConfig, "--validate", "-", "--height-tolerance", "-1"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.substr(0, r.err.find('\n')),
            "sample_scenes: --height-tolerance: expected a non-negative number of metres, got "
            "'-1'");
}

TEST(SampleScenesValidate, MissingFieldNamesTheLine) {
  const TempFile scenes("missing.jsonl",
                        "\n{\"scene\": 0, \"placements\": [{\"name\": \"cube\"}]}\n");
  const CliRun r = run({"--config", kDefaultConfig, "--validate", scenes.path});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "sample_scenes: --validate " + scenes.path +
                       ": line 2: placement 0 ('cube'): missing field \"position\"\n");
}

TEST(SampleScenesValidate, PlacementsPerSceneBounded) {
  std::string good = "{\"placements\": [";
  for (int i = 0; i <= 100000; ++i) {
    good += std::string(i ? ", " : "") +
            "{\"name\": \"c\", \"position\": [0, 0, 0], \"orientation\": [0, 0, 0, 1]}";
  }
  const TempFile tooMany("too_many.jsonl", good + "]}\n");
  const CliRun many = run({"--config", kDefaultConfig, "--validate", tooMany.path});
  EXPECT_EQ(many.status, 2);
  EXPECT_EQ(many.err, "sample_scenes: --validate " + tooMany.path +
                          ": line 1: \"placements\": more than 100000 placements (the limit of a "
                          "scene)\n");
}

/// A name that is not valid UTF-8 (from input) still gives a JSON line: U+FFFD in its place.
TEST(SampleScenesValidate, InvalidUtf8NameGivesJson) {
  const TempFile scenes("utf8.jsonl",
                        "{\"placements\": [{\"name\": \"b\xff\xc3\", \"position\": [0, 0, 0], "
                        "\"orientation\": [0, 0, 0, 1]}]}\n");
  const CliRun r = run({"--config", kDefaultConfig, "--validate", scenes.path});
  EXPECT_EQ(r.status, 1) << r.err;
  ASSERT_EQ(r.lines.size(), 1u);
  EXPECT_EQ(r.lines[0].find('\xff'), std::string::npos);
  EXPECT_NE(r.lines[0].find("{\"name\": \"b\xef\xbf\xbd\xef\xbf\xbd\", \"valid\": false, "
                            "\"reasons\": [{\"kind\": \"unknown_object\""),
            std::string::npos)
      << r.lines[0];
  // The message shows the bytes escaped, as every message does.
  EXPECT_NE(r.lines[0].find("\"message\": \"object 'b\\\\xff\\\\xc3' is not placed by sampler"),
            std::string::npos)
      << r.lines[0];
}

TEST(SampleScenesValidate, OutputIsRefused) {
  CliRun r = run({"--config", kDefaultConfig, "--validate", "-", "--output", "x.npz"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.substr(0, r.err.find('\n')),
            "sample_scenes: --output writes sampled scenes; --validate prints JSON to stdout "
            "instead (drop --output)");
  r = run({"--config", kDefaultConfig, "--describe", "--output", "x.npz"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.substr(0, r.err.find('\n')),
            "sample_scenes: --output writes sampled scenes; --describe prints JSON to stdout "
            "instead (drop --output)");
  r = run({"--config", kDefaultConfig, "--describe", "--validate", "-"});
  EXPECT_EQ(r.err.substr(0, r.err.find('\n')),
            "sample_scenes: --describe and --validate: choose one");
  // Flags that only change sampling have no effect on --validate: refused, not ignored.
  for (const char* flag : {"--seed", "--scenes", "--first-scene", "--max-attempts", "--threads",
                           "--physics", "--max-scene-seconds"}) {
    r = run({"--config", kDefaultConfig, "--validate", "-", flag, "1"});
    EXPECT_EQ(r.status, 2) << flag;
    EXPECT_EQ(r.err.substr(0, r.err.find('\n')),
              std::string("sample_scenes: ") + flag +
                  " changes how scenes are sampled; --validate checks the poses it reads (drop " +
                  flag + ")");
  }
  r = run({"--config", kDefaultConfig, "--validate", testing::TempDir()});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.rfind("sample_scenes: --validate ", 0), 0u);
  EXPECT_EQ(r.err.substr(r.err.size() - 17), ": is a directory\n");
}

/// A FIFO as the .npz file: refused at once, whether a reader waits on it or not (opening it
/// for writing would wait for one).
TEST(SampleScenesNpz, FifoIsRefused) {
  const TempFile fifo("fifo.npz");
  ASSERT_EQ(::mkfifo(fifo.path.c_str(), 0600), 0);
  const CliRun r = run({"--config", kDefaultConfig, "--output", fifo.path});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "sample_scenes: " + fifo.path +
                       ": is a FIFO or socket: an .npz file is written at offsets, so it must be "
                       "a regular file\n");
  const int reader = ::open(fifo.path.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  EXPECT_EQ(run({"--config", kDefaultConfig, "--output", fifo.path}).err, r.err);
  ::close(reader);
}

TEST(SampleScenesCli, MaxSceneSeconds) {
  CliRun r = run({"--config", kDefaultConfig, "--max-scene-seconds", "-1"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.substr(0, r.err.find('\n')),
            "sample_scenes: --max-scene-seconds: expected a non-negative number of seconds (at "
            "most 1e+06), got '-1'");
  r = run({"--config", kDefaultConfig, "--max-scene-seconds", "2e6"});
  EXPECT_EQ(r.status, 2);
  r = run({"--config", kDefaultConfig, "--max-scene-seconds"});
  EXPECT_EQ(r.err.substr(0, r.err.find('\n')), "sample_scenes: --max-scene-seconds: missing value");
  // 0 = no limit; a limit changes nothing for scenes that end in time.
  const CliRun plain = run({"--config", kDefaultConfig, "--seed", "3", "--scenes", "5"});
  EXPECT_EQ(
      run({"--config", kDefaultConfig, "--seed", "3", "--scenes", "5", "--max-scene-seconds", "0"})
          .out,
      plain.out);
  EXPECT_EQ(run({"--config", kDefaultConfig, "--seed", "3", "--scenes", "5", "--max-scene-seconds",
                 "100"})
                .out,
            plain.out);
  // The simulation counts too: its clock is the scene's (started when the simulation starts,
  // sampling being quick here), each scene fails on its own.
  r = run({"--config", kDefaultConfig, "--seed", "3", "--scenes", "2", "--threads", "1",
           "--physics", "check", "--max-scene-seconds", "1e-6"});
  EXPECT_EQ(r.status, 1);
  ASSERT_EQ(r.lines.size(), 2u);
  for (const std::string& line : r.lines) {
    EXPECT_NE(line.find("\"message\": \"not finished: the scene ran out of time (its limit is "
                        "1e-06 s) while simulating it\""),
              std::string::npos)
        << line;
  }
}

}  // namespace
}  // namespace placement_samplers
