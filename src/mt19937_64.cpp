#include "placement_samplers/mt19937_64.hpp"

#include <algorithm>

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
  // Lockstep over groups of up to 8 engines: each step of one chain waits for its previous
  // word (multiply latency), so the steps of the other chains fill the gaps.
  constexpr std::size_t kGroup = 8;
  for (std::size_t first = 0; first < count; first += kGroup) {
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
