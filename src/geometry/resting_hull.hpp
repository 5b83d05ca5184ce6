#pragma once
// Resting poses through the convex hull of an object's geometry: the share of drop directions
// each hull face takes, which faces are stable and where the others topple. Private to the core;
// restingPoses() turns it into poses.

#include <Eigen/Core>
#include <vector>

#include "geometry/convex_hull.hpp"
#include "placement_samplers/geometry/resting_poses.hpp"
#include "placement_samplers/geometry/shape.hpp"

namespace placement_samplers::detail {

/// Segments of a full circle in the polygons and polyhedra that stand for cylinders, spheres and
/// capsules in the hull (5.6 deg: the true surface lies at most 0.12 % of the radius outside).
constexpr int kCircleSegments = 64;

/// The points whose convex hull stands for an object, and what each one samples.
struct HullPoints {
  /// A circle of a cylinder's rim or a sphere (a sphere, a capsule's cap) in the object frame.
  struct Curve {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< a rim's axis
    double radius = 0.0;
    bool sphere = false;
  };
  std::vector<Eigen::Vector3d> points;
  /// Per point: the curve it lies on, or -1 for a corner that is exact (a box's, a mesh vertex).
  std::vector<int> curve;
  std::vector<Curve> curves;
};

/// Box corners, mesh vertices, and cylinders, spheres and capsules as inscribed polygons and
/// polyhedra of kCircleSegments segments, in the object frame.
/// @throw std::invalid_argument when there would be more than kMaxHullPoints
HullPoints hullPoints(const std::vector<Shape>& shapes);

/// The hull faces of an object with their shares of the drop directions and where they lead.
struct RestingHull {
  /// What a face's share ends on: a stable face, or a set of faces the object rolls or rocks on
  /// without a stable face among them (a cylinder's side, tiny faces around a rounded bottom).
  struct Sink {
    int face = -1;  ///< the stable face; for a rolling sink the one with the lowest centre of mass
    bool rolling = false;
    double share = 0.0;  ///< the shares of the faces that end here
  };
  HullPoints input;
  ConvexHull hull;
  Eigen::Vector3d centreOfMass = Eigen::Vector3d::Zero();
  std::vector<double> share;   ///< per face: its solid angle from the centre of mass over 4 pi
  std::vector<double> height;  ///< per face: the centre of mass's distance from its plane [m]
  /// Per face: how far inside the face's true contact with the support the centre of mass
  /// projects [m] (negative: outside; -infinity: the contact is a point or a line, as on a
  /// polygon that samples a sphere or a cylinder's side).
  std::vector<double> depth;
  std::vector<int> next;  ///< per face: the face it topples onto, -1 when stable
  std::vector<int> sink;  ///< per face: the index of its sink in sinks
  std::vector<Sink> sinks;
};

/// The hull analysis of @p shapes (one object's geometry in its frame): a face is stable when
/// depth >= options.margin (and > 0); an unstable one topples across the edge of its polygon
/// the centre of mass lies farthest beyond (or is nearest to, when inside). Chains of faces that
/// come back to a face end in a rolling sink; rolling sinks whose faces touch are one.
/// @throw std::invalid_argument when the hull has no volume (flat or collinear geometry) or has
///   too many points
RestingHull restingHull(const std::vector<Shape>& shapes, const RestingOptions& options);

/// The solid angle of the triangle @p a, @p b, @p c (vectors from the viewpoint) [sr], positive
/// when they go counter-clockwise seen from the viewpoint's far side (Van Oosterom and Strackee).
double triangleSolidAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                          const Eigen::Vector3d& c);

}  // namespace placement_samplers::detail
