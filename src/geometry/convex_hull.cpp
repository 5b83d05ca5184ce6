#include "geometry/convex_hull.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "geometry/hull_builder.hpp"

namespace placement_samplers::detail {
namespace {

/// The tolerance relative to the points' extent (ConvexHull::tolerance).
constexpr double kRelativeTolerance = 1e-6;
/// The factor between the tolerances of the attempts convexHull() makes.
constexpr double kRetryFactor = 100.0;

double toleranceOf(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const double magnitude = lo.cwiseAbs().cwiseMax(hi.cwiseAbs()).sum();
  return std::max(3.0 * std::numeric_limits<double>::epsilon() * magnitude,
                  kRelativeTolerance * (hi - lo).norm());
}

ConvexHull hullWithTolerance(const std::vector<Eigen::Vector3d>& points, double tol,
                             const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                             const int* loIndex, const int* hiIndex) {
  const std::size_t n = points.size();
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const int v0 = loIndex[axis], v1 = hiIndex[axis];
  if (hi[axis] - lo[axis] <= tol) {
    throw std::invalid_argument("convex hull: all " + std::to_string(n) +
                                " points are at one place, they span no volume");
  }
  const Eigen::Vector3d u = (points[v1] - points[v0]).normalized();
  int v2 = -1;
  double best = tol;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = (points[i] - points[v0]).cross(u).norm();
    if (d > best) {
      best = d;
      v2 = static_cast<int>(i);
    }
  }
  if (v2 < 0) {
    throw std::invalid_argument("convex hull: all " + std::to_string(n) +
                                " points lie on a line, they span no volume");
  }
  const Eigen::Vector3d normal =
      (points[v1] - points[v0]).cross(points[v2] - points[v0]).normalized();
  int v3 = -1;
  best = tol;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = std::abs(normal.dot(points[i] - points[v0]));
    if (d > best) {
      best = d;
      v3 = static_cast<int>(i);
    }
  }
  if (v3 < 0) {
    throw std::invalid_argument("convex hull: all " + std::to_string(n) +
                                " points lie on a plane, they span no volume");
  }
  return HullBuilder(points, tol).build(v0, v1, v2, v3);
}

}  // namespace

ConvexHull convexHull(const std::vector<Eigen::Vector3d>& points) {
  const std::size_t n = points.size();
  if (n > kMaxHullPoints) {
    throw std::invalid_argument("convex hull: " + std::to_string(n) + " points, at most " +
                                std::to_string(kMaxHullPoints) + " are taken");
  }
  if (n < 4) {
    throw std::invalid_argument("convex hull: " + std::to_string(n) +
                                (n == 1 ? " point spans" : " points span") +
                                " no volume (at least four are needed)");
  }
  Eigen::Vector3d lo = points[0], hi = points[0];
  int loIndex[3] = {0, 0, 0}, hiIndex[3] = {0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    if (!points[i].allFinite()) {
      throw std::invalid_argument("convex hull: point " + std::to_string(i) + " is not finite");
    }
    for (int k = 0; k < 3; ++k) {
      if (points[i][k] < lo[k]) {
        lo[k] = points[i][k];
        loIndex[k] = static_cast<int>(i);
      }
      if (points[i][k] > hi[k]) {
        hi[k] = points[i][k];
        hiIndex[k] = static_cast<int>(i);
      }
    }
  }
  const double tol = toleranceOf(lo, hi);
  // Nearly coplanar points can defeat the merges' bookkeeping; a coarser tolerance merges them
  // earlier and more boldly. Never seen in tests; a safety net.
  for (int attempt = 0;; ++attempt) {
    try {
      return hullWithTolerance(points, tol * std::pow(kRetryFactor, attempt), lo, hi, loIndex,
                               hiIndex);
    } catch (const HullInternalError& e) {
      if (attempt == 2) {
        throw std::invalid_argument(std::string("convex hull: internal inconsistency (") +
                                    e.what() + ") with " + std::to_string(n) + " points");
      }
    }
  }
}

double hullTolerance(const std::vector<Eigen::Vector3d>& points) {
  if (points.empty()) {
    return 0.0;
  }
  Eigen::Vector3d lo = points[0], hi = points[0];
  for (const Eigen::Vector3d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return toleranceOf(lo, hi);
}

void hullVolume(const ConvexHull& hull, const std::vector<Eigen::Vector3d>& points, double& volume,
                Eigen::Vector3d& centroid, Eigen::Matrix3d* spread) {
  // Tetrahedra from a point inside (the mean of the vertices): no cancellation of large terms.
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();
  for (int v : hull.vertices) {
    reference += points[static_cast<std::size_t>(v)];
  }
  reference /= static_cast<double>(std::max<std::size_t>(hull.vertices.size(), 1));
  volume = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // about the reference point
  for (std::size_t f = 0; f < hull.faceCount(); ++f) {
    const int* corner = hull.vertices.data() + hull.start[f];
    const Eigen::Vector3d a = points[static_cast<std::size_t>(corner[0])] - reference;
    for (int i = 1; i + 1 < hull.cornerCount(f); ++i) {
      const Eigen::Vector3d b = points[static_cast<std::size_t>(corner[i])] - reference;
      const Eigen::Vector3d c = points[static_cast<std::size_t>(corner[i + 1])] - reference;
      const double v = a.dot(b.cross(c)) / 6.0;
      volume += v;
      moment += v * (a + b + c) / 4.0;
      if (spread) {  // a tetrahedron with a corner at the origin: v/20 (sum p p^T + s s^T)
        const Eigen::Vector3d s = a + b + c;
        second += v / 20.0 *
                  (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
      }
    }
  }
  const Eigen::Vector3d offset =
      volume > 0.0 ? Eigen::Vector3d(moment / volume) : Eigen::Vector3d::Zero();
  centroid = reference + offset;
  if (spread) {
    *spread = second - volume * offset * offset.transpose();
  }
}

}  // namespace placement_samplers::detail
