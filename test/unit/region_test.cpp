// Region shapes: uniform draws over each shape (statistical, fixed seeds), insets, the shapes'
// own tests, and the shapes a configuration refuses.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "placement_samplers/sampling/region.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::expectUniform;
using V = Eigen::Vector2d;

constexpr int kDraws = 40000;

/// The chi-square statistic's value that a fit exceeds with probability 1e-4, for @p dof
/// degrees of freedom (Wilson-Hilferty; within 1% for dof >= 3).
double chiSquareCritical(int dof) {
  const double k = dof;
  const double z = 3.719;  // the standard normal's 1 - 1e-4 quantile
  const double t = 1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k));
  return k * t * t * t;
}

/// Pearson's statistic of @p counts against @p expected (same total).
double chiSquare(const std::vector<double>& counts, const std::vector<double>& expected) {
  double sum = 0.0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    sum += (counts[i] - expected[i]) * (counts[i] - expected[i]) / expected[i];
  }
  return sum;
}

std::vector<V> drawMany(const RegionDraw& draw, std::uint64_t seed, int n = kDraws) {
  Engine engine = sceneEngine(seed, 0);
  std::vector<V> out;
  while (static_cast<int>(out.size()) < n) {
    const V p = draw.draw(engine);
    if (draw.accepts(p)) {
      out.push_back(p);
    }
  }
  return out;
}

/// Equal-area cells of a disk or annulus: squared radius in 4 bands, angle in 8 sectors.
void expectUniformOverRing(const std::vector<V>& points, const V& centre, double inner,
                           double outer) {
  std::vector<double> radial;
  std::vector<double> angle;
  std::vector<double> cells(32, 0.0);
  for (const V& p : points) {
    const V d = p - centre;
    const double s = (d.squaredNorm() - inner * inner) / (outer * outer - inner * inner);
    const double a = std::atan2(d.y(), d.x()) + M_PI;
    radial.push_back(s);
    angle.push_back(a);
    const int band = std::min(3, static_cast<int>(4.0 * s));
    const int sector = std::min(7, static_cast<int>(8.0 * a / (2.0 * M_PI)));
    cells[static_cast<std::size_t>(band * 8 + sector)] += 1.0;
  }
  expectUniform(radial, 0.0, 1.0);
  expectUniform(angle, 0.0, 2.0 * M_PI);
  EXPECT_LT(chiSquare(cells, std::vector<double>(32, points.size() / 32.0)), chiSquareCritical(31));
}

TEST(RegionDraw, DiskIsUniformOverItsArea) {
  const auto draw = RegionDraw::make(RegionShape::disk(V(0.1, -0.2), 0.3), 0.0);
  ASSERT_TRUE(draw);
  EXPECT_TRUE(draw->exact());
  EXPECT_NEAR(draw->drawnArea(), M_PI * 0.09, 1e-15);
  expectUniformOverRing(drawMany(*draw, 1), V(0.1, -0.2), 0.0, 0.3);
}

TEST(RegionDraw, AnnulusIsUniformOverItsArea) {
  const auto draw = RegionDraw::make(RegionShape::annulus(V(0, 0), 0.2, 0.5), 0.0);
  ASSERT_TRUE(draw);
  const std::vector<V> points = drawMany(*draw, 2);
  expectUniformOverRing(points, V(0, 0), 0.2, 0.5);
  // A draw uniform in the radius (not its square) would put half the points below 0.35 m.
  double below = 0;
  for (const V& p : points) {
    below += p.norm() < 0.35 ? 1.0 : 0.0;
  }
  const double expected = (0.35 * 0.35 - 0.04) / (0.25 - 0.04);
  EXPECT_NEAR(below / points.size(), expected, 4.0 * std::sqrt(0.25 / points.size()));
}

