// The convex hull behind resting poses and mesh masses: closed, convex, every point inside,
// flat sides merged into one polygon, degenerate input refused with a clear message.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geometry/convex_hull.hpp"

namespace placement_samplers::detail {
namespace {

using Points = std::vector<Eigen::Vector3d>;

/// Checks that @p hull is a closed convex polyhedron over @p points: every directed edge has its
/// reverse on the face listed as neighbour, V - E + F = 2, faces are flat and every point lies
/// inside every face's plane (both within a few tolerances).
void expectValidHull(const ConvexHull& hull, const Points& points, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(hull.start.size(), hull.faceCount() + 1);
  std::map<std::pair<int, int>, int> edges;
  double worstOutside = 0.0, worstBend = 0.0;
  for (std::size_t f = 0; f < hull.faceCount(); ++f) {
    const int n = hull.cornerCount(f);
    ASSERT_GE(n, 3);
    const int* corner = hull.vertices.data() + hull.start[f];
    double hi = -1e300, lo = 1e300;
    for (int k = 0; k < n; ++k) {
      const double d = hull.normals[f].dot(points[static_cast<std::size_t>(corner[k])]);
      hi = std::max(hi, d);
      lo = std::min(lo, d);
      ASSERT_TRUE(edges.emplace(std::make_pair(corner[k], corner[(k + 1) % n]), f).second);
    }
    worstBend = std::max(worstBend, hi - lo);
    for (const Eigen::Vector3d& p : points) {
      worstOutside = std::max(worstOutside, hull.normals[f].dot(p) - hi);
    }
    EXPECT_NEAR(hull.normals[f].norm(), 1.0, 1e-12);
  }
  for (std::size_t f = 0; f < hull.faceCount(); ++f) {
    const int n = hull.cornerCount(f);
    const int* corner = hull.vertices.data() + hull.start[f];
    for (int k = 0; k < n; ++k) {
      const auto reverse = edges.find({corner[(k + 1) % n], corner[k]});
      ASSERT_NE(reverse, edges.end());
      EXPECT_EQ(reverse->second, hull.neighbours[static_cast<std::size_t>(hull.start[f] + k)]);
    }
  }
  const std::set<int> vertices(hull.vertices.begin(), hull.vertices.end());
  const long v = static_cast<long>(vertices.size()), e = static_cast<long>(edges.size() / 2),
             f = static_cast<long>(hull.faceCount());
  EXPECT_EQ(v - e + f, 2);
  EXPECT_LE(worstOutside, 10.0 * hull.tolerance);
  EXPECT_LE(worstBend, 10.0 * hull.tolerance);
}

Points boxCorners(const Eigen::Vector3d& half) {
  Points p;
  for (int i = 0; i < 8; ++i) {
    p.emplace_back((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                   (i & 4) ? half.z() : -half.z());
  }
  return p;
}

TEST(ConvexHull, BoxCornersMakeSixSquareFaces) {
  const Points p = boxCorners(Eigen::Vector3d(0.1, 0.05, 0.025));
  const ConvexHull hull = convexHull(p);
  expectValidHull(hull, p, "box");
  ASSERT_EQ(hull.faceCount(), 6u);
  for (std::size_t f = 0; f < 6; ++f) {
    EXPECT_EQ(hull.cornerCount(f), 4);
    EXPECT_NEAR(hull.normals[f].cwiseAbs().maxCoeff(), 1.0, 1e-15);
  }
  double volume = 0.0;
  Eigen::Vector3d centroid;
  hullVolume(hull, p, volume, centroid);
  EXPECT_NEAR(volume, 0.2 * 0.1 * 0.05, 1e-15);
  EXPECT_LT(centroid.norm(), 1e-15);
}

TEST(ConvexHull, PointsOnTheSidesOfABoxAreNotVertices) {
  // A tessellated box: every side a grid of coplanar points, its edges full of collinear ones.
  Points p;
  const int n = 20;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      for (int k = 0; k <= n; ++k) {
        if (i == 0 || j == 0 || k == 0 || i == n || j == n || k == n) {
          p.emplace_back(0.1 * i / n, 0.3 * j / n - 0.1, 0.05 * k / n);
        }
      }
    }
  }
  const ConvexHull hull = convexHull(p);
  expectValidHull(hull, p, "tessellated box");
  EXPECT_EQ(hull.faceCount(), 6u);
  EXPECT_EQ(std::set<int>(hull.vertices.begin(), hull.vertices.end()).size(), 8u);
}

TEST(ConvexHull, SinglePrecisionSidesMergeIntoOneFace) {
  // A turned cube whose corners and side points went through float: its sides are flat only to
  // about 1e-9 m, far below the tolerance (1e-6 of the extent).
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  Points p;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Eigen::Vector3d& c : boxCorners(Eigen::Vector3d::Constant(0.05))) {
    p.push_back((turn * c).cast<float>().cast<double>());
  }
  for (int i = 0; i < 3000; ++i) {
    Eigen::Vector3d v(u(rng), u(rng), u(rng));
    v[i % 3] = (i / 3) % 2 ? 1.0 : -1.0;
    p.push_back((turn * (0.05 * v)).cast<float>().cast<double>());
  }
  const ConvexHull hull = convexHull(p);
  expectValidHull(hull, p, "float cube");
  EXPECT_EQ(hull.faceCount(), 6u);
}

