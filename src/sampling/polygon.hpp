#pragma once
// Plane polygon helpers of the region shapes (region.cpp, region_draw.cpp). Private to the core.

#include <Eigen/Core>
#include <vector>

namespace placement_samplers::detail {

inline double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Twice the signed area: positive for counter-clockwise vertices [m^2].
double signedArea2(const std::vector<Eigen::Vector2d>& v);

/// True when the closed segments [a, b] and [c, d] share a point.
bool segmentsIntersect(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                       const Eigen::Vector2d& d);

/// The distance from @p p to the segment [a, b] [m].
double segmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b);

/// The distance from @p p to the polygon's boundary [m].
double boundaryDistance(const std::vector<Eigen::Vector2d>& v, const Eigen::Vector2d& p);

/// True when @p p is inside the polygon or on its boundary (crossing number).
bool polygonContains(const std::vector<Eigen::Vector2d>& v, const Eigen::Vector2d& p);

/// The vertices in counter-clockwise order.
std::vector<Eigen::Vector2d> counterClockwise(std::vector<Eigen::Vector2d> v);

/// Triangles (three corners each) of a simple counter-clockwise polygon: a fan from vertex 0
/// when it is convex, ear clipping otherwise.
/// @throw ConfigError when ear clipping finds no ear (rounding in a near-degenerate polygon)
std::vector<Eigen::Vector2d> triangulate(const std::vector<Eigen::Vector2d>& ccw);

/// The convex counter-clockwise polygon @p ccw with every edge moved inwards by @p margin [m]
/// (empty when nothing is left).
std::vector<Eigen::Vector2d> insetConvex(const std::vector<Eigen::Vector2d>& ccw, double margin);

/// Triangles (three corners each, counter-clockwise) that cover a polygon with holes exactly:
/// the trapezoids between consecutive vertex heights (y), each cut in two. Any winding; the
/// rings must not cross. Degenerate trapezoids are left out.
std::vector<Eigen::Vector2d> trapezoidTriangles(
    const std::vector<Eigen::Vector2d>& outer,
    const std::vector<std::vector<Eigen::Vector2d>>& holes);

}  // namespace placement_samplers::detail
