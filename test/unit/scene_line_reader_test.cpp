// sample_scenes --validate's line reader: the poses of one JSON line, exact numbers, fields in
// any order, each error naming what is wrong, and bounded lines and placements.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "cli/scene_line_reader.hpp"

namespace placement_samplers {
namespace {

std::vector<GivenPose> read(const std::string& line, std::uint64_t& scene,
                            std::size_t maxPlacements = 1000) {
  return readSceneLine(line, 42, maxPlacements, scene);
}

/// The LineError message of reading @p line, or "no error".
std::string error(const std::string& line, std::size_t maxPlacements = 1000) {
  std::uint64_t scene = 0;
  try {
    read(line, scene, maxPlacements);
  } catch (const LineError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SceneLineReader, ReadsPosesExactly) {
  std::uint64_t scene = 0;
  const std::vector<GivenPose> poses = read(
      R"({"scene": 18446744073709551615, "seed": 7, "success": true, "message": "", )"
      R"("placements": [{"name": "cube", "sampler": "S", "position": [0.052540095973960144, )"
      R"(-1e-320, 0.8200000000000001], "orientation": [0, 0, 0.6478085070606253, )"
      R"(-0.7618032148658102], "attempts": 1, "extra": {"a": [1, {"b": null}], "c": false}}]})",
      scene);
  EXPECT_EQ(scene, std::numeric_limits<std::uint64_t>::max());
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_EQ(poses[0].name, "cube");
  EXPECT_EQ(poses[0].position.x(), 0.052540095973960144);
  EXPECT_EQ(poses[0].position.y(), -1e-320);
  EXPECT_EQ(poses[0].position.z(), 0.8200000000000001);
  EXPECT_EQ(poses[0].orientation.z(), 0.6478085070606253);
  EXPECT_EQ(poses[0].orientation.w(), -0.7618032148658102);
}

TEST(SceneLineReader, FieldsInAnyOrderSampledPosesFirst) {
  std::uint64_t scene = 0;
  std::vector<GivenPose> poses =
      read(R"({"placements": [{"orientation": [0, 0, 0, 1], "position": [1, 2, 3], "name": "a"}, )"
           R"({"name": "b", "position": [9, 9, 9], "orientation": [0, 0, 0, 1], )"
           R"("sampled_position": [4, 5, 6], "sampled_orientation": [1, 0, 0, 0]}]})",
           scene);
  EXPECT_EQ(scene, 42u) << "no \"scene\": the caller's count";
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].position, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(poses[1].position, Eigen::Vector3d(4, 5, 6));
  EXPECT_EQ(poses[1].orientation.x(), 1.0);
  // NaN and infinities (Python's json writes them) are read; validation calls them bad poses.
  poses = read(R"({"placements": [{"name": "n", "position": [NaN, Infinity, -Infinity], )"
               R"("orientation": [0, 0, 0, 1]}]})",
               scene);
  EXPECT_TRUE(std::isnan(poses[0].position.x()));
  EXPECT_EQ(poses[0].position.z(), -std::numeric_limits<double>::infinity());
}

TEST(SceneLineReader, NamesWithEscapes) {
  std::uint64_t scene = 0;
  const std::vector<GivenPose> poses =
      read(R"({"placements": [{"name": "a\"b\\\u00e9\ud83d\ude00\ud800x", )"
           R"("position": [0, 0, 0], "orientation": [0, 0, 0, 1]}]})",
           scene);
  EXPECT_EQ(poses[0].name, "a\"b\\\xc3\xa9\xf0\x9f\x98\x80\xef\xbf\xbdx");
}

TEST(SceneLineReader, MissingAndBadFields) {
  EXPECT_EQ(error(R"({"scene": 0, "placements": [{"name": "cube"}]})"),
            "placement 0 ('cube'): missing field \"position\"");
  EXPECT_EQ(error(R"({"placements": [{"name": "cube", "position": [1, 2, 3]}]})"),
            "placement 0 ('cube'): missing field \"orientation\"");
  EXPECT_EQ(error(R"({"placements": [{"name": "cube", "position": [1, 2]}]})"),
            "placement 0 ('cube') position: expected a list of 3 numbers");
  EXPECT_EQ(error(R"({"placements": [{"name": "c", "position": [1, "2", 3]}]})"),
            "placement 0 ('c') position: expected a list of 3 numbers");
  EXPECT_EQ(error(R"({"placements": [{"name": "c", "position": 5, "orientation": 1}]})"),
            "placement 0 ('c') position: expected a list of 3 numbers");
  EXPECT_EQ(error(R"({"placements": [{"name": "c", "position": [1, 2, 3], )"
                  R"("orientation": [0, 0, 0, 1, 0]}]})"),
            "placement 0 ('c') orientation: expected a list of 4 numbers");
  EXPECT_EQ(error(R"({"placements": [{"name": "c", "position": [1, 2, 3], )"
                  R"("orientation": [0, 0, 0, 1], "sampled_position": [1, 2, 3], )"
                  R"("sampled_orientation": []}]})"),
            "placement 0 ('c') sampled_orientation: expected a list of 4 numbers");
  EXPECT_EQ(error(R"({"placements": [{"position": [1, 2, 3]}]})"),
            "placement 0: expected an object with a \"name\"");
  EXPECT_EQ(error(R"({"placements": [{"name": 5}]})"),
            "placement 0: expected an object with a \"name\"");
  EXPECT_EQ(error(R"({"placements": [[]]})"), "placement 0: expected an object with a \"name\"");
  EXPECT_EQ(error(R"({"scene": -1, "placements": []})"),
            "\"scene\": expected a non-negative integer");
  EXPECT_EQ(error(R"({"scene": 1.5, "placements": []})"),
            "\"scene\": expected a non-negative integer");
  EXPECT_EQ(error(R"({"scene": 18446744073709551616, "placements": []})"),
            "\"scene\": expected a non-negative integer");
  EXPECT_EQ(error(R"({"scene": 1})"),
            "\"placements\": expected a list of {\"name\", \"position\", \"orientation\"}");
  EXPECT_EQ(error(R"({"placements": {}})"),
            "\"placements\": expected a list of {\"name\", \"position\", \"orientation\"}");
  EXPECT_EQ(error("[1, 2]"), "expected a JSON object (one scene of sample_scenes)");
  EXPECT_EQ(error("scene"), "expected a JSON object (one scene of sample_scenes)");
}

TEST(SceneLineReader, NotJson) {
  EXPECT_EQ(error("{"), "not JSON: expected a key in double quotes at byte 2");
  EXPECT_EQ(error(R"({"placements": []} x)"), "not JSON: text after the scene's object at byte 20");
  EXPECT_EQ(error(R"({"placements": [], "a": [1, 2)"), "not JSON: expected ']' at byte 30");
  EXPECT_EQ(error(R"({"placements": [], "a": "x)"), "not JSON: unterminated string at byte 27");
  EXPECT_EQ(error(R"({"placements": [], "a": 1.2.3})"), "not JSON: bad number at byte 25");
  EXPECT_EQ(error(R"({"placements": [], "a": tru})"), "not JSON: expected a value at byte 25");
  EXPECT_EQ(error(R"({"placements": [], "a": "\q"})"),
            "not JSON: unknown escape in a string at byte 28");
  // Skipped values nest at most 100 levels: a deeper one is an error, not a stack overflow.
  EXPECT_EQ(error("{\"a\": " + std::string(100000, '[')),
            "not JSON: nested deeper than 100 levels at byte 108");
}

TEST(SceneLineReader, PlacementsPerLineBounded) {
  std::string line = "{\"placements\": [";
  for (int i = 0; i < 4; ++i) {
    line += std::string(i ? ", " : "") +
            R"({"name": "o", "position": [0, 0, 0], "orientation": [0, 0, 0, 1]})";
  }
  line += "]}";
  std::uint64_t scene = 0;
  EXPECT_EQ(read(line, scene, 4).size(), 4u);
  EXPECT_EQ(error(line, 3), "\"placements\": more than 3 placements (the limit of a scene)");
}

TEST(SceneLineReader, BoundedLines) {
  std::istringstream in("ab\n\ncd");
  std::string line;
  ASSERT_TRUE(readBoundedLine(in, line, 10));
  EXPECT_EQ(line, "ab");
  ASSERT_TRUE(readBoundedLine(in, line, 10));
  EXPECT_EQ(line, "");
  ASSERT_TRUE(readBoundedLine(in, line, 10)) << "a last line without a newline";
  EXPECT_EQ(line, "cd");
  EXPECT_FALSE(readBoundedLine(in, line, 10));
  std::istringstream exact(std::string(10, 'x') + "\n" + std::string(11, 'y'));
  ASSERT_TRUE(readBoundedLine(exact, line, 10));
  EXPECT_EQ(line.size(), 10u);
  try {
    readBoundedLine(exact, line, 10);
    ADD_FAILURE() << "no LineError";
  } catch (const LineError& e) {
    EXPECT_STREQ(e.what(), "longer than 10 bytes (the limit of a line)");
  }
  EXPECT_EQ(kMaxSceneLineBytes, std::size_t{32} << 20);
}

}  // namespace
}  // namespace placement_samplers