TEST(ConvexHull, RandomCloudsAreClosedAndContainEveryPoint) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 60; ++trial) {
    Points p;
    const int kind = trial % 4;
    const Eigen::Quaterniond turn = Eigen::Quaterniond::UnitRandom();
    for (int i = 0; i < 500; ++i) {
      Eigen::Vector3d v;
      if (kind == 0) {  // in a cube
        v = Eigen::Vector3d(u(rng), u(rng), u(rng));
      } else if (kind == 1) {  // on an ellipsoid: every point a vertex
        v = Eigen::Vector3d(g(rng), g(rng), g(rng))
                .normalized()
                .cwiseProduct(Eigen::Vector3d(0.1, 0.06, 0.04));
      } else if (kind == 2) {  // a small turned lattice: duplicates, coplanar, collinear points
        v = turn * Eigen::Vector3d(static_cast<double>(rng() % 5), static_cast<double>(rng() % 4),
                                   static_cast<double>(rng() % 3));
      } else {  // a cylinder's rims, as restingPoses samples them
        const double t = 2.0 * M_PI * static_cast<double>(rng() % 64) / 64.0;
        v = turn *
            Eigen::Vector3d(0.03 * std::cos(t), 0.03 * std::sin(t), rng() % 2 ? 0.05 : -0.05);
      }
      p.push_back(v);
    }
    expectValidHull(convexHull(p), p, "trial " + std::to_string(trial));
  }
}

TEST(ConvexHull, LargeEllipsoid) {
  Points p;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g;
  for (int i = 0; i < 20000; ++i) {
    p.push_back(Eigen::Vector3d(g(rng), g(rng), g(rng))
                    .normalized()
                    .cwiseProduct(Eigen::Vector3d(0.1, 0.06, 0.04)));
  }
  const ConvexHull hull = convexHull(p);
  double volume = 0.0;
  Eigen::Vector3d centroid;
  hullVolume(hull, p, volume, centroid);
  // The inscribed polyhedron of 20,000 points: a little less than 4/3 pi abc.
  const double ellipsoid = 4.0 / 3.0 * M_PI * 0.1 * 0.06 * 0.04;
  EXPECT_LT(volume, ellipsoid);
  EXPECT_GT(volume, 0.995 * ellipsoid);
  EXPECT_LT(centroid.norm(), 1e-4);
  EXPECT_GT(hull.faceCount(), 30000u);
}

using Triangles = std::vector<Eigen::Vector3i>;

/// A closed box mesh of 12 triangles, counter-clockwise seen from outside.
Triangles boxTriangles() {
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  Triangles t;
  for (const auto& q : quads) {
    t.emplace_back(q[0], q[1], q[2]);
    t.emplace_back(q[0], q[2], q[3]);
  }
  return t;
}

/// An ellipsoid: two poles and @p rings rings of @p segments vertices, each ring turned half a
/// segment from the last.
void ellipsoidMesh(int rings, int segments, Points& p, Triangles& t) {
  p.assign(1, Eigen::Vector3d(0, 0, 0.04));
  for (int j = 1; j <= rings; ++j) {
    const double polar = M_PI * j / (rings + 1);
    for (int k = 0; k < segments; ++k) {
      const double a = 2.0 * M_PI * (k + 0.5 * (j % 2)) / segments;
      p.emplace_back(0.1 * std::sin(polar) * std::cos(a), 0.06 * std::sin(polar) * std::sin(a),
                     0.04 * std::cos(polar));
    }
  }
  p.emplace_back(0, 0, -0.04);
  const int last = static_cast<int>(p.size()) - 1;
  auto at = [&](int ring, int k) { return 1 + (ring - 1) * segments + k % segments; };
  t.clear();
  for (int k = 0; k < segments; ++k) {
    t.emplace_back(0, at(1, k), at(1, k + 1));
    t.emplace_back(last, at(rings, k + 1), at(rings, k));
  }
  // Each quad between two rings split along the diagonal that keeps the surface convex.
  for (int j = 1; j < rings; ++j) {
    for (int k = 0; k < segments; ++k) {
      const int a = at(j, k), b = at(j + 1, k), c = at(j + 1, k + 1), d = at(j, k + 1);
      const Eigen::Vector3d n = (p[b] - p[a]).cross(p[d] - p[a]);
      if (n.dot(p[c] - p[a]) <= 0.0) {
        t.emplace_back(a, b, d);
        t.emplace_back(d, b, c);
      } else {
        t.emplace_back(a, b, c);
        t.emplace_back(a, c, d);
      }
    }
  }
}

