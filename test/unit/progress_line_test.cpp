// sample_scenes' progress line: its text, and when runSampleScenes shows it.

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "cli/progress_line.hpp"
#include "cli/sample_scenes_cli.hpp"

namespace placement_samplers {
namespace {

const std::string kConfig = std::string(PLACEMENT_SAMPLERS_SOURCE_DIR) + "/config/lift.yaml";

struct CliResult {
  int status = -1;
  std::string out;
  std::string err;
};

CliResult run(std::vector<std::string> args, Terminals terminals = Terminals()) {
  std::ostringstream out;
  std::ostringstream err;
  CliResult r;
  r.status = runSampleScenes(args, out, err, terminals);
  r.out = out.str();
  r.err = err.str();
  return r;
}

TEST(ProgressLine, Text) {
  EXPECT_EQ(progressText(1234, 10000, 3, 2.0),
            "sample_scenes: 1234/10000 scenes (12.3 %), 617 scenes/s, 3 failed, ETA 0:00:14");
  EXPECT_EQ(progressText(0, 10, 0, 0.5),
            "sample_scenes: 0/10 scenes (0.0 %), 0 scenes/s, 0 failed, ETA ?");
  EXPECT_EQ(progressText(1, 1000000, 0, 10.0),
            "sample_scenes: 1/1000000 scenes (0.0 %), 0 scenes/s, 0 failed, ETA 2777:46:30");
}

TEST(ProgressLine, ForcedOutsideATerminalEndsWithTheFinalCounts) {
  const std::vector<std::string> args{"--config", kConfig, "--seed", "2", "--scenes", "50"};
  const CliResult plain = run(args);
  std::vector<std::string> forced = args;
  forced.push_back("--progress");
  const CliResult shown = run(forced);
  EXPECT_EQ(shown.status, 0);
  EXPECT_EQ(shown.out, plain.out);
  EXPECT_EQ(plain.err, "");
  ASSERT_FALSE(shown.err.empty());
  EXPECT_EQ(shown.err.find('\r'), std::string::npos);
  const std::string last = shown.err.substr(shown.err.rfind('\n', shown.err.size() - 2) + 1);
  EXPECT_EQ(last.rfind("sample_scenes: 50/50 scenes (100.0 %), ", 0), 0u) << shown.err;
  EXPECT_NE(last.find(" 0 failed, ETA 0:00:00\n"), std::string::npos) << last;
}

TEST(ProgressLine, ForcedOnATerminalRewritesOneLine) {
  Terminals terminal;
  terminal.err = true;
  const CliResult shown =
      run({"--config", kConfig, "--scenes", "20", "--seed", "2", "--progress"}, terminal);
  EXPECT_EQ(shown.err.front(), '\r');
  EXPECT_EQ(shown.err.back(), '\n');
  EXPECT_NE(shown.err.find("sample_scenes: 20/20 scenes (100.0 %), "), std::string::npos);
  EXPECT_NE(shown.err.find("\x1b[K"), std::string::npos);
}

TEST(ProgressLine, NotForAShortRunNorWhenTheScenesGoToTheTerminalNorWithNoProgress) {
  Terminals both;
  both.out = both.err = true;
  Terminals errOnly;
  errOnly.err = true;
  const std::vector<std::string> args{"--config", kConfig, "--scenes", "5"};
  EXPECT_EQ(run(args, errOnly).err, "");  // a fraction of a second
  std::vector<std::string> quiet = args;
  quiet.push_back("--no-progress");
  EXPECT_EQ(run(quiet, errOnly).err, "");
  EXPECT_EQ(run(args, both).err, "");
  quiet.push_back("--progress");
  const CliResult both_flags = run(quiet);
  EXPECT_EQ(both_flags.status, 2);
  EXPECT_EQ(both_flags.err.rfind("sample_scenes: --progress and --no-progress: choose one\n", 0),
            0u);
}

}  // namespace
}  // namespace placement_samplers
