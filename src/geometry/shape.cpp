#include "placement_samplers/geometry/shape.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"

namespace placement_samplers {
namespace {

/// Largest |c + cos(t) u + sin(t) v| over t: the farthest point of an ellipse from the origin in
/// the plane. Dense scan, then a golden-section refinement around the best sample; the function
/// of t has at most two maxima, so the refined value is exact to rounding.
double ellipseMaxNorm(const Eigen::Vector2d& c, const Eigen::Vector2d& u,
                      const Eigen::Vector2d& v) {
  auto norm = [&](double t) { return (c + std::cos(t) * u + std::sin(t) * v).norm(); };
  constexpr int kSamples = 256;
  constexpr double kStep = 2.0 * M_PI / kSamples;
  double best = -1.0;
  double bestT = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    const double t = i * kStep;
    const double n = norm(t);
    if (n > best) {
      best = n;
      bestT = t;
    }
  }
  double a = bestT - kStep;
  double b = bestT + kStep;
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int i = 0; i < 100 && b - a > 1e-15; ++i) {
    const double m1 = b - g * (b - a);
    const double m2 = a + g * (b - a);
    if (norm(m1) < norm(m2)) {
      a = m1;
    } else {
      b = m2;
    }
  }
  return std::max(best, norm(0.5 * (a + b)));
}

/// A unit vector orthogonal to @p axis, and the one completing the right-handed pair.
void orthonormalPair(const Eigen::Vector3d& axis, Eigen::Vector3d& e1, Eigen::Vector3d& e2) {
  e1 = axis.unitOrthogonal();
  e2 = axis.cross(e1);
}

Bounds boxBounds(const Eigen::Vector3d& half, const Eigen::Isometry3d& pose) {
  Bounds b{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 0.0};
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d corner((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                                 (i & 4) ? half.z() : -half.z());
    const Eigen::Vector3d p = pose * corner;
    b.bottomZ = std::min(b.bottomZ, p.z());
    b.topZ = std::max(b.topZ, p.z());
    b.horizontalRadius = std::max(b.horizontalRadius, p.head<2>().norm());
  }
  return b;
}

/// A disc of @p radius centred at @p centre, normal @p axis; or a segment of spheres (capsule).
Bounds cylinderBounds(double radius, double halfLength, const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d axis = pose.linear().col(2);
  const Eigen::Vector3d centre = pose.translation();
  const double zSpan = halfLength * std::abs(axis.z()) +
                       radius * std::sqrt(std::max(0.0, 1.0 - axis.z() * axis.z()));
  Eigen::Vector3d e1, e2;
  orthonormalPair(axis, e1, e2);
  double horizontal = 0.0;
  // The farthest point lies on one of the two rim circles (the norm is convex along the axis).
  for (double s : {-1.0, 1.0}) {
    const Eigen::Vector3d c = centre + s * halfLength * axis;
    horizontal = std::max(
        horizontal, ellipseMaxNorm(c.head<2>(), radius * e1.head<2>(), radius * e2.head<2>()));
  }
  return Bounds{centre.z() - zSpan, centre.z() + zSpan, horizontal};
}

Bounds capsuleBounds(double radius, double halfLength, const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d axis = pose.linear().col(2);
  const Eigen::Vector3d centre = pose.translation();
  const double zSpan = halfLength * std::abs(axis.z()) + radius;
  const double horizontal = std::max((centre + halfLength * axis).head<2>().norm(),
                                     (centre - halfLength * axis).head<2>().norm()) +
                            radius;
  return Bounds{centre.z() - zSpan, centre.z() + zSpan, horizontal};
}

/// True when @p pose keeps its z axis vertical (up or down) and its origin on the world z axis:
/// a turn about z, possibly upside down. A box, cylinder, sphere or capsule then has the bounds
/// it has unturned, which uprightBounds() gives exactly as robosuite's primitive objects do.
bool keepsAxisVertical(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d r = pose.linear();
  return r(0, 2) == 0.0 && r(1, 2) == 0.0 && r(2, 0) == 0.0 && r(2, 1) == 0.0 &&
         pose.translation().x() == 0.0 && pose.translation().y() == 0.0;
}

/// robosuite's numbers for a primitive whose axis is vertical, centred at height @p z, computed
/// as numpy computes them: bottom -size[2] / -size[1] / -size[0] / -(size[0] + size[1]) for a
/// box / cylinder / ball / capsule, and horizontal radius np.linalg.norm(size[0:2]) for a box
/// (sqrt of the dot product, x*x + y*y without FMA, as numpy's norm of a 1-D array is), the
/// radius for the others. A generic path (corners turned, a scan over the rim) can end one bit
/// off, and robosuite's boundary shrink and overlap test would then differ in the last bit.
Bounds uprightBounds(const Shape& shape, double z) {
  double halfHeight = 0.0;
  double radius = 0.0;
  switch (shape.type) {
    case ShapeType::Box: {
      const double hx = 0.5 * shape.size.x();
      const double hy = 0.5 * shape.size.y();
      halfHeight = 0.5 * shape.size.z();
      radius = std::sqrt(hx * hx + hy * hy);
      break;
    }
    case ShapeType::Cylinder:
      halfHeight = 0.5 * shape.length;
      radius = shape.radius;
      break;
    case ShapeType::Sphere:
      halfHeight = shape.radius;
      radius = shape.radius;
      break;
    case ShapeType::Capsule:
      halfHeight = shape.radius + 0.5 * shape.length;
      radius = shape.radius;
      break;
    case ShapeType::Mesh:
      throw std::invalid_argument("uprightBounds: a mesh has no closed form");
  }
  return Bounds{z - halfHeight, z + halfHeight, radius};
}

