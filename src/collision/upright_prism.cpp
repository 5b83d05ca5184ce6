#include "collision/upright_prism.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace placement_samplers {
namespace detail {
namespace {

/// Tilt (sine) below which a shape counts as upright: a rotation built from a turn about z
/// carries rounding of about 1e-16 in these entries; the error it makes here is far below the
/// tolerance the checker decides with.
constexpr double kUprightTolerance = 1e-12;

double rectangleRectangle(const UprightPrism& a, const UprightPrism& b) {
  // Separating axes: the sides' normals of both. The largest gap is the signed distance when
  // they overlap (the penetration depth of two convex polygons) and a lower bound when apart.
  const Eigen::Vector2d d = b.centre - a.centre;
  const Eigen::Vector2d axes[4] = {a.axisX, a.axisY, b.axisX, b.axisY};
  double gap = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& n : axes) {
    const double reachA = a.halfX * std::abs(n.dot(a.axisX)) + a.halfY * std::abs(n.dot(a.axisY));
    const double reachB = b.halfX * std::abs(n.dot(b.axisX)) + b.halfY * std::abs(n.dot(b.axisY));
    gap = std::max(gap, std::abs(n.dot(d)) - reachA - reachB);
  }
  return gap;
}

double rectangleDisk(const UprightPrism& rect, const UprightPrism& disk) {
  const Eigen::Vector2d d = disk.centre - rect.centre;
  const double qx = std::abs(d.dot(rect.axisX)) - rect.halfX;
  const double qy = std::abs(d.dot(rect.axisY)) - rect.halfY;
  const double outside = std::hypot(std::max(qx, 0.0), std::max(qy, 0.0));
  return outside + std::min(std::max(qx, qy), 0.0) - disk.radius;
}

}  // namespace

UprightPrism uprightPrism(const Shape& shape, const Eigen::Isometry3d& pose) {
  UprightPrism p;
  const Eigen::Matrix3d& r = pose.linear();
  if (std::abs(r(2, 0)) > kUprightTolerance || std::abs(r(2, 1)) > kUprightTolerance ||
      std::abs(r(0, 2)) > kUprightTolerance || std::abs(r(1, 2)) > kUprightTolerance) {
    return p;
  }
  double halfZ = 0.0;
  if (shape.type == ShapeType::Box) {
    p.kind = UprightPrism::Kind::Rectangle;
    p.axisX = Eigen::Vector2d(r(0, 0), r(1, 0));
    p.axisY = Eigen::Vector2d(r(0, 1), r(1, 1));
    p.halfX = 0.5 * shape.size.x();
    p.halfY = 0.5 * shape.size.y();
    halfZ = 0.5 * shape.size.z();
  } else if (shape.type == ShapeType::Cylinder) {
    p.kind = UprightPrism::Kind::Disk;
    p.radius = shape.radius;
    halfZ = 0.5 * shape.length;
  } else {
    return p;
  }
  const Eigen::Vector3d& t = pose.translation();
  p.centre = t.head<2>();
  p.zMin = t.z() - halfZ;
  p.zMax = t.z() + halfZ;
  return p;
}

SignedDistanceBounds prismDistance(const UprightPrism& a, const UprightPrism& b) {
  using Kind = UprightPrism::Kind;
  double planar = 0.0;
  bool planarExact = true;
  if (a.kind == Kind::Disk && b.kind == Kind::Disk) {
    planar = (b.centre - a.centre).norm() - a.radius - b.radius;
  } else if (a.kind == Kind::Rectangle && b.kind == Kind::Rectangle) {
    planar = rectangleRectangle(a, b);
    planarExact = planar <= 0.0;
  } else if (a.kind == Kind::Rectangle) {
    planar = rectangleDisk(a, b);
  } else {
    planar = rectangleDisk(b, a);
  }
  const double vertical = std::max(b.zMin - a.zMax, a.zMin - b.zMax);
  // A swept shape is a product of its 2-D shape and an interval: apart in both, the distances
  // add in squares; overlapping in one, the other decides; overlapping in both, the shallower.
  const double value =
      planar > 0.0 && vertical > 0.0 ? std::hypot(planar, vertical) : std::max(planar, vertical);
  return {value, planarExact ? value : std::numeric_limits<double>::infinity()};
}

}  // namespace detail
}  // namespace placement_samplers
