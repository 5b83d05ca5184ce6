#include "placement_samplers/mt19937_64.hpp"

#include <algorithm>

#if defined(__x86_64__) && defined(__GNUC__)
// GCC 12 warns about its own AVX-512 headers (_mm512_undefined_epi32, GCC bug 105593).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#define PLACEMENT_SAMPLERS_X86 1
#endif

namespace placement_samplers {
namespace {

constexpr std::size_t kN = Mt19937_64::kStateSize;
constexpr std::size_t kM = Mt19937_64::kShiftSize;
constexpr std::size_t kHalf = kN - kM;  // words 0 .. kHalf - 1 need only old words
constexpr std::uint64_t kMatrixA = 0xB5026F5AA96619E9ULL;
constexpr std::uint64_t kUpperMask = ~std::uint64_t{0} << 31;  // r = 31
constexpr std::uint64_t kLowerMask = ~kUpperMask;
constexpr std::uint64_t kSeedMultiplier = 6364136223846793005ULL;
/// Words regenerated per call in the first block after a seed.
constexpr std::size_t kLazyStep = 4;

/// The new value of a word from the word itself, the next one and the one m ahead (mod n).
/// Branch-free: libstdc++'s (y & 1) ? a : 0 becomes a jump that mispredicts half the time.
inline std::uint64_t twistWord(std::uint64_t word, std::uint64_t next, std::uint64_t far) {
  const std::uint64_t y = (word & kUpperMask) | (next & kLowerMask);
  return far ^ (y >> 1) ^ ((std::uint64_t{0} - (y & 1)) & kMatrixA);
}

/// Words kHalf .. kN - 1 of a regeneration whose words 0 .. kHalf - 1 are done: they read the
/// NEW words 0 .. kM - 1 (the last one the new word 0).
void twistTail(std::uint64_t* state) {
  for (std::size_t k = kHalf; k < kN - 1; ++k) {
    state[k] = twistWord(state[k], state[k + 1], state[k - kHalf]);
  }
  state[kN - 1] = twistWord(state[kN - 1], state[0], state[kM - 1]);
}

#ifdef PLACEMENT_SAMPLERS_X86

/// Engines seedChainsAvx512() seeds at once: two vectors of 8 chains, so that each one's
/// multiply latency is filled by the other.
constexpr std::size_t kWide = 16;
/// Seed chain words it computes: 0 .. 160, twenty blocks of 8 steps (kManySeedDepth and one).
constexpr std::size_t kWideDepth = 1 + 8 * 20;

bool haveAvx512dq() {
  static const bool have = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq");
  return have;
}

/// Transposes the 8 x 8 block r[step][lane] in place: r[lane][step] afterwards.
__attribute__((target("avx512f"))) inline void transpose8x8(__m512i* r) {
  __m512i t[8];
  for (int i = 0; i < 8; i += 2) {
    t[i] = _mm512_unpacklo_epi64(r[i], r[i + 1]);      // lanes 0 2 4 6 of rows i, i + 1
    t[i + 1] = _mm512_unpackhi_epi64(r[i], r[i + 1]);  // lanes 1 3 5 7
  }
  const __m512i lowPairs = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13);
  const __m512i highPairs = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
  __m512i u[8];
  for (int i = 0; i < 8; i += 4) {
    u[i] = _mm512_permutex2var_epi64(t[i], lowPairs, t[i + 2]);           // lanes 0, 4
    u[i + 1] = _mm512_permutex2var_epi64(t[i + 1], lowPairs, t[i + 3]);   // lanes 1, 5
    u[i + 2] = _mm512_permutex2var_epi64(t[i], highPairs, t[i + 2]);      // lanes 2, 6
    u[i + 3] = _mm512_permutex2var_epi64(t[i + 1], highPairs, t[i + 3]);  // lanes 3, 7
  }
  const __m512i lowHalves = _mm512_setr_epi64(0, 1, 2, 3, 8, 9, 10, 11);
  const __m512i highHalves = _mm512_setr_epi64(4, 5, 6, 7, 12, 13, 14, 15);
  for (int lane = 0; lane < 4; ++lane) {
    r[lane] = _mm512_permutex2var_epi64(u[lane], lowHalves, u[lane + 4]);
    r[lane + 4] = _mm512_permutex2var_epi64(u[lane], highHalves, u[lane + 4]);
  }
}

/// Words 1 .. kWideDepth - 1 of the seed chains of @p seeds[0 .. 15] into states[e][1 ..]:
/// the scalar chain, 8 lanes per vector, written 8 words at a time after a transpose.
__attribute__((target("avx512f,avx512dq"))) void seedChainsAvx512(std::uint64_t* const* states,
                                                                  const std::uint64_t* seeds) {
  __m512i chain[2] = {_mm512_loadu_si512(seeds), _mm512_loadu_si512(seeds + 8)};
  const __m512i multiplier = _mm512_set1_epi64(static_cast<long long>(kSeedMultiplier));
  for (std::size_t j0 = 1; j0 < kWideDepth; j0 += 8) {
    __m512i rows[2][8];
    for (std::size_t step = 0; step < 8; ++step) {
      const __m512i index = _mm512_set1_epi64(static_cast<long long>(j0 + step));
      for (int g = 0; g < 2; ++g) {
        const __m512i mixed = _mm512_xor_si512(chain[g], _mm512_srli_epi64(chain[g], 62));
        chain[g] = _mm512_add_epi64(_mm512_mullo_epi64(mixed, multiplier), index);
        rows[g][step] = chain[g];
      }
    }
    for (int g = 0; g < 2; ++g) {
      transpose8x8(rows[g]);
      for (int lane = 0; lane < 8; ++lane) {
        _mm512_storeu_si512(states[8 * g + lane] + j0, rows[g][lane]);
      }
    }
  }
}

#endif  // PLACEMENT_SAMPLERS_X86

}  // namespace