TEST(RegionDraw, InsetRingKeepsTheObjectInside) {
  const double r = 0.05;
  const auto draw = RegionDraw::make(RegionShape::annulus(V(0, 0), 0.2, 0.5), r);
  ASSERT_TRUE(draw);
  const std::vector<V> points = drawMany(*draw, 3);
  double lo = 1.0;
  double hi = 0.0;
  for (const V& p : points) {
    lo = std::min(lo, p.norm());
    hi = std::max(hi, p.norm());
  }
  EXPECT_GE(lo, 0.25 - 1e-12);
  EXPECT_LE(hi, 0.45 + 1e-12);
  EXPECT_LT(lo, 0.2501);  // and it reaches its edges
  EXPECT_GT(hi, 0.4499);
  expectUniformOverRing(points, V(0, 0), 0.25, 0.45);
  // No room: the inset ring would be empty; a disk inset to a point is room (as a range that
  // the shrink leaves zero wide).
  EXPECT_FALSE(RegionDraw::make(RegionShape::annulus(V(0, 0), 0.2, 0.3), 0.0500001));
  EXPECT_TRUE(RegionDraw::make(RegionShape::annulus(V(0, 0), 0.2, 0.3), 0.05));
  EXPECT_FALSE(RegionDraw::make(RegionShape::disk(V(0, 0), 0.1), 0.1000001));
  EXPECT_TRUE(RegionDraw::make(RegionShape::disk(V(0, 0), 0.1), 0.1));
}

TEST(RegionDraw, RotatedRectangleIsUniformInItsOwnAxes) {
  const double yaw = 0.7;
  const RegionShape shape = RegionShape::rotatedRectangle(V(0.3, 0.1), V(0.4, 0.2), yaw);
  const double r = 0.02;
  const auto draw = RegionDraw::make(shape, r);
  ASSERT_TRUE(draw);
  std::vector<double> u;
  std::vector<double> v;
  std::vector<double> cells(64, 0.0);
  for (const V& p : drawMany(*draw, 4)) {
    const V d = p - V(0.3, 0.1);
    const double a = std::cos(yaw) * d.x() + std::sin(yaw) * d.y();
    const double b = -std::sin(yaw) * d.x() + std::cos(yaw) * d.y();
    u.push_back(a);
    v.push_back(b);
    const int i = std::clamp(static_cast<int>((a + 0.18) / 0.36 * 8.0), 0, 7);
    const int j = std::clamp(static_cast<int>((b + 0.08) / 0.16 * 8.0), 0, 7);
    cells[static_cast<std::size_t>(i * 8 + j)] += 1.0;
    EXPECT_TRUE(shapeContains(shape, p));
  }
  expectUniform(u, -0.18, 0.18);  // inset by r on each side
  expectUniform(v, -0.08, 0.08);
  EXPECT_LT(chiSquare(cells, std::vector<double>(64, kDraws / 64.0)), chiSquareCritical(63));
  EXPECT_FALSE(RegionDraw::make(shape, 0.1000001));
}

/// A convex hexagon (clockwise on purpose) and its fan: counts per triangle follow the areas,
/// and within a triangle the barycentric coordinates are uniform.
TEST(RegionDraw, ConvexPolygonIsUniformOverItsArea) {
  const std::vector<V> hexagon{{0, 0},      {-0.1, 0.2}, {0, 0.4},
                               {0.3, 0.45}, {0.5, 0.2},  {0.35, -0.05}};
  const auto draw = RegionDraw::make(RegionShape::polygon(hexagon), 0.0);
  ASSERT_TRUE(draw);
  EXPECT_TRUE(draw->exact());
  // Cells: the six triangles from an interior point, whose areas are known.
  const V hub(0.2, 0.2);
  std::vector<double> areas;
  double total = 0.0;
  for (std::size_t i = 0; i < hexagon.size(); ++i) {
    const V a = hexagon[i] - hub;
    const V b = hexagon[(i + 1) % hexagon.size()] - hub;
    areas.push_back(0.5 * std::abs(a.x() * b.y() - a.y() * b.x()));
    total += areas.back();
  }
  EXPECT_NEAR(draw->drawnArea(), total, 1e-12);
  std::vector<double> counts(hexagon.size(), 0.0);
  std::vector<double> expected;
  for (double a : areas) {
    expected.push_back(kDraws * a / total);
  }
  for (const V& p : drawMany(*draw, 5)) {
    EXPECT_TRUE(shapeContains(RegionShape::polygon(hexagon), p));
    const double angle = std::atan2(p.y() - hub.y(), p.x() - hub.x());
    for (std::size_t i = 0; i < hexagon.size(); ++i) {
      // The sector between the hub's rays to vertex i and i + 1 (clockwise).
      const double a0 = std::atan2(hexagon[i].y() - hub.y(), hexagon[i].x() - hub.x());
      const double a1 =
          std::atan2(hexagon[(i + 1) % 6].y() - hub.y(), hexagon[(i + 1) % 6].x() - hub.x());
      double span = a0 - a1;
      double off = a0 - angle;
      span += span < 0 ? 2 * M_PI : 0;
      off += off < 0 ? 2 * M_PI : 0;
      if (off <= span) {
        counts[i] += 1.0;
        break;
      }
    }
  }
  EXPECT_LT(chiSquare(counts, expected), chiSquareCritical(5));
}

