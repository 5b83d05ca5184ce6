#pragma once

// Internal to the core library: the packed scan behind RadiusChecker, vectorised where the CPU
// allows. Not installed.

#include <cstddef>
#include <vector>

#include "collision/radius_test.hpp"
#include "sampling/cache_line.hpp"

namespace placement_samplers {
namespace detail {

/// What robosuite's test reads of each entry, one column per value, in entry order. The
/// columns are sized to whole blocks of 8 so that a kernel may load past size(); lanes past
/// size() are masked off, never compared.
class alignas(kCacheLine) RadiusColumns {
 public:
  void clear() { size_ = 0; }
  /// Appends an entry: position [m], horizontal radius [m], top offset z [m].
  void push(double x, double y, double z, double radius, double top);
  std::size_t size() const { return size_; }

  const double* x() const { return x_.data(); }
  const double* y() const { return y_.data(); }
  const double* z() const { return z_.data(); }
  const double* radius() const { return radius_.data(); }
  const double* top() const { return top_.data(); }

 private:
  std::size_t size_ = 0;
  CacheLineVector<double> x_, y_, z_, radius_, top_;
};

/// The scalar kernel, inline: the lowest index whose entry overlaps @p p under
/// radiusOverlap() (radius_test.hpp), or columns.size().
inline std::size_t firstOverlapInline(const RadiusColumns& c, const RadiusProbe& p) {
  const std::size_t n = c.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (radiusOverlap(p, c.x()[i], c.y()[i], c.z()[i], c.radius()[i], c.top()[i])) {
      return i;
    }
  }
  return n;
}

/// The lowest index whose entry overlaps @p p under robosuite's test, or columns.size().
using FirstOverlapFn = std::size_t (*)(const RadiusColumns& columns, const RadiusProbe& p);

/// Instruction sets a kernel can use.
enum class ScanKernel { Scalar, Avx2, Avx512 };

/// The widest kernel this CPU runs (checked once).
ScanKernel bestScanKernel();
/// The kernel @p kernel, or nullptr when this build or CPU has none.
FirstOverlapFn scanKernel(ScanKernel kernel);

}  // namespace detail
}  // namespace placement_samplers