double volumeOf(const ConvexHull& hull, const Points& p) {
  double volume = 0.0;
  Eigen::Vector3d centroid;
  hullVolume(hull, p, volume, centroid);
  return volume;
}

TEST(ConvexMeshHull, ConvexMeshIsItsOwnHull) {
  const Points box = boxCorners(Eigen::Vector3d(0.1, 0.05, 0.025));
  const std::optional<ConvexHull> boxHull = convexMeshHull(box, boxTriangles());
  ASSERT_TRUE(boxHull);
  expectValidHull(*boxHull, box, "box mesh");
  EXPECT_EQ(boxHull->faceCount(), 6u);
  EXPECT_EQ(boxHull->vertices.size(), 24u);
  EXPECT_NEAR(volumeOf(*boxHull, box), 0.001, 1e-15);

  Points p;
  Triangles t;
  ellipsoidMesh(30, 40, p, t);
  const std::optional<ConvexHull> mesh = convexMeshHull(p, t);
  ASSERT_TRUE(mesh);
  expectValidHull(*mesh, p, "ellipsoid mesh");
  // The same solid as quickhull makes of its vertices.
  const ConvexHull quick = convexHull(p);
  EXPECT_NEAR(volumeOf(*mesh, p), volumeOf(quick, p), 1e-12);
  EXPECT_EQ(mesh->faceCount(), quick.faceCount());
}

TEST(ConvexMeshHull, OtherMeshesAreLeftToQuickhull) {
  const Points box = boxCorners(Eigen::Vector3d(0.1, 0.05, 0.025));
  Triangles open = boxTriangles();
  open.pop_back();
  EXPECT_FALSE(convexMeshHull(box, open));
  Triangles inverted = boxTriangles();
  for (Eigen::Vector3i& tri : inverted) {
    std::swap(tri[1], tri[2]);
  }
  EXPECT_FALSE(convexMeshHull(box, inverted));
  Points extra = box;
  extra.emplace_back(0.5, 0.0, 0.0);  // used by no triangle: it could be anywhere
  EXPECT_FALSE(convexMeshHull(extra, boxTriangles()));
  // A dent: one corner pushed in past its neighbours' planes.
  Points dented = box;
  dented[7] = Eigen::Vector3d(0.02, 0.01, 0.005);
  EXPECT_FALSE(convexMeshHull(dented, boxTriangles()));
  // Triangles that do not share their vertices (as an STL file stores them).
  Points soup;
  Triangles separate;
  for (const Eigen::Vector3i& tri : boxTriangles()) {
    const int base = static_cast<int>(soup.size());
    for (int k = 0; k < 3; ++k) {
      soup.push_back(box[static_cast<std::size_t>(tri[k])]);
    }
    separate.emplace_back(base, base + 1, base + 2);
  }
  EXPECT_FALSE(convexMeshHull(soup, separate));
  EXPECT_FALSE(convexMeshHull(box, {}));
  Triangles bad = boxTriangles();
  bad[0][1] = 8;
  EXPECT_FALSE(convexMeshHull(box, bad));
}

std::string hullError(const Points& p) {
  try {
    convexHull(p);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(ConvexHull, DegenerateInputIsRefused) {
  EXPECT_EQ(
      hullError({Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()}),
      "convex hull: 3 points span no volume (at least four are needed)");
  EXPECT_EQ(hullError({Eigen::Vector3d::Zero()}),
            "convex hull: 1 point spans no volume (at least four are needed)");
  EXPECT_EQ(hullError(Points(5, Eigen::Vector3d(1, 2, 3))),
            "convex hull: all 5 points are at one place, they span no volume");
  Points line, plane;
  for (int i = 0; i < 10; ++i) {
    line.emplace_back(0.1 * i, 0.2 * i, -0.05 * i);
    plane.emplace_back(0.1 * (i % 3), 0.1 * (i / 3), 0.0);
  }
  EXPECT_EQ(hullError(line), "convex hull: all 10 points lie on a line, they span no volume");
  EXPECT_EQ(hullError(plane), "convex hull: all 10 points lie on a plane, they span no volume");
  Points bad = boxCorners(Eigen::Vector3d::Ones());
  bad[5].y() = std::nan("");
  EXPECT_EQ(hullError(bad), "convex hull: point 5 is not finite");
  EXPECT_EQ(hullError(Points(kMaxHullPoints + 1, Eigen::Vector3d::Zero())),
            "convex hull: 1000001 points, at most 1000000 are taken");
}

}  // namespace
}  // namespace placement_samplers::detail