TEST(RegionDraw, TriangleHasUniformBarycentricCoordinates) {
  const V a(0.1, 0.0), b(0.5, 0.1), c(0.2, 0.4);
  const auto draw = RegionDraw::make(RegionShape::polygon({a, b, c}), 0.0);
  ASSERT_TRUE(draw);
  std::vector<double> fu;
  std::vector<double> fv;
  for (const V& p : drawMany(*draw, 6)) {
    // p = a + u (b - a) + v (c - a); u has density 2 (1 - u), so 1 - (1 - u)^2 is U(0, 1).
    Eigen::Matrix2d m;
    m << b - a, c - a;
    const V uv = m.inverse() * (p - a);
    EXPECT_GE(uv.x(), -1e-12);
    EXPECT_GE(uv.y(), -1e-12);
    EXPECT_LE(uv.sum(), 1.0 + 1e-12);
    fu.push_back(1.0 - (1.0 - uv.x()) * (1.0 - uv.x()));
    fv.push_back(1.0 - (1.0 - uv.y()) * (1.0 - uv.y()));
  }
  expectUniform(fu, 0.0, 1.0);
  expectUniform(fv, 0.0, 1.0);
}

/// A U-shaped (non-convex) polygon on a 0.1 m grid: every grid cell inside is equally likely,
/// with and without an inset (the inset one by rejection).
TEST(RegionDraw, NonConvexPolygonIsUniformAndInsetByRejection) {
  const std::vector<V> u{{0, 0},     {0.6, 0},   {0.6, 0.5}, {0.4, 0.5},
                         {0.4, 0.2}, {0.2, 0.2}, {0.2, 0.5}, {0, 0.5}};
  const RegionShape shape = RegionShape::polygon(u);
  const auto whole = RegionDraw::make(shape, 0.0);
  ASSERT_TRUE(whole);
  EXPECT_TRUE(whole->exact());
  EXPECT_NEAR(whole->drawnArea(), 0.3 - 0.06, 1e-12);
  // Cells of 0.1 m: 6 x 2 along the bottom, 2 x 3 in each arm.
  std::vector<double> counts(30, 0.0);
  for (const V& p : drawMany(*whole, 7)) {
    ASSERT_TRUE(shapeContains(shape, p));
    const int i = std::min(5, static_cast<int>(p.x() / 0.1));
    const int j = std::min(4, static_cast<int>(p.y() / 0.1));
    counts[static_cast<std::size_t>(i * 5 + j)] += 1.0;
  }
  std::vector<double> in;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 5; ++j) {
      const bool inside = j < 2 || i < 2 || i >= 4;
      if (inside) {
        in.push_back(counts[static_cast<std::size_t>(i * 5 + j)]);
      } else {
        EXPECT_EQ(counts[static_cast<std::size_t>(i * 5 + j)], 0.0) << i << " " << j;
      }
    }
  }
  ASSERT_EQ(in.size(), 24u);
  EXPECT_LT(chiSquare(in, std::vector<double>(24, kDraws / 24.0)), chiSquareCritical(23));

  // Inset by 0.05 m: a draw is accepted exactly when it keeps that far from every edge, and the
  // accepted ones are uniform over what is left.
  const auto inset = RegionDraw::make(shape, 0.05);
  ASSERT_TRUE(inset);
  EXPECT_FALSE(inset->exact());
  const auto clearance = [&](const V& p) {
    double best = 1.0;
    for (std::size_t k = 0; k < u.size(); ++k) {
      const V a = u[k];
      const V ab = u[(k + 1) % u.size()] - a;
      const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (a + t * ab - p).norm());
    }
    return best;
  };
  std::vector<double> bottom;
  Engine engine = sceneEngine(8, 0);
  int accepted = 0;
  for (int k = 0; k < kDraws; ++k) {
    const V p = inset->draw(engine);
    ASSERT_TRUE(shapeContains(shape, p));
    EXPECT_EQ(inset->accepts(p), clearance(p) >= 0.05) << p.transpose();
    if (inset->accepts(p)) {
      ++accepted;
      if (p.y() < 0.15) {
        bottom.push_back(p.x());
      }
    }
  }
  // What is left: the bottom bar 0.5 x 0.1, the arms 2 x 0.1 x 0.3, and at each inner corner
  // a 0.05 m square less a quarter disk of that radius; of the 0.24 m^2 drawn from.
  const double left = 0.05 + 0.06 + 2.0 * 0.0025 * (1.0 - M_PI / 4.0);
  EXPECT_NEAR(static_cast<double>(accepted) / kDraws, left / 0.24, 4.0 * std::sqrt(0.25 / kDraws));
  expectUniform(bottom, 0.05, 0.55);
  // The widest room is at the inner corners: the circle touching x = 0, y = 0 and the corner
  // (0.2, 0.2) has radius 0.2 sqrt(2) / (1 + sqrt(2)) = 0.1172 m.
  EXPECT_TRUE(RegionDraw::make(shape, 0.11));
  EXPECT_FALSE(RegionDraw::make(shape, 0.118));
}

