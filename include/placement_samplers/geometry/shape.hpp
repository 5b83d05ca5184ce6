#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

namespace placement_samplers {

/// A triangle mesh in its own frame [m], already scaled.
struct Mesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  std::string source;  ///< where it was read from, for messages and markers
};

enum class ShapeType { Box, Cylinder, Sphere, Capsule, Mesh };

/// Name of a shape type as written in configurations ("box", "cylinder", ...).
const char* shapeTypeName(ShapeType type);

/// One collision element of an object, in the object's frame.
/// Cylinders and capsules have their axis along the local z axis, centred on the origin.
struct Shape {
  ShapeType type = ShapeType::Box;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< box: full extents [m]
  double radius = 0.0;                             ///< cylinder, sphere, capsule [m]
  double length = 0.0;  ///< cylinder: full length; capsule: distance between cap centres [m]
  std::shared_ptr<const Mesh> mesh;                        ///< mesh only
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< in the object frame

  static Shape box(const Eigen::Vector3d& size);
  static Shape cylinder(double radius, double length);
  static Shape sphere(double radius);
  static Shape capsule(double radius, double length);
};

/// The one rule for a shape's sizes [m]: finite, positive and at most limits::kCoordinate;
/// a mesh must have vertices. Used for YAML, URDF and MJCF objects and request fixtures.
/// @throw ConfigError naming the size, e.g. "cylinder radius must be finite and positive, got 0"
void validateShape(const Shape& shape);

/// robosuite's three numbers for a set of shapes seen from a rotated object frame.
struct Bounds {
  double bottomZ = 0.0;           ///< lowest z of the geometry relative to the origin [m]
  double topZ = 0.0;              ///< highest z [m]
  double horizontalRadius = 0.0;  ///< largest x-y distance from the origin [m]
};

/// Exact bounds of @p shape after rotating the object frame by @p orientation.
Bounds shapeBounds(const Shape& shape, const Eigen::Quaterniond& orientation);

/// Bounds of all @p shapes (their union) under @p orientation.
/// @throw std::invalid_argument when @p shapes is empty
Bounds shapesBounds(const std::vector<Shape>& shapes, const Eigen::Quaterniond& orientation);

}  // namespace placement_samplers