void Mt19937_64::extendSeed(std::size_t last) {
  // Serial: word j needs word j - 1. Words past index_ + kM are never overwritten before this
  // reads them (the lazy regeneration only writes words below kHalf).
  for (std::size_t j = seeded_; j <= last; ++j) {
    const std::uint64_t previous = state_[j - 1];
    state_[j] = kSeedMultiplier * (previous ^ (previous >> 62)) + j;
  }
  if (seeded_ <= last) {
    seeded_ = last + 1;
  }
}

void Mt19937_64::seedMany(Mt19937_64* const* engines, const result_type* seeds, std::size_t count) {
  std::size_t first = 0;
#ifdef PLACEMENT_SAMPLERS_X86
  if (haveAvx512dq()) {
    for (; first + kWide <= count; first += kWide) {
      std::uint64_t* states[kWide];
      for (std::size_t e = 0; e < kWide; ++e) {
        engines[first + e]->seed(seeds[first + e]);
        states[e] = engines[first + e]->state_;
      }
      seedChainsAvx512(states, seeds + first);
      for (std::size_t e = 0; e < kWide; ++e) {
        engines[first + e]->seeded_ = kWideDepth;
      }
    }
  }
#endif
  // Lockstep over groups of up to 8 engines: each step of one chain waits for its previous
  // word (multiply latency), so the steps of the other chains fill the gaps.
  constexpr std::size_t kGroup = 8;
  for (; first < count; first += kGroup) {
    const std::size_t n = std::min(kGroup, count - first);
    std::uint64_t word[kGroup] = {};
    for (std::size_t e = 0; e < n; ++e) {
      Mt19937_64& engine = *engines[first + e];
      engine.seed(seeds[first + e]);
      word[e] = seeds[first + e];
    }
    for (std::size_t j = 1; j < kManySeedDepth; ++j) {
      for (std::size_t e = 0; e < kGroup; ++e) {  // a fixed count: the compiler unrolls it
        word[e] = kSeedMultiplier * (word[e] ^ (word[e] >> 62)) + j;
      }
      for (std::size_t e = 0; e < n; ++e) {
        engines[first + e]->state_[j] = word[e];
      }
    }
    for (std::size_t e = 0; e < n; ++e) {
      engines[first + e]->seeded_ = kManySeedDepth;
    }
  }
}

void Mt19937_64::prepareNext() {
  if (index_ >= kN) {
    // A whole block was output: a full regeneration, as any MT.
    for (std::size_t k = 0; k < kHalf; ++k) {
      state_[k] = twistWord(state_[k], state_[k + 1], state_[k + kM]);
    }
    twistTail(state_);
    index_ = 0;
    ready_ = kN;
  } else if (index_ < kHalf) {
    // First block after seed(): new word k from old words k, k + 1 and k + kM, which the seed
    // chain must reach first. Four words at a time: one call per four draws, and a scene
    // drawing three numbers (Lift) still extends the chain only as far as it needs.
    const std::size_t end = std::min(index_ + kLazyStep, kHalf);
    extendSeed(end - 1 + kM);
    for (std::size_t k = index_; k < end; ++k) {
      state_[k] = twistWord(state_[k], state_[k + 1], state_[k + kM]);
    }
    ready_ = end;
  } else {
    // index_ == kHalf in the first block: the chain is complete (word kHalf - 1 needed word
    // kN - 1); finish the regeneration.
    extendSeed(kN - 1);
    twistTail(state_);
    ready_ = kN;
  }
}

void Mt19937_64::discard(unsigned long long count) {
  while (count > 0) {
    if (index_ >= ready_) {
      prepareNext();
    }
    const std::size_t available = ready_ - index_;
    const std::size_t skip = count < available ? static_cast<std::size_t>(count) : available;
    index_ += skip;
    count -= skip;
  }
}

}  // namespace placement_samplers