TEST(RegionDraw, ConvexPolygonInsetIsExact) {
  const RegionShape square = RegionShape::polygon({{0, 0}, {0.4, 0}, {0.4, 0.4}, {0, 0.4}});
  const auto draw = RegionDraw::make(square, 0.05);
  ASSERT_TRUE(draw);
  EXPECT_TRUE(draw->exact());
  EXPECT_NEAR(draw->drawnArea(), 0.09, 1e-12);
  std::vector<double> x;
  for (const V& p : drawMany(*draw, 9, 10000)) {
    x.push_back(p.x());
    EXPECT_GE(std::min({p.x(), p.y(), 0.4 - p.x(), 0.4 - p.y()}), 0.05 - 1e-12);
  }
  expectUniform(x, 0.05, 0.35);
  EXPECT_FALSE(RegionDraw::make(square, 0.2));  // a point has no area
}

/// Rectangle regions draw x then y, as robosuite: the same doubles as uniform() twice.
TEST(RegionDraw, RectangleDrawsAsRobosuite) {
  const auto draw = RegionDraw::make(RegionShape::rectangle(V(-0.3, 0.2), V(-0.1, 0.4)), 0.02);
  ASSERT_TRUE(draw);
  Engine a = sceneEngine(10, 0);
  Engine b = sceneEngine(10, 0);
  for (int k = 0; k < 100; ++k) {
    const V p = draw->draw(a);
    // The same sums as robosuite's shrink: min + radius, max - radius.
    const double x = uniform(b, -0.3 + 0.02, 0.2 - 0.02);
    EXPECT_EQ(p, V(x, uniform(b, -0.1 + 0.02, 0.4 - 0.02)));
  }
}

TEST(RegionShapes, ContainsAndDistance) {
  const RegionShape ring = RegionShape::annulus(V(1, 1), 0.1, 0.2);
  EXPECT_TRUE(shapeContains(ring, V(1.15, 1)));
  EXPECT_FALSE(shapeContains(ring, V(1.05, 1)));
  EXPECT_NEAR(distanceToShape(ring, V(1.05, 1)), 0.05, 1e-12);
  EXPECT_NEAR(distanceToShape(ring, V(1, 1.5)), 0.3, 1e-12);
  const RegionShape box = RegionShape::rotatedRectangle(V(0, 0), V(0.2, 0.1), M_PI / 2);
  EXPECT_TRUE(shapeContains(box, V(0.0, 0.09)));
  EXPECT_FALSE(shapeContains(box, V(0.09, 0.0)));
  EXPECT_NEAR(distanceToShape(box, V(0.1, 0.0)), 0.05, 1e-12);
  const RegionShape l = RegionShape::polygon({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});
  EXPECT_TRUE(shapeContains(l, V(0.5, 1.5)));
  EXPECT_FALSE(shapeContains(l, V(1.5, 1.5)));
  EXPECT_NEAR(distanceToShape(l, V(1.5, 1.5)), 0.5, 1e-12);
  KeepOutZone zone{RegionShape::disk(V(0, 0), 0.1), false};
  EXPECT_TRUE(keepOutBlocks(zone, V(0.05, 0), 0.0));
  EXPECT_FALSE(keepOutBlocks(zone, V(0.15, 0), 0.0));
  EXPECT_TRUE(keepOutBlocks(zone, V(0.15, 0), 0.06));
  EXPECT_FALSE(keepOutBlocks(zone, V(0.15, 0), 0.04));
}