Bounds meshBounds(const Mesh& mesh, const Eigen::Isometry3d& pose) {
  Bounds b{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 0.0};
  for (const Eigen::Vector3d& v : mesh.vertices) {
    const Eigen::Vector3d p = pose * v;
    b.bottomZ = std::min(b.bottomZ, p.z());
    b.topZ = std::max(b.topZ, p.z());
    b.horizontalRadius = std::max(b.horizontalRadius, p.head<2>().norm());
  }
  return b;
}

}  // namespace

const char* shapeTypeName(ShapeType type) {
  switch (type) {
    case ShapeType::Box:
      return "box";
    case ShapeType::Cylinder:
      return "cylinder";
    case ShapeType::Sphere:
      return "sphere";
    case ShapeType::Capsule:
      return "capsule";
    case ShapeType::Mesh:
      return "mesh";
  }
  return "unknown";
}

void validateShape(const Shape& shape) {
  const std::string type = shapeTypeName(shape.type);
  auto check = [&](double v, const char* what) {
    if (!std::isfinite(v) || v <= 0.0) {
      std::ostringstream out;
      out << type << " " << what << " must be finite and positive, got " << v;
      throw ConfigError(out.str());
    }
    if (v > limits::kCoordinate) {
      std::ostringstream out;
      out << type << " " << what << " must be at most " << limits::kCoordinate << " m, got " << v;
      throw ConfigError(out.str());
    }
  };
  switch (shape.type) {
    case ShapeType::Box:
      check(shape.size.x(), "size x");
      check(shape.size.y(), "size y");
      check(shape.size.z(), "size z");
      break;
    case ShapeType::Cylinder:
    case ShapeType::Capsule:
      check(shape.radius, "radius");
      check(shape.length, "length");
      break;
    case ShapeType::Sphere:
      check(shape.radius, "radius");
      break;
    case ShapeType::Mesh:
      if (!shape.mesh || shape.mesh->vertices.empty()) {
        throw ConfigError("mesh has no vertices");
      }
      break;
  }
}

Shape Shape::box(const Eigen::Vector3d& size) {
  Shape s;
  s.type = ShapeType::Box;
  s.size = size;
  return s;
}

/// A shape given by a radius and a length (cylinder, sphere, capsule).
static Shape roundShape(ShapeType type, double radius, double length) {
  Shape s;
  s.type = type;
  s.radius = radius;
  s.length = length;
  return s;
}

Shape Shape::cylinder(double radius, double length) {
  return roundShape(ShapeType::Cylinder, radius, length);
}

Shape Shape::sphere(double radius) { return roundShape(ShapeType::Sphere, radius, 0.0); }

Shape Shape::capsule(double radius, double length) {
  return roundShape(ShapeType::Capsule, radius, length);
}

Bounds shapeBounds(const Shape& shape, const Eigen::Quaterniond& orientation) {
  const Eigen::Isometry3d pose = Eigen::Isometry3d(orientation) * shape.pose;
  if (shape.type != ShapeType::Mesh && keepsAxisVertical(pose)) {
    return uprightBounds(shape, pose.translation().z());
  }
  switch (shape.type) {
    case ShapeType::Box:
      return boxBounds(0.5 * shape.size, pose);
    case ShapeType::Cylinder:
      return cylinderBounds(shape.radius, 0.5 * shape.length, pose);
    case ShapeType::Sphere: {
      const Eigen::Vector3d c = pose.translation();
      return Bounds{c.z() - shape.radius, c.z() + shape.radius, c.head<2>().norm() + shape.radius};
    }
    case ShapeType::Capsule:
      return capsuleBounds(shape.radius, 0.5 * shape.length, pose);
    case ShapeType::Mesh:
      if (!shape.mesh || shape.mesh->vertices.empty()) {
        throw std::invalid_argument("mesh shape without vertices");
      }
      return meshBounds(*shape.mesh, pose);
  }
  throw std::invalid_argument("unknown shape type");
}

Bounds shapesBounds(const std::vector<Shape>& shapes, const Eigen::Quaterniond& orientation) {
  if (shapes.empty()) {
    throw std::invalid_argument("no collision geometry");
  }
  Bounds all = shapeBounds(shapes.front(), orientation);
  for (std::size_t i = 1; i < shapes.size(); ++i) {
    const Bounds b = shapeBounds(shapes[i], orientation);
    all.bottomZ = std::min(all.bottomZ, b.bottomZ);
    all.topZ = std::max(all.topZ, b.topZ);
    all.horizontalRadius = std::max(all.horizontalRadius, b.horizontalRadius);
  }
  return all;
}

}  // namespace placement_samplers
