#pragma once

// Internal to the core library: an exact test for upright boxes and cylinders that decides most
// pairs before FCL is asked. Not installed.

#include <Eigen/Geometry>

#include "placement_samplers/geometry/shape.hpp"

namespace placement_samplers {
namespace detail {

/// A box turned about the world z axis only, or a cylinder whose axis is the world z axis: a
/// convex 2-D shape (rectangle or disk) swept over a z interval.
struct UprightPrism {
  enum class Kind { None, Rectangle, Disk };
  Kind kind = Kind::None;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< world x-y [m]
  Eigen::Vector2d axisX = Eigen::Vector2d::UnitX();  ///< rectangle: unit direction of its x side
  Eigen::Vector2d axisY = Eigen::Vector2d::UnitY();  ///< rectangle: unit direction of its y side
  double halfX = 0.0;                                ///< rectangle: half extent along axisX [m]
  double halfY = 0.0;                                ///< rectangle: half extent along axisY [m]
  double radius = 0.0;                               ///< disk [m]
  double zMin = 0.0;                                 ///< world z interval [m]
  double zMax = 0.0;
};

/// The prism of @p shape at world pose @p pose; Kind::None when the shape is not a box or a
/// cylinder, or is tilted out of upright by more than rounding.
UprightPrism uprightPrism(const Shape& shape, const Eigen::Isometry3d& pose);

/// Bounds on the signed distance of two prisms [m]: the distance when apart, minus the
/// penetration depth when they overlap. Exact (lower == upper) except for two rectangles apart
/// in x-y, where the separating-axis gap is only a lower bound and upper is +infinity.
struct SignedDistanceBounds {
  double lower;
  double upper;
};

/// Both prisms must have a kind other than None.
SignedDistanceBounds prismDistance(const UprightPrism& a, const UprightPrism& b);

}  // namespace detail
}  // namespace placement_samplers
