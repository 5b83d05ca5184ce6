#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "placement_samplers/geometry/shape.hpp"

namespace placement_samplers {

/// A pose in which an object rests stably on a horizontal support: one face of its convex hull
/// down (README, "Resting poses").
struct RestingPose {
  /// The rotation of the object frame that puts the face down (its outward normal along -z);
  /// about z it is fixed by turning the object's own x axis as little as possible. Placing the
  /// object applies the sampler's yaw after it.
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  /// The quasi-static chance of coming to rest on this face when dropped in a uniformly random
  /// orientation; the poses of an object sum to 1 (before min_probability drops any).
  double probability = 0.0;
  /// The face's outward unit normal in the object frame.
  Eigen::Vector3d normal = -Eigen::Vector3d::UnitZ();
  /// robosuite's numbers in this pose (shapesBounds() under @ref orientation) [m].
  Bounds bounds;
  /// True for a neutral pose that rolls (a cylinder or capsule on its side), listed only with
  /// RestingOptions::allowRolling.
  bool rolling = false;
};

struct RestingOptions {
  /// A face is stable when the centre of mass projects inside it by at least this [m].
  double margin = 1e-3;
  /// Also list the neutral poses that roll (a cylinder, a capsule on its side).
  bool allowRolling = false;
};

/// The centre of mass of @p shapes in their frame under a uniform density, as the physics'
/// mass model computes it (each shape's own volume: overlaps count twice) [m].
Eigen::Vector3d centreOfMass(const std::vector<Shape>& shapes);

/// The resting poses of @p shapes (one object's collision geometry, in its frame), most probable
/// first (ties: the order of their normals' x, y, z). Primitives exact (a box: its six faces; a
/// cylinder: its two caps, and its side when rolling is allowed; a sphere: none), others through
/// the convex hull of their vertices (cylinders and spheres as inscribed polygons), with each
/// unstable face's share passed on to the face it topples onto. An object with no stable face
/// (a sphere) has none: the caller keeps its upright pose.
std::vector<RestingPose> restingPoses(const std::vector<Shape>& shapes,
                                      const RestingOptions& options = RestingOptions());

}  // namespace placement_samplers
