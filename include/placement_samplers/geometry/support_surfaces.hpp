#pragma once

#include <Eigen/Geometry>
#include <limits>
#include <vector>

#include "placement_samplers/geometry/shape.hpp"

namespace placement_samplers {

/// A flat, up-facing part of an object's collision geometry that other objects can stand on: a
/// shelf board, a bin's floor, a counter around its sink, a box's top.
struct SupportSurface {
  /// Height [m] in the frame the shapes were posed in. A group of facets tilted within the
  /// normal tolerance takes its highest point, so that nothing placed on it starts inside it;
  /// its outline is its projection on x-y.
  double z = 0.0;
  /// The outline in x-y [m], counter-clockwise, no vertex repeated, collinear vertices removed.
  std::vector<Eigen::Vector2d> outer;
  /// Holes (a sink in a counter, the footprint of a wall standing on a floor), clockwise [m].
  std::vector<std::vector<Eigen::Vector2d>> holes;
  double area = 0.0;  ///< the outline's area minus the holes' [m^2]
  /// Free height above the surface up to the same geometry above it (the next board), its
  /// smallest value over the surface [m]; infinity when nothing is above.
  double clearance = std::numeric_limits<double>::infinity();
};

/// What counts as a support surface.
struct SurfaceOptions {
  /// Facets whose normal is within this angle of +z [rad].
  double normalTolerance = 0.1;
  /// Surfaces of less area are dropped [m^2].
  double minArea = 0.0025;
  /// Geometry that begins less than this above a surface stands on it (a wall on a floor):
  /// its footprint is cut out of the surface instead of bounding its clearance [m].
  double standingGap = 1e-3;
};

/// The result of findSupportSurfaces().
struct SurfaceSearch {
  /// Sorted by z (lowest first), then by the x, then the y of the outline's lowest-x vertex:
  /// their indices are those a configuration's `select` names.
  std::vector<SupportSurface> surfaces;
  /// The largest area of a surface dropped for SurfaceOptions::minArea, 0 when none [m^2]
  /// (for the message that no surface is large enough).
  double largestDroppedArea = 0.0;
};

/// The support surfaces of @p shapes (one object's collision geometry) placed at @p pose, in
/// the frame of @p pose:
/// - facets: boxes' faces and cylinders' caps whose outward normal is within
///   SurfaceOptions::normalTolerance of +z (a cap as the inscribed regular 64-gon, so every
///   point of it is on the cap: 0.9984 of the disc's area), and meshes' triangles likewise
///   (normal from the winding, counter-clockwise seen from outside). Spheres and capsules have
///   none.
/// - merging: facets within 1e-6 m of one plane that touch become one polygon, holes kept (a
///   counter's sink); level facets within 1e-6 m in height all take the highest. A mesh's
///   triangles are joined through their shared edges (vertices in one 1e-9 m cell welded), so
///   that a mesh of 100,000 triangles needs no polygon union per triangle.
/// - standing geometry: every other part that reaches more than 1e-6 m above a surface and
///   begins less than SurfaceOptions::standingGap above it (a bin's wall on its floor, a panel
///   through a shelf board) is cut out: a primitive as the convex hull of its projection (round
///   ones by circumscribed 32-gons), a mesh triangle as its projection, and a mesh's
///   cross-section just above the surface (for walls whose own projection has no area).
/// - clearance: how far above the surface the lowest part begins among those beginning at
///   least standingGap above it whose footprints overlap it (with area: touching edges do not
///   count), footprints as above.
/// Cuts and clearance take whole parts, so they err on the side of less room. Surfaces of less
/// than SurfaceOptions::minArea are dropped. Degenerate input is no error: degenerate triangles
/// and loops are left out, geometry beyond 1e12 m ignored, meshes' broken groups (folds,
/// non-manifold edges) rebuilt from their triangles, open loops of open meshes' cross-sections
/// left out.
SurfaceSearch findSupportSurfaces(const std::vector<Shape>& shapes, const Eigen::Isometry3d& pose,
                                  const SurfaceOptions& options = SurfaceOptions());

/// @p surface turned by @p yaw about the z axis, then moved by @p translation (a placed object's
/// surfaces from those found at its origin) [rad], [m].
SupportSurface movedSurface(const SupportSurface& surface, double yaw,
                            const Eigen::Vector3d& translation);

}  // namespace placement_samplers
