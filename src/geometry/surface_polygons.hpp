#pragma once

// Planar polygon work of support surface extraction (private to the core): rings, loops to
// polygons, and the few Boolean operations done with Boost.Geometry, which no other file sees.

#include <Eigen/Core>
#include <vector>

namespace placement_samplers {
namespace surfaces {

using Point2 = Eigen::Vector2d;
/// A closed ring without its closing vertex [m].
using Ring = std::vector<Point2>;

/// A polygon with holes: outer counter-clockwise, holes clockwise [m].
struct Polygon2 {
  Ring outer;
  std::vector<Ring> holes;
};
using Polygons = std::vector<Polygon2>;

/// An axis-aligned box in x-y [m].
struct Box2 {
  double minX = 0.0, minY = 0.0, maxX = 0.0, maxY = 0.0;
  /// True when the interiors overlap (boxes that only touch do not).
  bool overlaps(const Box2& other) const {
    return maxX > other.minX && other.maxX > minX && maxY > other.minY && other.maxY > minY;
  }
};

/// Points closer than this are one, and a vertex this close to the line of its neighbours is
/// removed [m].
constexpr double kLinearTolerance = 1e-9;
/// Rings of less area are degenerate and dropped [m^2].
constexpr double kDegenerateArea = 1e-14;

/// Shoelace area, positive for a counter-clockwise ring [m^2].
double signedArea(const Ring& ring);
/// The outer ring's area minus the holes' [m^2].
double polygonArea(const Polygon2& polygon);
Box2 ringBox(const Ring& ring);

/// Removes repeated vertices, vertices on the line of their neighbours and zero-width spikes.
/// @return false when the ring is degenerate (fewer than 3 vertices or no area left)
bool simplifyRing(Ring& ring);
/// simplifyRing on every ring: degenerate holes are dropped, and polygons whose outer ring is.
void simplifyPolygons(Polygons& polygons);

/// The convex hull of @p points, counter-clockwise (empty when they have no area).
Ring convexHull(std::vector<Point2> points);

/// Whether counter-clockwise @p ring turns left (or goes straight) at every vertex.
bool isConvex(const Ring& ring);
/// Whether the interiors of convex rings @p a and @p b are apart (a line separates them; rings
/// that touch, or overlap by less than kLinearTolerance, are apart).
bool convexApart(const Ring& a, const Ring& b);

/// Whether convex rings @p a and @p b overlap or share a piece of boundary longer than
/// kLinearTolerance: whether their union is one polygon rather than both as they are.
bool convexJoined(const Ring& a, const Ring& b);

/// Polygons from closed loops of a planar region's boundary, the region on each loop's left:
/// counter-clockwise loops are outer rings, clockwise ones holes, each given to the smallest
/// outer ring that contains it. Degenerate loops are dropped, holes outside every outer ring too.
/// @param valid set to false when a polygon made is not valid (self-intersecting loops of a
///        broken mesh); those polygons are left out
Polygons polygonsFromLoops(std::vector<Ring> loops, bool& valid);

/// The union of @p polygons (pairwise, in rounds). Inputs that Boost.Geometry refuses are
/// returned as they are.
Polygons unitePolygons(Polygons polygons);

/// @p polygons minus the union of @p cuts. Empty when Boost.Geometry refuses the input: a
/// surface that cannot be cut is dropped rather than kept whole.
Polygons subtractPolygons(const Polygons& polygons, Polygons cuts);

/// Area of the intersection of @p a and @p b [m^2]; infinity when Boost.Geometry refuses the
/// input (counted as overlapping, the conservative side for clearance).
double overlapArea(const Polygon2& a, const Polygon2& b);

}  // namespace surfaces
}  // namespace placement_samplers
