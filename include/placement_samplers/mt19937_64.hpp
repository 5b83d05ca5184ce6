#pragma once

#include <cstddef>
#include <cstdint>

namespace placement_samplers {

/// MT19937-64 (Matsumoto and Nishimura): the same numbers as std::mt19937_64 for every seed,
/// but cheap to seed when a few numbers are drawn.
///
/// Why: every scene seeds its own engine, and std::mt19937_64 pays 312 serial seeding steps in
/// seed() and a regeneration of all 312 state words at the first draw (about 1.7 us), while a
/// scene draws a handful of numbers. Here seed() only stores the seed; the first 156 outputs are
/// made four at a time (new word k needs old words k, k + 1 and k + 156 only, so the serial seed
/// chain is extended just as far as the draws need it), and the rest of the first regeneration
/// is done when output 156 is asked for. After that it is a plain MT19937-64 with a branch-free
/// regeneration. test/unit/mt19937_64_test.cpp compares it with std::mt19937_64.
///
/// Satisfies UniformRandomBitGenerator. No heap allocation; trivially copyable.
class Mt19937_64 {
 public:
  using result_type = std::uint64_t;

  static constexpr std::size_t kStateSize = 312;      ///< n
  static constexpr std::size_t kShiftSize = 156;      ///< m
  static constexpr result_type kDefaultSeed = 5489u;  ///< std::mt19937_64::default_seed

  /// Seeded with kDefaultSeed, as a default-constructed std::mt19937_64.
  Mt19937_64() { seed(kDefaultSeed); }

  /// Seeded with @p value, as std::mt19937_64(value).
  explicit Mt19937_64(result_type value) { seed(value); }

  /// Restarts the sequence of seed @p value (any 64-bit value). Constant time: the state is
  /// computed on demand by the draws that follow.
  void seed(result_type value) {
    state_[0] = value;
    seeded_ = 1;
    index_ = 0;
    ready_ = 0;
  }

  /// Seeds @p count engines at once, as engines[i]->seed(seeds[i]) would, and computes the
  /// part of each seed chain that the first draws need (at least kManySeedDepth words). Why:
  /// the chain is serial, about 1.6 ns a word, but independent chains run side by side on one
  /// core: eight at a time in scalar code, sixteen in two AVX-512 vectors where the CPU has
  /// them (docs/benchmarks.md).
  static void seedMany(Mt19937_64* const* engines, const result_type* seeds, std::size_t count);

  /// Words of the seed chain seedMany() computes at least: enough for the first four draws.
  static constexpr std::size_t kManySeedDepth = kShiftSize + 4;

  /// The next number of the sequence.
  result_type operator()() {
    if (index_ >= ready_) {
      prepareNext();
    }
    return temper(state_[index_++]);
  }

  /// Skips @p count numbers, as that many calls of operator()() would.
  void discard(unsigned long long count);

  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return ~result_type{0}; }

 private:
  static result_type temper(result_type x) {
    x ^= (x >> 29) & 0x5555555555555555ULL;
    x ^= (x << 17) & 0x71D67FFFEDA60000ULL;
    x ^= (x << 37) & 0xFFF7EEE000000000ULL;
    return x ^ (x >> 43);
  }

  /// Makes state_[index_] a new (regenerated) word, ready_ > index_. Out of line: rare, or at
  /// most once per draw for the first 156 draws after a seed.
  void prepareNext();

  /// Extends the seed chain up to and including word @p last.
  void extendSeed(std::size_t last);

  result_type state_[kStateSize] = {};  // zeroed once here, never by seed()
  std::size_t seeded_ = 0;              ///< words 0 .. seeded_ - 1 of the seed chain are computed
  std::size_t index_ = 0;               ///< next word to output
  std::size_t ready_ = 0;               ///< words 0 .. ready_ - 1 are regenerated (can be output)
};

}  // namespace placement_samplers
