// SampleProgress: the scenes of a range counted as they finish, and cancelling it between
// scenes without changing any scene that was sampled.

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "placement_samplers/sampling/scene_generator.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::buildFromYaml;

// Discs on a small table: about a fifth of the scenes fail with max_attempts 40.
const std::string kDiscs = R"(
ground_z: 0.8
max_attempts: 40
objects:
  a: {shape: cylinder, radius: 0.05, length: 0.04}
  b: {shape: cylinder, radius: 0.05, length: 0.04}
  c: {shape: cylinder, radius: 0.05, length: 0.04}
  d: {shape: cylinder, radius: 0.05, length: 0.04}
samplers:
  - name: Table
    objects: [a, b, c, d]
    x_range: [-0.15, 0.15]
    y_range: [-0.15, 0.15]
    reference_pos: [0, 0, 0.8]
)";

std::uint64_t countFailed(const std::vector<SceneResult>& scenes) {
  std::uint64_t failed = 0;
  for (const SceneResult& s : scenes) {
    failed += s.success ? 0 : 1;
  }
  return failed;
}

TEST(SampleProgress, CountsEveryFinishedSceneAndChangesNone) {
  const SceneGenerator generator(buildFromYaml(kDiscs));
  const PreparedRequest request = generator.prepare({});
  const std::vector<SceneResult> plain = generator.sampleSceneRange(request, 9, 3, 500, 1);
  for (unsigned threads : {1u, 2u}) {
    SampleProgress progress;
    std::vector<SceneResult> counted;
    generator.sampleSceneRange(request, 9, 3, 500, threads, counted, &progress);
    EXPECT_EQ(progress.done.load(), 500u);
    const std::uint64_t failed = countFailed(plain);
    EXPECT_GT(failed, 0u);  // the configuration fails some scenes: the count is tested
    EXPECT_EQ(progress.failed.load(), failed);
    ASSERT_EQ(counted.size(), plain.size());
    for (std::size_t i = 0; i < plain.size(); ++i) {
      EXPECT_EQ(counted[i].success, plain[i].success);
      EXPECT_EQ(counted[i].message, plain[i].message);
      test::expectSamePlacements(counted[i].placements, plain[i].placements);
    }
  }
}

TEST(SampleProgress, CancelledBeforeTheStartSamplesNothing) {
  const SceneGenerator generator(buildFromYaml(kDiscs));
  const PreparedRequest request = generator.prepare({});
  SampleProgress progress;
  progress.cancel = true;
  std::vector<SceneResult> out;
  generator.sampleSceneRange(request, 9, 0, 100, 2, out, &progress);
  ASSERT_EQ(out.size(), 100u);
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_TRUE(wasCancelled(out[i])) << out[i].message;
    EXPECT_EQ(out[i].message, "not sampled: cancelled");
    EXPECT_EQ(out[i].index, i);
    EXPECT_TRUE(out[i].placements.empty());
  }
  EXPECT_EQ(progress.done.load(), 0u);
  EXPECT_EQ(progress.failed.load(), 0u);
  // A cancelled probe is no proof of a hopeless request: it does not give up.
  EXPECT_FALSE(generator.sampleSceneRangeOrGiveUp(request, 9, 0, 100, 2, 8, out, &progress));
  EXPECT_EQ(out.size(), 100u);
  EXPECT_TRUE(wasCancelled(out.back()));
}

TEST(SampleProgress, CancelMidwayKeepsTheScenesDone) {
  // Simulated scenes take a millisecond or more each: 5000 of them run long after the cancel.
  const SceneGenerator generator(buildFromYaml(kDiscs + "physics: check\n"));
  const PreparedRequest request = generator.prepare({});
  SampleProgress progress;
  std::thread canceller([&] {
    while (progress.done.load() < 20) {
      std::this_thread::yield();
    }
    progress.cancel = true;
  });
  std::vector<SceneResult> out;
  generator.sampleSceneRange(request, 4, 0, 5000, 2, out, &progress);
  canceller.join();
  ASSERT_EQ(out.size(), 5000u);
  std::uint64_t sampled = 0;
  std::uint64_t failed = 0;
  for (const SceneResult& s : out) {
    sampled += wasCancelled(s) ? 0 : 1;
    failed += !s.success && !wasCancelled(s) ? 1 : 0;
  }
  EXPECT_EQ(progress.done.load(), sampled);
  EXPECT_EQ(progress.failed.load(), failed);
  EXPECT_GE(sampled, 20u);
  EXPECT_LT(sampled, 5000u);
  // Every scene sampled is the one an uncancelled range gives.
  for (const SceneResult& s : out) {
    if (!wasCancelled(s) && s.index < 200) {
      const SceneResult alone = generator.sampleScene(request, 4, s.index);
      EXPECT_EQ(s.success, alone.success);
      EXPECT_EQ(s.stable, alone.stable);
      test::expectSamePlacements(s.placements, alone.placements);
    }
  }
}

}  // namespace
}  // namespace placement_samplers
