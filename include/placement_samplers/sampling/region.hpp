#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "placement_samplers/sampling/random.hpp"

namespace placement_samplers {

/// A planar shape: a uniform sampler's region or a keep-out zone, in x-y [m] relative to the
/// sampler's reference (or to the world origin for a keep-out zone in the world frame).
struct RegionShape {
  enum class Kind { Rectangle, RotatedRectangle, Disk, Annulus, Polygon };
  Kind kind = Kind::Rectangle;
  Eigen::Vector2d xRange = Eigen::Vector2d::Zero();  ///< Rectangle: [min, max] [m]
  Eigen::Vector2d yRange = Eigen::Vector2d::Zero();  ///< Rectangle: [min, max] [m]
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< RotatedRectangle, Disk, Annulus [m]
  Eigen::Vector2d size = Eigen::Vector2d::Zero();    ///< RotatedRectangle: full extents [m]
  double yaw = 0.0;          ///< RotatedRectangle: its x axis from the frame's x axis [rad]
  double radius = 0.0;       ///< Disk: radius; Annulus: outer radius [m]
  double innerRadius = 0.0;  ///< Annulus [m]
  std::vector<Eigen::Vector2d> vertices;  ///< Polygon: a simple polygon, either winding [m]

  static RegionShape rectangle(const Eigen::Vector2d& x, const Eigen::Vector2d& y);
  static RegionShape rotatedRectangle(const Eigen::Vector2d& centre, const Eigen::Vector2d& size,
                                      double yaw);
  static RegionShape disk(const Eigen::Vector2d& centre, double radius);
  static RegionShape annulus(const Eigen::Vector2d& centre, double inner, double outer);
  static RegionShape polygon(std::vector<Eigen::Vector2d> vertices);
};

/// The most vertices a polygon may have (its checks cost vertices^2).
constexpr std::size_t kMaxPolygonVertices = 1000;

/// "rectangle", "rotated_rectangle", "disk", "annulus" or "polygon": the configuration's names.
const char* shapeKindName(RegionShape::Kind kind);

/// What is wrong with a shape: the parameter (as in the configuration: "inner_radius",
/// "vertices") and why.
struct ShapeProblem {
  std::string key;
  std::string message;
};

/// The first problem of @p shape (a non-finite or unbounded value, a negative size, inner radius
/// >= outer radius, fewer than 3 vertices, a repeated vertex, a self-intersecting or flat
/// polygon), or nothing.
std::optional<ShapeProblem> findShapeProblem(const RegionShape& shape);

/// True when @p p lies in the closed shape.
bool shapeContains(const RegionShape& shape, const Eigen::Vector2d& p);

/// The distance from @p p to the shape, 0 inside [m].
double distanceToShape(const RegionShape& shape, const Eigen::Vector2d& p);

/// The signed distance from @p p to the shape's boundary: positive inside, negative outside
/// [m]. It changes by at most |dp| when p moves by dp (free_space prunes whole cells with it).
double shapeDepth(const RegionShape& shape, const Eigen::Vector2d& p);

/// The shape's axis-aligned bounding box [m].
void shapeBounds(const RegionShape& shape, Eigen::Vector2d& lo, Eigen::Vector2d& hi);

/// The shape as triangles (three corners each) in its frame [m], disks and annuli as
/// @p segments-gons: for display.
std::vector<Eigen::Vector2d> shapeTriangles(const RegionShape& shape, int segments = 48);

/// True when the polygon's vertices turn one way only (collinear ones allowed).
bool isConvexPolygon(const std::vector<Eigen::Vector2d>& vertices);

/// Uniform draws over a valid shape inset by a margin (the positions whose disk of that radius
/// stays inside the shape). Exact shapes (rectangles, disks, annuli, convex polygons) are inset
/// in closed form and every draw is inside; a non-convex polygon draws over the whole polygon
/// and accepts() rejects the draws closer than the margin to its boundary.
class RegionDraw {
 public:
  /// @return nothing when the inset leaves no room (the inset shape has no area; for
  /// rectangles, disks and annuli a zero width is room enough, as for robosuite's ranges)
  /// @param shape a shape without findShapeProblem()
  /// @param margin the inset [m], >= 0
  static std::optional<RegionDraw> make(const RegionShape& shape, double margin);

  /// One candidate from @p engine (draw order: README, "Region shapes") [m].
  Eigen::Vector2d draw(Engine& engine) const;
  /// False for a candidate of a non-convex polygon closer than the margin to its boundary.
  bool accepts(const Eigen::Vector2d& p) const;
  /// The area that draw() covers [m^2] (the whole polygon for a non-convex one).
  double drawnArea() const { return area_; }
  /// True when every draw is accepted.
  bool exact() const { return !rejects_; }

 private:
  RegionShape::Kind kind_ = RegionShape::Kind::Rectangle;
  Eigen::Vector2d a_ = Eigen::Vector2d::Zero();  // rectangle: x range; rotated: half extents
  Eigen::Vector2d b_ = Eigen::Vector2d::Zero();  // rectangle: y range; rotated: cos, sin yaw
  Eigen::Vector2d centre_ = Eigen::Vector2d::Zero();
  double inner2_ = 0.0;  // annulus, disk: squared radii
  double outer2_ = 0.0;
  std::vector<Eigen::Vector2d> triangles_;  // polygon: three corners each
  std::vector<double> cumulative_;          // polygon: running sums of the triangles' areas
  std::vector<Eigen::Vector2d> outline_;    // non-convex polygon: its vertices, for accepts()
  double margin_ = 0.0;
  double area_ = 0.0;
  bool rejects_ = false;
};

/// A keep-out zone: no object's centre (with ensure_object_boundary_in_range, no part of its
/// horizontal disk) may be in it.
struct KeepOutZone {
  RegionShape shape;
  bool world = false;  ///< shape in the world frame; else relative to the sampler's reference
};

/// True when a disk of radius @p margin at @p p reaches into @p zone (touching its edge does
/// not) [m].
inline bool keepOutBlocks(const KeepOutZone& zone, const Eigen::Vector2d& p, double margin) {
  return shapeContains(zone.shape, p) || distanceToShape(zone.shape, p) < margin;
}

}  // namespace placement_samplers
