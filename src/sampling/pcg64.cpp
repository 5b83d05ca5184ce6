#include "placement_samplers/sampling/pcg64.hpp"

#include <stdexcept>
#include <string>

namespace placement_samplers {
namespace {

// SeedSequence's constants (numpy/random/bit_generator.pyx).
constexpr std::uint32_t kInitA = 0x43b0d7e5;
constexpr std::uint32_t kMultA = 0x931e8875;
constexpr std::uint32_t kInitB = 0x8b51f9dd;
constexpr std::uint32_t kMultB = 0x58f38ded;
constexpr std::uint32_t kMixMultL = 0xca01f9dd;
constexpr std::uint32_t kMixMultR = 0x4973f715;
constexpr unsigned kXShift = 16;

/// numpy's hashmix: xor with the running constant, advance it, multiply by the new one.
inline std::uint32_t hashMix(std::uint32_t value, std::uint32_t& hashConst) {
  value ^= hashConst;
  hashConst *= kMultA;
  value *= hashConst;
  return value ^ (value >> kXShift);
}

/// The running constants, init * mult^k for k = 0 .. N - 1, known at compile time: the scene
/// path then has no serial chain of constant multiplications (seeding is per scene).
template <std::size_t N>
constexpr std::array<std::uint32_t, N> powers(std::uint32_t init, std::uint32_t mult) {
  std::array<std::uint32_t, N> out{};
  out[0] = init;
  for (std::size_t k = 1; k < N; ++k) {
    out[k] = out[k - 1] * mult;
  }
  return out;
}

// mixEntropy's first 4 + 12 hashmix calls; generate_state's first 8 words (PCG64's seed).
constexpr std::size_t kPoolHashes = SeedSequence::kPoolSize * SeedSequence::kPoolSize;
constexpr std::array<std::uint32_t, kPoolHashes + 1> kHashA =
    powers<kPoolHashes + 1>(kInitA, kMultA);
constexpr std::array<std::uint32_t, 9> kHashB = powers<9>(kInitB, kMultB);

/// hashmix call @p k of mix_entropy.
inline std::uint32_t hashMixAt(std::uint32_t value, std::size_t k) {
  value ^= kHashA[k];
  value *= kHashA[k + 1];
  return value ^ (value >> kXShift);
}

inline std::uint32_t mix(std::uint32_t x, std::uint32_t y) {
  const std::uint32_t result = kMixMultL * x - kMixMultR * y;
  return result ^ (result >> kXShift);
}

/// Appends numpy's 32-bit words of @p value (lowest first; zero is one word) to @p words.
void appendWords(std::uint64_t value, std::uint32_t* words, std::size_t& count) {
  if (count + 2 > SeedSequence::kMaxWords) {
    throw std::invalid_argument("SeedSequence: more than " +
                                std::to_string(SeedSequence::kMaxWords) + " entropy words");
  }
  words[count++] = static_cast<std::uint32_t>(value);
  if ((value >> 32) != 0) {
    words[count++] = static_cast<std::uint32_t>(value >> 32);
  }
}

constexpr std::size_t kPool = SeedSequence::kPoolSize;

/// mix_entropy's steps for at most kPool words, which numpy pads with zeros: the same for
/// every such entropy. Lanes side by side: pool[i][lane] holds word i of entropy `lane` and
/// becomes its mixed pool word i. Each lane is one long chain of multiplications; several
/// lanes keep the CPU busy while each waits (Pcg64::forScenes).
template <std::size_t kLanes>
void mixPoolWords(std::uint32_t (&pool)[kPool][kLanes]) {
  for (std::size_t i = 0; i < kPool; ++i) {
    for (std::size_t lane = 0; lane < kLanes; ++lane) {
      pool[i][lane] = hashMixAt(pool[i][lane], i);
    }
  }
  // Every word into every other, so that late words affect early ones.
  std::size_t k = kPool;  // hashmix calls so far
  for (std::size_t source = 0; source < kPool; ++source) {
    for (std::size_t target = 0; target < kPool; ++target) {
      if (source == target) {
        continue;
      }
      for (std::size_t lane = 0; lane < kLanes; ++lane) {
        pool[target][lane] = mix(pool[target][lane], hashMixAt(pool[source][lane], k));
      }
      ++k;
    }
  }
}

/// generate_state(4, uint64) of mixed pools, lanes as in mixPoolWords(): PCG64's seed.
template <std::size_t kLanes>
void pcgSeedWords(const std::uint32_t (&pool)[kPool][kLanes], std::uint64_t (&out)[4][kLanes]) {
  for (std::size_t i = 0; i < 8; i += 2) {
    for (std::size_t lane = 0; lane < kLanes; ++lane) {
      std::uint32_t low = (pool[i % kPool][lane] ^ kHashB[i]) * kHashB[i + 1];
      std::uint32_t high = (pool[(i + 1) % kPool][lane] ^ kHashB[i + 1]) * kHashB[i + 2];
      low ^= low >> kXShift;
      high ^= high >> kXShift;
      out[i / 2][lane] = low | (std::uint64_t{high} << 32);  // little-endian pairs, as numpy
    }
  }
}

}  // namespace

SeedSequence::SeedSequence(const std::uint64_t* entropy, std::size_t entropyCount,
                           const std::uint64_t* spawnKey, std::size_t spawnKeyCount) {
  if (entropyCount == 0) {
    throw std::invalid_argument("SeedSequence: entropy must hold at least one integer");
  }
  std::uint32_t words[kMaxWords] = {};
  std::size_t count = 0;
  for (std::size_t k = 0; k < entropyCount; ++k) {
    appendWords(entropy[k], words, count);
  }
  if (spawnKeyCount > 0) {
    // numpy pads the entropy to the pool size before a spawn key (since numpy 1.19).
    count = count < kPoolSize ? kPoolSize : count;
    for (std::size_t k = 0; k < spawnKeyCount; ++k) {
      appendWords(spawnKey[k], words, count);
    }
  }
  mixEntropy(words, count);
}

SeedSequence SeedSequence::ofPair(std::uint64_t seed, std::uint64_t index) {
  std::uint32_t words[kPoolSize] = {};
  std::size_t count = 0;
  appendWords(seed, words, count);
  appendWords(index, words, count);
  SeedSequence sequence;
  sequence.mixEntropy(words, count);
  return sequence;
}

void SeedSequence::mixEntropy(const std::uint32_t* words, std::size_t count) {
  std::uint32_t pool[kPoolSize][1];
  for (std::size_t i = 0; i < kPoolSize; ++i) {
    pool[i][0] = i < count ? words[i] : 0u;
  }
  mixPoolWords(pool);
  for (std::size_t i = 0; i < kPoolSize; ++i) {
    pool_[i] = pool[i][0];
  }
  // Words beyond the pool are mixed into each pool word in turn.
  std::uint32_t hashConst = kHashA[kPoolHashes];
  for (std::size_t source = kPoolSize; source < count; ++source) {
    for (std::size_t target = 0; target < kPoolSize; ++target) {
      pool_[target] = mix(pool_[target], hashMix(words[source], hashConst));
    }
  }
}

void SeedSequence::generateState(std::uint32_t* out, std::size_t count) const {
  std::uint32_t hashConst = kInitB;
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t value = pool_[i % kPoolSize] ^ hashConst;
    hashConst *= kMultB;
    value *= hashConst;
    out[i] = value ^ (value >> kXShift);
  }
}

