// Mt19937_64 (the library's Engine) against std::mt19937_64: the same numbers for every seed,
// across the lazy first 156 draws, the end of the first regeneration (312) and later ones (624),
// after re-seeding mid-stream and after discard().

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

#include "placement_samplers/mt19937_64.hpp"
#include "placement_samplers/random.hpp"

namespace placement_samplers {
namespace {

constexpr int kDraws = 2000;  // crosses 156, 312, 624, 936, ... 1872

static_assert(std::is_same<Engine, Mt19937_64>::value, "the library's engine");
static_assert(std::is_same<Mt19937_64::result_type, std::uint64_t>::value, "result_type");
static_assert(Mt19937_64::min() == std::mt19937_64::min(), "min()");
static_assert(Mt19937_64::max() == std::mt19937_64::max(), "max()");
static_assert(Mt19937_64::max() == std::numeric_limits<std::uint64_t>::max(), "max()");
static_assert(Mt19937_64::kDefaultSeed == std::mt19937_64::default_seed, "default seed");
static_assert(std::is_trivially_copyable<Mt19937_64>::value, "no heap, copyable state");

/// About 200 seeds: edge values, scene seeds as the generator makes them, random values.
std::vector<std::uint64_t> testSeeds() {
  std::vector<std::uint64_t> seeds = {0,
                                      1,
                                      2,
                                      5489,
                                      0xFFFFFFFFULL,
                                      0x100000000ULL,
                                      std::uint64_t{1} << 62,
                                      std::uint64_t{3} << 62,
                                      std::uint64_t{1} << 63,
                                      std::numeric_limits<std::uint64_t>::max(),
                                      std::numeric_limits<std::uint64_t>::max() - 1};
  for (std::uint64_t i = 0; i < 60; ++i) {
    seeds.push_back(sceneSeed(42, i));
    seeds.push_back(sceneSeed(20240605, i));
  }
  std::mt19937_64 random(20240605);
  while (seeds.size() < 200) {
    seeds.push_back(random());
  }
  return seeds;
}

/// Draws @p count numbers from both and expects them equal; returns false at the first mismatch.
bool sameDraws(Mt19937_64& ours, std::mt19937_64& reference, int count) {
  for (int i = 0; i < count; ++i) {
    const std::uint64_t expected = reference();
    const std::uint64_t actual = ours();
    if (actual != expected) {
      ADD_FAILURE() << "draw " << i << ": " << actual << " != " << expected;
      return false;
    }
  }
  return true;
}

TEST(Mt19937_64, SameNumbersAsStdForManySeeds) {
  const std::vector<std::uint64_t> seeds = testSeeds();
  ASSERT_GE(seeds.size(), 200u);
  for (const std::uint64_t seed : seeds) {
    Mt19937_64 ours(seed);
    std::mt19937_64 reference(seed);
    EXPECT_TRUE(sameDraws(ours, reference, kDraws)) << "seed " << seed;
  }
}

TEST(Mt19937_64, SeedOnTheSameObject) {
  const std::vector<std::uint64_t> seeds = testSeeds();
  Mt19937_64 ours;
  std::mt19937_64 reference;
  for (const std::uint64_t seed : seeds) {
    ours.seed(seed);
    reference.seed(seed);
    ASSERT_TRUE(sameDraws(ours, reference, kDraws)) << "seed " << seed;
  }
}

TEST(Mt19937_64, ReseedMidStream) {
  // Re-seeding inside the lazy part (10), between 156 and 312 (200), in a later block (400) and
  // at the boundaries themselves.
  const int before[] = {0, 1, 10, 155, 156, 157, 200, 311, 312, 313, 400, 623, 624, 625};
  const std::uint64_t seeds[] = {0, 5489, sceneSeed(42, 7),
                                 std::numeric_limits<std::uint64_t>::max()};
  for (const std::uint64_t first : seeds) {
    for (const std::uint64_t second : seeds) {
      for (const int n : before) {
        Mt19937_64 ours(first);
        std::mt19937_64 reference(first);
        ASSERT_TRUE(sameDraws(ours, reference, n));
        ours.seed(second);
        reference.seed(second);
        EXPECT_TRUE(sameDraws(ours, reference, kDraws))
            << "seed " << first << ", " << n << " draws, then seed " << second;
        // And a third time, so that a seed after a completed regeneration is covered too.
        ours.seed(first);
        reference.seed(first);
        EXPECT_TRUE(sameDraws(ours, reference, 700));
      }
    }
  }
}

TEST(Mt19937_64, Discard) {
  const unsigned long long counts[] = {0,   1,   2,   100, 154, 155, 156, 157,  200,
                                       311, 312, 313, 500, 623, 624, 625, 1000, 5000};
  const int drawnBefore[] = {0, 1, 7, 155, 156, 200, 312, 400};
  for (const std::uint64_t seed : {std::uint64_t{0}, std::uint64_t{5489}, sceneSeed(1, 2)}) {
    for (const int drawn : drawnBefore) {
      for (const unsigned long long count : counts) {
        Mt19937_64 ours(seed);
        std::mt19937_64 reference(seed);
        ASSERT_TRUE(sameDraws(ours, reference, drawn));
        ours.discard(count);
        reference.discard(count);
        EXPECT_TRUE(sameDraws(ours, reference, 700))
            << "seed " << seed << ", " << drawn << " draws, discard(" << count << ")";
      }
    }
  }
}

TEST(Mt19937_64, DefaultSeed) {
  Mt19937_64 ours;
  std::mt19937_64 reference;
  EXPECT_TRUE(sameDraws(ours, reference, kDraws));
  // The standard's check: the 10000th number of a default-constructed std::mt19937_64.
  Mt19937_64 standard;
  standard.discard(9999);
  EXPECT_EQ(standard(), 9981545732273789042ULL);
}

TEST(Mt19937_64, CopiesContinueTheSameSequence) {
  for (const int drawn : {0, 3, 156, 400}) {
    Mt19937_64 original(sceneSeed(5, 5));
    std::mt19937_64 reference(sceneSeed(5, 5));
    ASSERT_TRUE(sameDraws(original, reference, drawn));
    Mt19937_64 copy = original;
    std::mt19937_64 referenceCopy = reference;
    EXPECT_TRUE(sameDraws(original, reference, 1000));
    EXPECT_TRUE(sameDraws(copy, referenceCopy, 1000)) << drawn << " draws before the copy";
  }
}

TEST(Mt19937_64, RandomMixOfSeedsDrawsAndDiscards) {
  Mt19937_64 ours;
  std::mt19937_64 reference;
  std::mt19937_64 plan(99);
  for (int step = 0; step < 2000; ++step) {
    const std::uint64_t what = plan() % 8;
    if (what == 0) {
      const std::uint64_t seed = plan();
      ours.seed(seed);
      reference.seed(seed);
    } else if (what == 1) {
      const unsigned long long count = plan() % 700;
      ours.discard(count);
      reference.discard(count);
    } else {
      ASSERT_TRUE(sameDraws(ours, reference, static_cast<int>(plan() % 400))) << "step " << step;
    }
  }
}

TEST(Mt19937_64, WorksWithStandardDistributions) {
  Mt19937_64 ours(123);
  std::mt19937_64 reference(123);
  std::uniform_int_distribution<int> distribution(0, 9);
  for (int i = 0; i < 1000; ++i) {
    ASSERT_EQ(distribution(ours), distribution(reference));
  }
}

// seedMany() as a batch uses it: 1 to 19, 32 and 35 engines (the scalar groups of eight, whole
// and partial, and on AVX-512 machines the vector path's groups of 16 with a scalar rest),
// engines that drew before, then draws across every regeneration.
TEST(Mt19937_64, SeedManyGivesTheNumbersOfSeed) {
  const std::vector<std::uint64_t> seeds = testSeeds();
  std::vector<Mt19937_64> engines(35);
  std::vector<std::size_t> counts;
  for (std::size_t count = 1; count <= 19; ++count) {
    counts.push_back(count);
  }
  counts.push_back(32);
  counts.push_back(35);
  std::size_t used = 0;
  for (const std::size_t count : counts) {
    std::vector<Mt19937_64*> pointers;
    std::vector<std::uint64_t> batch;
    for (std::size_t k = 0; k < count; ++k) {
      engines[k]();  // a used engine: seedMany must restart it
      pointers.push_back(&engines[k]);
      batch.push_back(seeds[used++ % seeds.size()]);
    }
    Mt19937_64::seedMany(pointers.data(), batch.data(), count);
    for (std::size_t k = 0; k < count; ++k) {
      std::mt19937_64 reference(batch[k]);
      for (int i = 0; i < kDraws / 2; ++i) {
        ASSERT_EQ(engines[k](), reference())
            << "seed " << batch[k] << ", group of " << count << ", engine " << k << ", draw " << i;
      }
    }
  }
}

}  // namespace
}  // namespace placement_samplers
