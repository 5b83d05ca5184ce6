// Pcg64 and SeedSequence (the library's Engine) against numpy: the pool, the PCG64 state, raw
// outputs and Generator.uniform draws that numpy gives for the same seeds, from
// numpy_vectors.inc (scripts/numpy_vectors.py regenerates it with python3-numpy).

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <type_traits>

#include "placement_samplers/sampling/pcg64.hpp"
#include "placement_samplers/sampling/random.hpp"

namespace placement_samplers {
namespace {

static_assert(std::is_same<Engine, Pcg64>::value, "the library's engine is numpy's PCG64");
static_assert(std::is_trivially_copyable<Pcg64>::value, "no heap, copyable state");
static_assert(sizeof(Pcg64) == 32, "two 128-bit words");
static_assert(Pcg64::min() == 0 && Pcg64::max() == std::numeric_limits<std::uint64_t>::max(),
              "full 64-bit outputs");

struct NumpyRow {
  std::uint64_t seed;
  std::uint64_t index;
  bool hasIndex;  ///< false: default_rng(seed); true: default_rng([seed, index])
  bool hidden;    ///< SeedSequence([seed, index]).spawn(1)[0]: the hidden objects' stream
  std::array<std::uint32_t, 4> pool;
  std::array<std::uint64_t, 4> state;  ///< state high, low, inc high, low
  std::array<std::uint64_t, 6> raw;    ///< random_raw(6)
  std::array<double, 5> uniform;       ///< then uniform() over kRanges, one after the other
};

const NumpyRow kRows[] = {
#include "numpy_vectors.inc"
};

// scripts/numpy_vectors.py's UNIFORM_RANGES.
const double kRanges[5][2] = {
    {0.0, 1.0}, {-0.3, 0.3}, {0.0, 2 * M_PI}, {0.25, 0.25}, {-20.0, -10.0}};

SeedSequence sequenceOf(const NumpyRow& row) {
  const std::uint64_t entropy[2] = {row.seed, row.index};
  const std::uint64_t spawnKey[1] = {0};
  return SeedSequence(entropy, row.hasIndex ? 2 : 1, spawnKey, row.hidden ? 1 : 0);
}

Engine engineOf(const NumpyRow& row) {
  if (row.hidden) {
    return hiddenEngine(row.seed, row.index);
  }
  return row.hasIndex ? sceneEngine(row.seed, row.index) : Engine(row.seed);
}

std::string label(const NumpyRow& row) {
  return "seed " + std::to_string(row.seed) +
         (row.hasIndex ? ", index " + std::to_string(row.index) : std::string()) +
         (row.hidden ? " (hidden stream)" : "");
}

TEST(Pcg64, VectorsCoverSeedsAndIndicesBelowAndAbove2To32) {
  bool smallSeed = false, largeSeed = false, index0 = false, index1 = false, largeIndex = false;
  for (const NumpyRow& row : kRows) {
    smallSeed = smallSeed || row.seed < (std::uint64_t{1} << 32);
    largeSeed = largeSeed || row.seed >= (std::uint64_t{1} << 32);
    index0 = index0 || (row.hasIndex && row.index == 0);
    index1 = index1 || (row.hasIndex && row.index == 1);
    largeIndex = largeIndex || (row.hasIndex && row.index >= (std::uint64_t{1} << 32));
  }
  EXPECT_TRUE(smallSeed && largeSeed && index0 && index1 && largeIndex);
}

TEST(Pcg64, SeedSequencePoolIsNumpys) {
  for (const NumpyRow& row : kRows) {
    EXPECT_EQ(sequenceOf(row).pool(), row.pool) << label(row);
    if (row.hasIndex && !row.hidden) {
      EXPECT_EQ(SeedSequence::ofPair(row.seed, row.index).pool(), row.pool) << label(row);
    }
  }
}

TEST(Pcg64, SeededStateIsNumpys) {
  for (const NumpyRow& row : kRows) {
    EXPECT_EQ(engineOf(row).stateWords(), row.state) << label(row);
    EXPECT_EQ(Engine(sequenceOf(row)).stateWords(), row.state) << label(row);
  }
}

TEST(Pcg64, ScenesSeededTogetherAreScenesSeededAlone) {
  // forScenes against forScene (which the numpy vectors check): counts that are not a multiple
  // of its lanes, seeds and indices of one and two 32-bit words, indices across 2^32.
  const std::uint64_t seeds[] = {
      0, 1, 20240605, 0xffffffffULL, 0x100000000ULL, std::numeric_limits<std::uint64_t>::max()};
  const std::uint64_t firsts[] = {0,
                                  1,
                                  1000,
                                  0xffffffffULL - 9,
                                  0x100000000ULL,
                                  std::numeric_limits<std::uint64_t>::max() - 20};
  for (const std::uint64_t seed : seeds) {
    for (const std::uint64_t first : firsts) {
      for (const std::size_t count :
           {std::size_t{1}, std::size_t{7}, std::size_t{16}, std::size_t{21}}) {
        std::array<Engine, 21> engines;
        Engine::forScenes(seed, first, count, engines.data());
        for (std::size_t k = 0; k < count; ++k) {
          EXPECT_EQ(engines[k].stateWords(), sceneEngine(seed, first + k).stateWords())
              << "seed " << seed << ", scene " << first + k;
        }
      }
    }
  }
}

TEST(Pcg64, RawOutputsAreNumpys) {
  for (const NumpyRow& row : kRows) {
    Engine engine = engineOf(row);
    for (std::size_t k = 0; k < row.raw.size(); ++k) {
      EXPECT_EQ(engine(), row.raw[k]) << label(row) << ", output " << k;
    }
  }
}

TEST(Pcg64, UniformDrawsAreNumpysBitForBit) {
  for (const NumpyRow& row : kRows) {
    Engine engine = engineOf(row);
    for (std::size_t k = 0; k < row.raw.size(); ++k) {
      engine();
    }
    for (std::size_t k = 0; k < row.uniform.size(); ++k) {
      const double draw = uniform(engine, kRanges[k][0], kRanges[k][1]);
      EXPECT_EQ(draw, row.uniform[k]) << label(row) << ", uniform " << k;
      EXPECT_GE(draw, kRanges[k][0]);
      EXPECT_TRUE(draw < kRanges[k][1] || kRanges[k][0] == kRanges[k][1]);
    }
  }
}

TEST(Pcg64, EngineFromNumpysStateContinuesNumpysStream) {
  for (const NumpyRow& row : kRows) {
    // numpy's bit_generator.state after seeding, set on a fresh engine: numpy's next outputs.
    Engine engine = Engine::fromState(row.state[0], row.state[1], row.state[2], row.state[3]);
    EXPECT_EQ(engine.stateWords(), row.state) << label(row);
    for (std::size_t k = 0; k < row.raw.size(); ++k) {
      EXPECT_EQ(engine(), row.raw[k]) << label(row) << ", output " << k;
    }
    for (std::size_t k = 0; k < row.uniform.size(); ++k) {
      EXPECT_EQ(uniform(engine, kRanges[k][0], kRanges[k][1]), row.uniform[k]) << label(row);
    }
  }
}

TEST(Pcg64, StateWordsRoundTripMidStream) {
  Engine original = sceneEngine(9, 4);
  for (int k = 0; k < 37; ++k) {
    original();
  }
  const std::array<std::uint64_t, 4> words = original.stateWords();
  Engine copy = Engine::fromState(words[0], words[1], words[2], words[3]);
  EXPECT_EQ(copy.stateWords(), words);
  for (int k = 0; k < 100; ++k) {
    ASSERT_EQ(copy(), original());
  }
  // An even increment is kept as given (numpy's state setter keeps it too).
  Engine even = Engine::fromState(0, 5, 0, 4);
  EXPECT_EQ(even.stateWords()[3], 4u);
  even();
  EXPECT_NE(even.stateWords()[1], 5u);
}

TEST(Pcg64, GenerateStateWordsPairUpLittleEndian) {
  const SeedSequence sequence = SeedSequence::ofPair(42, 7);
  std::uint32_t words32[8];
  std::uint64_t words64[4];
  sequence.generateState(words32, 8);
  sequence.generateState64(words64, 4);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(words64[k], words32[2 * k] | (std::uint64_t{words32[2 * k + 1]} << 32));
  }
}

TEST(Pcg64, CopiesContinueTheSameStream) {
  Engine original = sceneEngine(5, 5);
  original();
  Engine copy = original;
  for (int k = 0; k < 100; ++k) {
    ASSERT_EQ(copy(), original());
  }
}

TEST(Pcg64, ScenesAndTheHiddenStreamDiffer) {
  // Neighbouring indices, the same pair in the other order and the hidden stream: all apart.
  const std::uint64_t first[] = {sceneEngine(1, 2)(), sceneEngine(1, 3)(), sceneEngine(2, 1)(),
                                 hiddenEngine(1, 2)(), Engine(1)()};
  for (std::size_t a = 0; a < 5; ++a) {
    for (std::size_t b = a + 1; b < 5; ++b) {
      EXPECT_NE(first[a], first[b]) << a << " " << b;
    }
  }
}

TEST(Pcg64, WorksWithStandardDistributions) {
  Engine engine = sceneEngine(3, 4);
  std::uniform_int_distribution<int> dice(1, 6);
  int counts[7] = {};
  for (int k = 0; k < 6000; ++k) {
    ++counts[dice(engine)];
  }
  for (int face = 1; face <= 6; ++face) {
    EXPECT_NEAR(counts[face], 1000, 150) << face;
  }
}

TEST(Pcg64, SeedSequenceNeedsEntropyAndBoundsIt) {
  EXPECT_THROW(SeedSequence(nullptr, 0), std::invalid_argument);
  const std::uint64_t many[7] = {~0ULL, ~0ULL, ~0ULL, ~0ULL, ~0ULL, ~0ULL, ~0ULL};
  EXPECT_THROW(SeedSequence(many, 7), std::invalid_argument);
  EXPECT_NO_THROW(SeedSequence(many, 6));
}

}  // namespace
}  // namespace placement_samplers
