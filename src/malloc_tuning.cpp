#include "placement_samplers/malloc_tuning.hpp"

#include <cstdlib>  // defines __GLIBC__ where it applies

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace placement_samplers {

bool keepFreedMemoryForBatches() {
#if defined(__GLIBC__)
  constexpr int kTrimThreshold = 128 << 20;  // [bytes] free memory kept at the top of a heap
  constexpr int kMmapThreshold = 32 << 20;   // [bytes] glibc's largest allowed value
  return mallopt(M_TRIM_THRESHOLD, kTrimThreshold) == 1 &&
         mallopt(M_MMAP_THRESHOLD, kMmapThreshold) == 1;
#else
  return false;
#endif
}

}  // namespace placement_samplers
