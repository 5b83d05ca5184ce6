// The vectorised scans behind RadiusChecker must answer as the scalar test, bit for bit: the
// same lowest overlapping index for every entry count (blocks of 4 and 8, groups of 64, the
// masked tail) and for touching, NaN, infinite and huge values.

#include "collision/radius_scan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <string>
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

const char* kernelName(ScanKernel kernel) {
  switch (kernel) {
    case ScanKernel::Scalar:
      return "scalar";
    case ScanKernel::Avx2:
      return "AVX2";
    case ScanKernel::Avx512:
      return "AVX-512";
  }
  return "unknown";
}

TEST(RadiusScan, ScalarIsAlwaysThereAndTheBestKernelRuns) {
  EXPECT_NE(scanKernel(ScanKernel::Scalar), nullptr);
  EXPECT_NE(scanKernel(bestScanKernel()), nullptr);
}

class EveryKernel : public ::testing::TestWithParam<ScanKernel> {};

TEST_P(EveryKernel, GivesTheLowestIndexOfTheScalarTest) {
  const FirstOverlapFn kernel = scanKernel(GetParam());
  if (kernel == nullptr) {
    GTEST_SKIP() << "no " << kernelName(GetParam()) << " kernel in this build or on this CPU";
  }
  std::mt19937_64 engine(2024);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double odd[] = {nan, inf, -inf, 1e200, -0.0, 0.0};
  RadiusColumns columns;
  std::vector<std::vector<double>> entries;
  std::size_t checked = 0;
  std::size_t hits = 0;
  std::size_t touching = 0;
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
      std::size_t touched = n;  // the entry the probe touches exactly, if any
      if (n > 0 && q % 10 == 0) {
        // Exactly touching entry k (dyadic values: no rounding): touching counts.
        touched = static_cast<std::size_t>(unit(engine) * static_cast<double>(n));
        entries[touched] = {0.25, 0.125, 0.0, 0.0625, 0.5};
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
      if (touched < n && q % 37 != 0) {
        ASSERT_LE(expected, touched) << "touching counts as overlapping";
        ++touching;
      }
      hits += expected < n ? 1 : 0;
      ASSERT_EQ(kernel(columns, p), expected) << n << " entries, probe " << q;
      ++checked;
    }
  }
  EXPECT_GT(touching, 7000u);  // about one probe in ten touches an entry exactly
  EXPECT_GT(hits, 10000u);     // both outcomes are exercised
  EXPECT_LT(hits, checked - 10000);
}

INSTANTIATE_TEST_SUITE_P(RadiusScan, EveryKernel,
                         ::testing::Values(ScanKernel::Scalar, ScanKernel::Avx2,
                                           ScanKernel::Avx512),
                         [](const ::testing::TestParamInfo<ScanKernel>& info) {
                           return std::string(info.param == ScanKernel::Scalar ? "Scalar"
                                              : info.param == ScanKernel::Avx2 ? "Avx2"
                                                                               : "Avx512");
                         });

}  // namespace
}  // namespace detail
}  // namespace placement_samplers
