#pragma once
// The convex hull of a point set in 3-d (quickhull with face merging), for the resting poses and
// the mass of meshes. Private to the core.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

namespace placement_samplers::detail {

/// A convex hull: its faces are convex polygons, stored one after another.
struct ConvexHull {
  /// Face f's corners are start[f] to start[f + 1] - 1 (start has one entry more than faces).
  std::vector<int> start{0};
  /// Per corner: the index of its input point; a face's corners go counter-clockwise seen from
  /// outside.
  std::vector<int> vertices;
  /// Per corner: the face across the edge from this corner to the face's next one.
  std::vector<int> neighbours;
  /// Per face: its outward unit normal.
  std::vector<Eigen::Vector3d> normals;
  /// Points within this of a face's plane count as on it, and adjacent faces closer than it to
  /// coplanar are one face [m].
  double tolerance = 0.0;

  std::size_t faceCount() const { return normals.size(); }
  int cornerCount(std::size_t f) const { return start[f + 1] - start[f]; }
};

/// The most points convexHull() takes: it bounds the time and the memory.
constexpr std::size_t kMaxHullPoints = 1000000;

/// The convex hull of @p points. Coplanar neighbours (within ConvexHull::tolerance: 1e-6 of the
/// points' extent, so that the flat sides of a mesh stored in single precision come out as one
/// face each) are merged into polygons; points on an edge or inside a face are not vertices.
/// @throw std::invalid_argument when the points span no volume (fewer than four, all on a line or
///   a plane), are not finite, or are more than kMaxHullPoints
ConvexHull convexHull(const std::vector<Eigen::Vector3d>& points);

/// The tolerance convexHull() works with for @p points [m]: 1e-6 of their extent (the diagonal
/// of their bounding box), and never below what rounding makes of their coordinates.
double hullTolerance(const std::vector<Eigen::Vector3d>& points);

/// The convex hull of a closed triangle mesh that is convex already, in linear time: its
/// triangles, neighbours coplanar within hullTolerance() merged into polygons. std::nullopt when
/// the mesh is not such a surface (convexHull() then takes its points): an edge without exactly
/// one opposite, a vertex no triangle uses, more than one piece or a hole (V - E + F != 2), or
/// a vertex whose neighbours do not all lie on or below the planes of its triangles. A closed
/// surface of the sphere's topology that is convex at every vertex bounds a convex body.
/// @param triangles indices into @p points, counter-clockwise seen from outside
std::optional<ConvexHull> convexMeshHull(const std::vector<Eigen::Vector3d>& points,
                                         const std::vector<Eigen::Vector3i>& triangles);

/// Volume [m^3] and centroid [m] of the solid a hull bounds (@p points as given to convexHull),
/// and when @p spread is given, its second moment about the centroid, the integral of
/// (x - centroid)(x - centroid)^T over the solid [m^5].
void hullVolume(const ConvexHull& hull, const std::vector<Eigen::Vector3d>& points, double& volume,
                Eigen::Vector3d& centroid, Eigen::Matrix3d* spread = nullptr);

}  // namespace placement_samplers::detail