void SeedSequence::generateState64(std::uint64_t* out, std::size_t count) const {
  if (count == 4) {  // PCG64's seed: constants from the table, the eight words side by side
    std::uint32_t pool[kPoolSize][1];
    std::uint64_t words[4][1];
    for (std::size_t i = 0; i < kPoolSize; ++i) {
      pool[i][0] = pool_[i];
    }
    pcgSeedWords(pool, words);
    for (std::size_t i = 0; i < 4; ++i) {
      out[i] = words[i][0];
    }
    return;
  }
  std::uint32_t hashConst = kInitB;
  for (std::size_t i = 0; i < count; ++i) {
    std::uint64_t halves[2];
    for (std::size_t h = 0; h < 2; ++h) {
      std::uint32_t value = pool_[(2 * i + h) % kPoolSize] ^ hashConst;
      hashConst *= kMultB;
      value *= hashConst;
      halves[h] = value ^ (value >> kXShift);
    }
    out[i] = halves[0] | (halves[1] << 32);  // little-endian pairs, as numpy views them
  }
}

Pcg64::Pcg64(std::uint64_t seed) : Pcg64(SeedSequence(&seed, 1)) {}

Pcg64::Pcg64(const SeedSequence& sequence) { seedFrom(sequence); }

Pcg64 Pcg64::fromState(std::uint64_t stateHigh, std::uint64_t stateLow, std::uint64_t incHigh,
                       std::uint64_t incLow) {
  Pcg64 engine{Unseeded{}};
  engine.increment_ = (static_cast<Uint128>(incHigh) << 64) | incLow;
  engine.stateLow_ = stateLow;
  engine.stateHigh_ = stateHigh;
  return engine;
}

Pcg64 Pcg64::forScene(std::uint64_t seed, std::uint64_t index) {
  Pcg64 engine{Unseeded{}};
  engine.seedFrom(SeedSequence::ofPair(seed, index));
  return engine;
}

void Pcg64::forScenes(std::uint64_t seed, std::uint64_t firstIndex, std::size_t count, Pcg64* out) {
  constexpr std::size_t kLanes = 8;
  for (std::size_t done = 0; done < count; done += kLanes) {
    // [seed, index] is at most four words (SeedSequence::ofPair), zero-padded to the pool.
    std::uint32_t pool[kPool][kLanes];
    for (std::size_t lane = 0; lane < kLanes; ++lane) {
      std::uint32_t words[kPool] = {};
      std::size_t used = 0;
      appendWords(seed, words, used);
      appendWords(firstIndex + done + lane, words, used);  // past the end: computed, not used
      for (std::size_t i = 0; i < kPool; ++i) {
        pool[i][lane] = words[i];
      }
    }
    mixPoolWords(pool);
    std::uint64_t words[4][kLanes];
    pcgSeedWords(pool, words);
    for (std::size_t lane = 0; lane < kLanes && done + lane < count; ++lane) {
      out[done + lane].seed((static_cast<Uint128>(words[0][lane]) << 64) | words[1][lane],
                            (static_cast<Uint128>(words[2][lane]) << 64) | words[3][lane]);
    }
  }
}

void Pcg64::seedFrom(const SeedSequence& sequence) {
  std::uint64_t words[4];
  sequence.generateState64(words, 4);
  seed((static_cast<Uint128>(words[0]) << 64) | words[1],
       (static_cast<Uint128>(words[2]) << 64) | words[3]);
}

void Pcg64::seed(Uint128 initState, Uint128 sequence) {
  increment_ = (sequence << 1) | 1u;
  Uint128 state = increment_;  // one step from state 0
  state += initState;
  state = state * multiplier() + increment_;
  stateLow_ = static_cast<std::uint64_t>(state);
  stateHigh_ = static_cast<std::uint64_t>(state >> 64);
}

std::array<std::uint64_t, 4> Pcg64::stateWords() const {
  return {stateHigh_, stateLow_, static_cast<std::uint64_t>(increment_ >> 64),
          static_cast<std::uint64_t>(increment_)};
}

}  // namespace placement_samplers
