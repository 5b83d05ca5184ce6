#pragma once

// What support surface extraction collects from an object's shapes before merging and cutting
// (private to the core): up-facing planar pieces, and the parts that may stand on a surface or
// hang over it.

#include <Eigen/Geometry>
#include <array>
#include <functional>
#include <vector>

#include "geometry/surface_polygons.hpp"
#include "placement_samplers/geometry/shape.hpp"
#include "placement_samplers/geometry/support_surfaces.hpp"

namespace placement_samplers {
namespace surfaces {

/// Heights closer than this are one: coplanar facets, geometry level with a surface [m].
constexpr double kHeightTolerance = 1e-6;
/// A cylinder's cap is this inscribed regular polygon (area 0.9984 of the disc's).
constexpr int kCapVertices = 64;
/// Round shapes cut out of a surface as this circumscribed regular polygon (conservative).
constexpr int kCutVertices = 32;
/// Geometry with a coordinate beyond this is left out (no meaningful surface there) [m].
constexpr double kFarAway = 1e12;

/// The plane z = a x + b y + c.
struct Plane {
  double a = 0.0, b = 0.0, c = 0.0;
  double at(double x, double y) const { return a * x + b * y + c; }
};

/// An up-facing planar piece: a primitive's face or cap, or a group of a mesh's triangles
/// coplanar and joined by their edges.
struct Facet {
  Polygons polygons;       ///< its x-y projection
  Plane plane;             ///< a = b = 0 when horizontal
  bool horizontal = true;  ///< its heights differ by at most kHeightTolerance
  double zMax = 0.0;       ///< its highest point [m]
  int element = -1;        ///< the primitive (SurfaceParts::primitives) it is a face of, or -1
  Box2 box;                ///< of its polygons
};

/// A primitive as something that can stand on a surface or hang over it.
struct Obstacle {
  double zMin = 0.0, zMax = 0.0;  ///< its height extent [m]
  Ring footprint;                 ///< convex, containing its x-y projection
  Box2 box;                       ///< of the footprint
};

/// A mesh in the frame of the surfaces, vertices welded, degenerate triangles left out.
struct WorldMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside
  double zMin = 0.0, zMax = 0.0;
};

/// A mesh triangle whose x-y projection has area, as an obstacle (its footprint: the triangle).
struct TriangleObstacle {
  double zMin = 0.0, zMax = 0.0;
  Box2 box;
  int mesh = 0;      ///< index in SurfaceParts::meshes
  int triangle = 0;  ///< index in its WorldMesh::triangles
};

/// Everything collected from one object's shapes.
struct SurfaceParts {
  std::vector<Facet> facets;
  std::vector<Obstacle> primitives;
  std::vector<TriangleObstacle> triangles;
  std::vector<WorldMesh> meshes;
};

/// Adds a box's, cylinder's, sphere's or capsule's obstacle, and a box's faces or a cylinder's
/// caps whose outward normal has a z component of at least @p cosTolerance.
/// @param pose the shape's pose in the frame of the surfaces
void addPrimitive(const Shape& shape, const Eigen::Isometry3d& pose, double cosTolerance,
                  SurfaceParts& parts);

/// Adds a mesh: its welded copy, its triangles as obstacles, and facets made of its up-facing
/// triangles (normal from the winding, counter-clockwise = outward) grouped by plane and edges.
void addMesh(const Mesh& mesh, const Eigen::Isometry3d& pose, double cosTolerance,
             SurfaceParts& parts);

/// Facets of the up-facing triangles @p up (indices in @p mesh's triangles): grouped across
/// shared edges where coplanar (within kHeightTolerance), each group's boundary chained into
/// loops, outer and holes.
void addMeshFacets(const WorldMesh& mesh, std::vector<int> up, std::vector<Facet>& facets);

/// The region inside @p mesh at height @p height (its cross-section, from the loops that its
/// triangles crossing the height make). Open loops of an open mesh are left out; loops that do
/// not make valid polygons are replaced by their convex hulls (the region is cut out of
/// surfaces: larger is the safe side).
Polygons meshSection(const WorldMesh& mesh, double height);

/// Coplanar facets, merged into the same surfaces.
struct Cluster {
  std::vector<int> facets;  ///< indices in SurfaceParts::facets
  double zFirst = 0.0;      ///< its first facet's highest point
  double z = 0.0;           ///< its highest point: the surfaces' height [m]
};

/// Groups of the indices of @p boxes, joined where two boxes touch or overlap (within
/// kLinearTolerance) and @p joinable(a, b) says so; each group ascending, the groups in the
/// order of their first index.
std::vector<std::vector<int>> touchingGroups(const std::vector<Box2>& boxes,
                                             const std::function<bool(int, int)>& joinable);

/// Level facets whose heights are within kHeightTolerance of the lowest of them are one
/// cluster; tilted facets are one where their boxes touch and their planes are within
/// kHeightTolerance of each other over both boxes.
std::vector<Cluster> clusterFacets(const std::vector<Facet>& facets);

/// The surfaces of @p clusters: each cluster's polygons united, geometry standing on them cut
/// out, clearance, surfaces of less than SurfaceOptions::minArea dropped. Not sorted.
SurfaceSearch extractSurfaces(const SurfaceParts& parts, const std::vector<Cluster>& clusters,
                              const SurfaceOptions& options);

/// The counter-clockwise projection of triangle @p index of @p mesh.
Ring triangleFootprint(const WorldMesh& mesh, int index);

}  // namespace surfaces
}  // namespace placement_samplers
