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
  /// A face is stable when the centre of mass projects inside it by at least this [m]
  /// (inside the face's true contact with the support, for polygons standing for round shapes).
  double margin = 1e-3;
  /// Also list the neutral poses that roll (a cylinder, a capsule on its side).
  bool allowRolling = false;
};

/// The centre of mass of @p shapes in their frame under a uniform density, as the physics'
/// MuJoCo model has it [m]: each shape weighs its own volume (overlaps count twice); a mesh is
/// its vertices' convex hull, centred at the hull's centroid and weighed, as MuJoCo 2.2.2 does,
/// by the volume of the box with the hull's inertia (a flat mesh weighs nothing).
/// @throw std::invalid_argument when @p shapes is empty or encloses no volume
Eigen::Vector3d centreOfMass(const std::vector<Shape>& shapes);

/// The resting poses of @p shapes (one object's collision geometry, in its frame), most probable
/// first (ties, to 1e-12: by their normals' x, then y, then z). Primitives exact (a box: its six
/// faces; a cylinder: its two caps, and its side when rolling is allowed; a capsule: its side
/// when rolling is allowed; a sphere: none), others through the convex hull of their vertices
/// (cylinders, spheres and capsules as inscribed 64-gons), with each unstable face's share
/// passed on to the face it topples onto (docs/design.md, "Resting poses"). Shares that end
/// rolling (on the polygons of a round side, or on faces too small for the margin) make one
/// rolling pose each with RestingOptions::allowRolling, and are dropped otherwise; the others
/// are renormalised. An object with no stable face (a sphere) has none: the caller keeps its
/// upright pose. Deterministic: the same shapes give the same poses, bit for bit.
/// @throw std::invalid_argument for geometry that spans no volume (a flat or straight mesh),
///   more than a million hull points, or a negative or non-finite margin
std::vector<RestingPose> restingPoses(const std::vector<Shape>& shapes,
                                      const RestingOptions& options = RestingOptions());

}  // namespace placement_samplers
