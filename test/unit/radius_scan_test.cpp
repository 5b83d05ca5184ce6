// The vectorised scans behind RadiusChecker must answer as the scalar test, bit for bit: the
// same lowest overlapping index for every entry count (blocks of 4 and 8, groups of 64, the
// masked tail) and for touching, NaN, infinite and huge values.

#include "radius_scan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <vector>

namespace placement_samplers {
namespace detail {
namespace {

/// robosuite's scan of every entry in order, with the one definition of the test.
std::size_t reference(const std::vector<std::vector<double>>& e, const RadiusProbe& p) {
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (radiusOverlap(p, e[i][0], e[i][1], e[i][2], e[i][3], e[i][4])) {
      return i;
    }
  }
  return e.size();
}

std::vector<ScanKernel> availableKernels() {
  std::vector<ScanKernel> kernels;
  for (const ScanKernel k : {ScanKernel::Scalar, ScanKernel::Avx2, ScanKernel::Avx512}) {
    if (scanKernel(k) != nullptr) {
      kernels.push_back(k);
    }
  }
  return kernels;
}

TEST(RadiusScan, ScalarIsAlwaysThereAndTheBestKernelRuns) {
  EXPECT_NE(scanKernel(ScanKernel::Scalar), nullptr);
  EXPECT_NE(scanKernel(bestScanKernel()), nullptr);
}

TEST(RadiusScan, EveryKernelGivesTheLowestIndexOfTheScalarTest) {
  std::mt19937_64 engine(2024);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double odd[] = {nan, inf, -inf, 1e200, -0.0, 0.0};
  const auto kernels = availableKernels();
  RadiusColumns columns;
  std::vector<std::vector<double>> entries;
  std::size_t checked = 0;
  std::size_t hits = 0;
  for (int world = 0; world < 400; ++world) {
    const std::size_t n = static_cast<std::size_t>(world % 140);  // 0 .. 139: tails, 2 groups
    columns.clear();  // keeps the old values past size(): they must stay masked off
    entries.clear();
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<double> e = {unit(engine) * 0.6 - 0.3, unit(engine) * 0.6 - 0.3,
                               unit(engine) * 0.2, 0.01 + unit(engine) * 0.05, unit(engine) * 0.1};
      if (unit(engine) < 0.05) {
        e[static_cast<std::size_t>(unit(engine) * 5.0)] =
            odd[static_cast<std::size_t>(unit(engine) * 6.0)];
      }
      entries.push_back(e);
      columns.push(e[0], e[1], e[2], e[3], e[4]);
    }
    for (int q = 0; q < 200; ++q) {
      RadiusProbe p{unit(engine) * 0.6 - 0.3, unit(engine) * 0.6 - 0.3, unit(engine) * 0.2,
                    0.03 * unit(engine), -0.05 * unit(engine)};
      if (n > 0 && q % 10 == 0) {
        // Exactly touching entry k (dyadic values: no rounding): touching counts.
        const std::size_t k = static_cast<std::size_t>(unit(engine) * static_cast<double>(n));
        entries[k] = {0.25, 0.125, 0.0, 0.0625, 0.5};
        columns = RadiusColumns();
        for (const auto& e : entries) {
          columns.push(e[0], e[1], e[2], e[3], e[4]);
        }
        p = RadiusProbe{0.25 + 0.125, 0.125, 0.0, 0.0625, 0.0};
      }
      if (q % 37 == 0) {
        p.x = odd[static_cast<std::size_t>(q) % 6];
      }
      const std::size_t expected = reference(entries, p);
      hits += expected < n ? 1 : 0;
      for (const ScanKernel k : kernels) {
        ASSERT_EQ(scanKernel(k)(columns, p), expected)
            << "kernel " << static_cast<int>(k) << ", " << n << " entries, probe " << q;
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 80000u);
  EXPECT_GT(hits, 10000u);  // both outcomes are exercised
  EXPECT_LT(hits, checked - 10000);
}

}  // namespace
}  // namespace detail
}  // namespace placement_samplers
