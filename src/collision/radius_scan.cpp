#include "collision/radius_scan.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define PLACEMENT_SAMPLERS_X86 1
#endif

// Every kernel evaluates, per entry and in this order, the operations of radiusOverlap()
// (radius_test.hpp, the one definition of robosuite's test):
//   (dx * dx + dy * dy <= reach * reach) & (p.z - z <= top - p.bottom)
// with dx = p.x - x, dy = p.y - y, reach = radius + p.radius, so that all kernels give the same
// answer bit for bit (radius_scan_test.cpp compares them with radiusOverlap()). The library is
// compiled with -ffp-contract=off, so no kernel fuses a multiply and an add.

namespace placement_samplers {
namespace detail {

void RadiusColumns::push(double x, double y, double z, double radius, double top) {
  if (size_ == x_.size()) {
    const std::size_t grown = size_ + 8;
    for (CacheLineVector<double>* column : {&x_, &y_, &z_, &radius_, &top_}) {
      column->resize(grown, std::numeric_limits<double>::quiet_NaN());
    }
  }
  x_[size_] = x;
  y_[size_] = y;
  z_[size_] = z;
  radius_[size_] = radius;
  top_[size_] = top;
  ++size_;
}

namespace {

#ifdef PLACEMENT_SAMPLERS_X86

/// Entries are compared 64 at a time without a branch on the outcome: where the first hit
/// falls is random, and a mispredicted early exit cost more than comparing the rest.
constexpr std::size_t kGroup = 64;

/// Bits 0 .. count - 1.
inline std::uint64_t lowBits(std::size_t count) {
  return count >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << count) - 1;
}

__attribute__((target("avx2"))) std::size_t firstOverlapAvx2(const RadiusColumns& c,
                                                             const RadiusProbe& p) {
  const std::size_t n = c.size();
  const __m256d px = _mm256_set1_pd(p.x);
  const __m256d py = _mm256_set1_pd(p.y);
  const __m256d pz = _mm256_set1_pd(p.z);
  const __m256d pr = _mm256_set1_pd(p.radius);
  const __m256d pb = _mm256_set1_pd(p.bottom);
  for (std::size_t start = 0; start < n; start += kGroup) {
    const std::size_t end = std::min(n, start + kGroup);
    std::uint64_t hits = 0;
    for (std::size_t i = start; i < end; i += 4) {
      const __m256d dx = _mm256_sub_pd(px, _mm256_loadu_pd(c.x() + i));
      const __m256d dy = _mm256_sub_pd(py, _mm256_loadu_pd(c.y() + i));
      const __m256d reach = _mm256_add_pd(_mm256_loadu_pd(c.radius() + i), pr);
      const __m256d d2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
      const __m256d near = _mm256_cmp_pd(d2, _mm256_mul_pd(reach, reach), _CMP_LE_OQ);
      const __m256d dz = _mm256_sub_pd(pz, _mm256_loadu_pd(c.z() + i));
      const __m256d limit = _mm256_sub_pd(_mm256_loadu_pd(c.top() + i), pb);
      const __m256d below = _mm256_cmp_pd(dz, limit, _CMP_LE_OQ);
      const auto lanes = static_cast<std::uint64_t>(_mm256_movemask_pd(_mm256_and_pd(near, below)));
      hits |= lanes << (i - start);
    }
    hits &= lowBits(end - start);
    if (hits != 0) {
      return start + static_cast<std::size_t>(__builtin_ctzll(hits));
    }
  }
  return n;
}

__attribute__((target("avx512f"))) std::size_t firstOverlapAvx512(const RadiusColumns& c,
                                                                  const RadiusProbe& p) {
  const std::size_t n = c.size();
  const __m512d px = _mm512_set1_pd(p.x);
  const __m512d py = _mm512_set1_pd(p.y);
  const __m512d pz = _mm512_set1_pd(p.z);
  const __m512d pr = _mm512_set1_pd(p.radius);
  const __m512d pb = _mm512_set1_pd(p.bottom);
  for (std::size_t start = 0; start < n; start += kGroup) {
    const std::size_t end = std::min(n, start + kGroup);
    std::uint64_t hits = 0;
    for (std::size_t i = start; i < end; i += 8) {
      const __m512d dx = _mm512_sub_pd(px, _mm512_loadu_pd(c.x() + i));
      const __m512d dy = _mm512_sub_pd(py, _mm512_loadu_pd(c.y() + i));
      const __m512d reach = _mm512_add_pd(_mm512_loadu_pd(c.radius() + i), pr);
      const __m512d d2 = _mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy));
      const __mmask8 near = _mm512_cmp_pd_mask(d2, _mm512_mul_pd(reach, reach), _CMP_LE_OQ);
      const __m512d dz = _mm512_sub_pd(pz, _mm512_loadu_pd(c.z() + i));
      const __m512d limit = _mm512_sub_pd(_mm512_loadu_pd(c.top() + i), pb);
      const __mmask8 both = _mm512_mask_cmp_pd_mask(near, dz, limit, _CMP_LE_OQ);
      hits |= static_cast<std::uint64_t>(both) << (i - start);
    }
    hits &= lowBits(end - start);
    if (hits != 0) {
      return start + static_cast<std::size_t>(__builtin_ctzll(hits));
    }
  }
  return n;
}

#endif  // PLACEMENT_SAMPLERS_X86

}  // namespace

namespace {

ScanKernel detectScanKernel() {
  // For comparisons (docs/benchmarks.md): PLACEMENT_SAMPLERS_SCAN=scalar|avx2 picks a narrower
  // kernel than the CPU allows.
  const char* forced = std::getenv("PLACEMENT_SAMPLERS_SCAN");
  const std::string choice = forced != nullptr ? forced : "";
  if (choice == "scalar") {
    return ScanKernel::Scalar;
  }
  if (choice == "avx2" && scanKernel(ScanKernel::Avx2) != nullptr) {
    return ScanKernel::Avx2;
  }
  // libgcc's check includes the operating system saving the wider registers.
  for (const ScanKernel k : {ScanKernel::Avx512, ScanKernel::Avx2}) {
    if (scanKernel(k) != nullptr) {
      return k;
    }
  }
  return ScanKernel::Scalar;
}

}  // namespace

ScanKernel bestScanKernel() {
  static const ScanKernel best = detectScanKernel();
  return best;
}

FirstOverlapFn scanKernel(ScanKernel kernel) {
  switch (kernel) {
    case ScanKernel::Scalar:
      return &firstOverlapInline;
#ifdef PLACEMENT_SAMPLERS_X86
    case ScanKernel::Avx2:
      return __builtin_cpu_supports("avx2") ? &firstOverlapAvx2 : nullptr;
    case ScanKernel::Avx512:
      return __builtin_cpu_supports("avx512f") ? &firstOverlapAvx512 : nullptr;
#else
    default:
      return nullptr;
#endif
  }
  return nullptr;
}

}  // namespace detail
}  // namespace placement_samplers
