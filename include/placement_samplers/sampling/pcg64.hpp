#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace placement_samplers {

/// numpy's SeedSequence (numpy/random/bit_generator.pyx) with its default pool of four 32-bit
/// words: the same pool and the same generated state for the same entropy, so that
/// `numpy.random.default_rng([S, i])` and Pcg64::forScene(S, i) give the same numbers.
///
/// Entropy is a list of 32-bit words, as numpy assembles it: each non-negative integer split
/// into 32-bit words, lowest first (0 is one word, a value below 2^32 one word, a larger
/// 64-bit value two), the integers concatenated; then the spawn key the same way, after
/// padding the entropy with zero words to the pool size when a spawn key is given.
class SeedSequence {
 public:
  static constexpr std::size_t kPoolSize = 4;
  /// At most this many entropy words (two 64-bit integers, a spawn key of two).
  static constexpr std::size_t kMaxWords = 12;

  /// SeedSequence(entropy, spawn_key=spawnKey) of numpy for the integers @p entropy
  /// (@p entropyCount of them, at least one) and @p spawnKey (@p spawnKeyCount).
  /// @throw std::invalid_argument when there is no entropy or more than kMaxWords words
  SeedSequence(const std::uint64_t* entropy, std::size_t entropyCount,
               const std::uint64_t* spawnKey = nullptr, std::size_t spawnKeyCount = 0);

  /// numpy's SeedSequence([seed, index]): what default_rng([seed, index]) uses.
  static SeedSequence ofPair(std::uint64_t seed, std::uint64_t index);

  /// generate_state(count, uint32): @p count words into @p out.
  void generateState(std::uint32_t* out, std::size_t count) const;
  /// generate_state(count, uint64): 2 * count 32-bit words, paired little-endian.
  void generateState64(std::uint64_t* out, std::size_t count) const;

  /// The mixed entropy pool (numpy's `pool` attribute).
  const std::array<std::uint32_t, kPoolSize>& pool() const { return pool_; }

 private:
  SeedSequence() = default;
  /// Mixes @p count words into pool_ (numpy's mix_entropy).
  void mixEntropy(const std::uint32_t* words, std::size_t count);

  std::array<std::uint32_t, kPoolSize> pool_{};
};

/// numpy's PCG64 bit generator (PCG XSL RR 128/64: a 128-bit LCG, output the xor of its halves
/// rotated by the top six bits), seeded as numpy seeds it from a SeedSequence: four 64-bit
/// words of generate_state, the first two the initial state, the last two the stream.
///
/// Satisfies UniformRandomBitGenerator. Trivially copyable, 32 bytes, no heap.
class Pcg64 {
 public:
  using result_type = std::uint64_t;

  /// numpy's PCG64(SeedSequence(0)), i.e. default_rng(0).
  Pcg64() : Pcg64(std::uint64_t{0}) {}
  /// numpy's default_rng(@p seed) for one integer seed.
  explicit Pcg64(std::uint64_t seed);
  /// numpy's PCG64(@p sequence).
  explicit Pcg64(const SeedSequence& sequence);

  /// numpy's PCG64 whose `bit_generator.state` is {'state': {'state': S, 'inc': I}}, S and I
  /// given as 64-bit halves: the stream continues where numpy's would. @p inc is taken as it
  /// is (numpy keeps an even one too). The inverse of stateWords().
  static Pcg64 fromState(std::uint64_t stateHigh, std::uint64_t stateLow, std::uint64_t incHigh,
                         std::uint64_t incLow);

  /// numpy's default_rng([seed, index]): the stream of scene @p index of request seed @p seed.
  static Pcg64 forScene(std::uint64_t seed, std::uint64_t index);
  /// forScene(seed, firstIndex + k) into out[k] for k < @p count: the engines of consecutive
  /// scenes, seeded side by side. Seeding one is a long chain of dependent multiplications
  /// (SeedSequence); several together keep the CPU busy while each waits.
  static void forScenes(std::uint64_t seed, std::uint64_t firstIndex, std::size_t count,
                        Pcg64* out);

  /// The next 64-bit output (numpy's next_uint64, random_raw()).
  result_type operator()() {
    const Uint128 state = this->state() * multiplier() + increment_;
    const auto high = static_cast<std::uint64_t>(state >> 64);
    const auto low = static_cast<std::uint64_t>(state);
    stateLow_ = low;
    stateHigh_ = high;
    const unsigned rotation = static_cast<unsigned>(high >> 58);
    const std::uint64_t x = high ^ low;
    return (x >> rotation) | (x << ((64u - rotation) & 63u));
  }

  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return ~result_type{0}; }

  /// State as numpy's PCG64.state shows it: {state high, state low, inc high, inc low}.
  std::array<std::uint64_t, 4> stateWords() const;

 private:
  __extension__ using Uint128 = unsigned __int128;
  struct Unseeded {};
  explicit Pcg64(Unseeded) {}

  static constexpr Uint128 multiplier() {
    return (static_cast<Uint128>(0x2360ED051FC65DA4ULL) << 64) | 0x4385DF649FCCF645ULL;
  }
  /// pcg_setseq_128_srandom_r: stream from @p sequence, then two steps around adding the state.
  void seed(Uint128 initState, Uint128 sequence);
  void seedFrom(const SeedSequence& sequence);
  Uint128 state() const { return (static_cast<Uint128>(stateHigh_) << 64) | stateLow_; }

  Uint128 increment_ = 1;
  // The state in two words, not one Uint128: g++ stores an aligned Uint128 member by way of a
  // stack slot and a 16-byte load, which waits for the two 8-byte stores before it (a failed
  // store forwarding, half of a clutter scene's placeOne in perf).
  std::uint64_t stateLow_ = 0;
  std::uint64_t stateHigh_ = 0;
};

}  // namespace placement_samplers
