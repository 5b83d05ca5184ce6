// The convex-ring helpers of surface_polygons.hpp: no Boost.Geometry, exact tests for the
// convex footprints of primitives and mesh triangles.

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/surface_polygons.hpp"

namespace placement_samplers {
namespace surfaces {
namespace {

double cross(const Point2& u, const Point2& v) { return u.x() * v.y() - u.y() * v.x(); }

}  // namespace

Ring convexHull(std::vector<Point2> points) {
  std::sort(points.begin(), points.end(), [](const Point2& a, const Point2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) {
    return {};
  }
  // Andrew's monotone chain: the lower hull left to right, then the upper hull back.
  Ring hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0) {
      --k;
    }
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, upperStart = k + 1; i-- > 0;) {
    while (k >= upperStart && cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0) {
      --k;
    }
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return simplifyRing(hull) ? hull : Ring();
}

bool isConvex(const Ring& ring) {
  const std::size_t n = ring.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (cross(ring[(i + 1) % n] - ring[i], ring[(i + 2) % n] - ring[(i + 1) % n]) < 0.0) {
      return false;
    }
  }
  return n >= 3;
}

bool convexApart(const Ring& a, const Ring& b) {
  // Separating axes: the outward normals of both rings' edges.
  for (const Ring* ring : {&a, &b}) {
    const Ring& r = *ring;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const Point2 edge = r[(i + 1) % r.size()] - r[i];
      const double length = edge.norm();
      if (length == 0.0) {
        continue;
      }
      const Point2 normal(edge.y() / length, -edge.x() / length);
      const double limit = normal.dot(r[i]) - kLinearTolerance;
      const Ring& other = ring == &a ? b : a;
      if (std::all_of(other.begin(), other.end(),
                      [&](const Point2& p) { return normal.dot(p) >= limit; })) {
        return true;
      }
    }
  }
  return false;
}

bool convexJoined(const Ring& a, const Ring& b) {
  for (const Ring* ring : {&a, &b}) {
    const Ring& r = *ring;
    const Ring& other = ring == &a ? b : a;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const Point2 edge = r[(i + 1) % r.size()] - r[i];
      const double length = edge.norm();
      if (length == 0.0) {
        continue;
      }
      const Point2 direction = edge / length;
      const Point2 normal(direction.y(), -direction.x());
      const double line = normal.dot(r[i]);
      if (!std::all_of(other.begin(), other.end(),
                       [&](const Point2& p) { return normal.dot(p) >= line - kLinearTolerance; })) {
        continue;  // not a separating line
      }
      // Separated by the line of this edge: joined only along a piece of it. Convex rings
      // that share a segment have no other separating line.
      double low = std::numeric_limits<double>::infinity();
      double high = -low;
      for (const Point2& p : other) {
        if (normal.dot(p) <= line + kLinearTolerance) {
          const double t = direction.dot(p - r[i]);
          low = std::min(low, t);
          high = std::max(high, t);
        }
      }
      return std::min(high, length) - std::max(low, 0.0) > kLinearTolerance;
    }
  }
  return true;
}

}  // namespace surfaces
}  // namespace placement_samplers