TEST(RegionShapes, Problems) {
  const auto problem = [](const RegionShape& s) {
    const auto p = findShapeProblem(s);
    return p ? p->key + ": " + p->message : std::string("none");
  };
  EXPECT_EQ(problem(RegionShape::polygon({{0, 0}, {1, 1}, {1, 0}, {0, 1}})),
            "vertices: the polygon intersects itself: the edge from vertex 0 [0, 0] to vertex 1 "
            "[1, 1] crosses the edge from vertex 2 [1, 0] to vertex 3 [0, 1]");
  // Flat polygons fold back onto themselves.
  EXPECT_EQ(problem(RegionShape::polygon({{0, 0}, {1, 0}, {0.5, 0}})),
            "vertices: the polygon intersects itself: the edge from vertex 0 [0, 0] to vertex 1 "
            "[1, 0] overlaps the edge from vertex 1 [1, 0] to vertex 2 [0.5, 0]");
  EXPECT_EQ(problem(RegionShape::polygon({{0, 0}, {1, 0}, {2, 0}})),
            "vertices: the polygon intersects itself: the edge from vertex 1 [1, 0] to vertex 2 "
            "[2, 0] overlaps the edge from vertex 2 [2, 0] to vertex 0 [0, 0]");
  EXPECT_EQ(problem(RegionShape::polygon({{0, 0}, {1, 0}, {1, 0}, {0, 1}})),
            "vertices: vertices 1 and 2 are the same point [1, 0]");
  EXPECT_EQ(problem(RegionShape::polygon({{0, 0}, {1, 0}})),
            "vertices: expected 3 to 1000 vertices [x, y], got 2");
  EXPECT_EQ(problem(RegionShape::polygon({{0, 0}, {NAN, 0}, {0, 1}})),
            "vertices: vertex 1 must lie within [-1e+06, 1e+06] m, got [nan, 0]");
  // Touching itself at a vertex is intersecting too.
  EXPECT_EQ(problem(RegionShape::polygon({{0, 0}, {2, 0}, {1, 1}, {2, 2}, {0, 2}, {1, 1}})),
            "vertices: the polygon intersects itself: the edge from vertex 1 [2, 0] to vertex 2 "
            "[1, 1] crosses the edge from vertex 4 [0, 2] to vertex 5 [1, 1]");
  EXPECT_EQ(problem(RegionShape::annulus(V(0, 0), 0.3, 0.3)),
            "inner_radius: the inner radius 0.3 m must be less than outer_radius 0.3 m");
  EXPECT_EQ(problem(RegionShape::disk(V(0, 0), 0.0)),
            "radius: expected a length > 0 [m] within [-1e+06, 1e+06] m, got 0");
  EXPECT_EQ(problem(RegionShape::rotatedRectangle(V(0, 0), V(-1, 1), 0.0)),
            "size: expected [x, y] lengths >= 0 [m] within [-1e+06, 1e+06] m, got [-1, 1]");
  EXPECT_EQ(problem(RegionShape::rectangle(V(1, 0), V(0, 1))),
            "x_range: expected [min, max] with min <= max, got [1, 0]");
  EXPECT_EQ(problem(RegionShape::disk(V(2e6, 0), 1.0)),
            "center: expected [x, y] within [-1e+06, 1e+06] m, got [2e+06, 0]");
  // Either winding is a valid polygon.
  EXPECT_EQ(problem(RegionShape::polygon({{0, 0}, {0, 1}, {1, 0}})), "none");
  EXPECT_EQ(problem(RegionShape::polygon({{0, 0}, {1, 0}, {0, 1}})), "none");
}

TEST(RegionShapes, TrianglesCoverTheArea) {
  const auto area = [](const std::vector<V>& t) {
    double sum = 0.0;
    for (std::size_t k = 0; k < t.size(); k += 3) {
      const V a = t[k + 1] - t[k];
      const V b = t[k + 2] - t[k];
      sum += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
    }
    return sum;
  };
  EXPECT_NEAR(
      area(shapeTriangles(RegionShape::polygon({{0, 0}, {0, 2}, {1, 2}, {1, 1}, {2, 1}, {2, 0}}))),
      3.0, 1e-12);
  EXPECT_NEAR(area(shapeTriangles(RegionShape::rotatedRectangle(V(1, 2), V(0.2, 0.3), 1.0))), 0.06,
              1e-12);
  // A 48-gon's area: 48 / 2 sin(2 pi / 48) r^2.
  EXPECT_NEAR(area(shapeTriangles(RegionShape::annulus(V(0, 0), 0.1, 0.2))),
              24.0 * std::sin(2.0 * M_PI / 48.0) * (0.04 - 0.01), 1e-12);
}

}  // namespace
}  // namespace placement_samplers
