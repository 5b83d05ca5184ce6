#include "placement_samplers/process/malloc_tuning.hpp"

#include <cstdlib>  // defines __GLIBC__ where it applies

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace placement_samplers {

namespace {
constexpr int kTrimThreshold = 32 << 20;  // [bytes] free memory kept at the top of a heap
constexpr int kMallocArenas = 4;          // kept memory: at most kTrimThreshold in each
static_assert(std::size_t{kTrimThreshold} * kMallocArenas <= kKeptFreeBytes,
              "the settings must keep the documented bound");
}  // namespace

bool keepFreedMemoryForBatches() {
#if defined(__GLIBC__)
  constexpr int kMmapThreshold = 32 << 20;  // [bytes] glibc's largest allowed value
  return mallopt(M_TRIM_THRESHOLD, kTrimThreshold) == 1 &&
         mallopt(M_MMAP_THRESHOLD, kMmapThreshold) == 1 && mallopt(M_ARENA_MAX, kMallocArenas) == 1;
#else
  return false;
#endif
}

bool trimAfterBatch(std::uint64_t placements) {
#if defined(__GLIBC__)
  if (placements < kTrimAfterPlacements) {
    return false;
  }
  malloc_trim(kTrimThreshold);
  return true;
#else
  (void)placements;
  return false;
#endif
}

bool trimAfterInput(std::size_t bytes) {
  return bytes >= kTrimAfterInputBytes && trimAfterBatch(kTrimAfterPlacements);
}

}  // namespace placement_samplers
