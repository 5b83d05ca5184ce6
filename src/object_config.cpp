#include "placement_samplers/object_config.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "placement_samplers/errors.hpp"

namespace placement_samplers {
namespace {

double positive(const ConfigNode& node) {
  const double v = node.asDouble();
  if (v <= 0.0) {
    std::ostringstream out;
    out << "expected a positive size in [m], got " << v;
    node.fail(out.str());
  }
  return v;
}

Shape parsePrimitive(const ConfigNode& node) {
  const ConfigNode& shapeNode = node.at("shape");
  const std::string& type = shapeNode.asString();
  if (type == "box") {
    node.checkKeys({"shape", "size", "horizontal_radius", "bottom_offset", "top_offset",
                    "init_orientation"});
    const ConfigNode& size = node.at("size");
    const Eigen::Vector3d s = size.asVector3();
    if ((s.array() <= 0.0).any()) {
      std::ostringstream out;
      out << "expected three positive extents [x, y, z] in [m], got [" << s.x() << ", " << s.y()
          << ", " << s.z() << "]";
      size.fail(out.str());
    }
    return Shape::box(s);
  }
  if (type == "cylinder" || type == "capsule") {
    node.checkKeys({"shape", "radius", "length", "horizontal_radius", "bottom_offset",
                    "top_offset", "init_orientation"});
    const double radius = positive(node.at("radius"));
    const double length = positive(node.at("length"));
    return type == "cylinder" ? Shape::cylinder(radius, length) : Shape::capsule(radius, length);
  }
  if (type == "sphere") {
    node.checkKeys({"shape", "radius", "horizontal_radius", "bottom_offset", "top_offset",
                    "init_orientation"});
    return Shape::sphere(positive(node.at("radius")));
  }
  shapeNode.fail("expected one of box, cylinder, sphere, capsule, got '" + type + "'");
}

}  // namespace

Eigen::Quaterniond parseQuaternion(const ConfigNode& node) {
  const std::vector<double> v = node.asNumbers(4);
  const Eigen::Quaterniond q(v[3], v[0], v[1], v[2]);
  if (std::abs(q.norm() - 1.0) > 1e-3) {
    std::ostringstream out;
    out << "expected a unit quaternion [x, y, z, w], got one of norm " << q.norm();
    node.fail(out.str());
  }
  return q.normalized();
}

void validateShape(const Shape& shape) {
  auto check = [](double v, const char* what) {
    if (!std::isfinite(v) || v <= 0.0) {
      std::ostringstream out;
      out << what << " must be finite and positive, got " << v;
      throw std::invalid_argument(out.str());
    }
  };
  switch (shape.type) {
    case ShapeType::Box:
      check(shape.size.x(), "box size x");
      check(shape.size.y(), "box size y");
      check(shape.size.z(), "box size z");
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
        throw std::invalid_argument("mesh has no vertices");
      }
      break;
  }
}

ObjectModel parseObject(const std::string& name, const ConfigNode& node) {
  if (!node.isMap()) {
    node.fail("expected a map with the object's shape and sizes, got " +
              std::string(ConfigNode::typeName(node.type())));
  }
  if (node.get("shape") == nullptr) {
    node.fail("missing required key 'shape' (box, cylinder, sphere or capsule)");
  }
  Shape shape = parsePrimitive(node);

  ObjectOverrides overrides;
  if (const ConfigNode* r = node.get("horizontal_radius")) {
    overrides.hasHorizontalRadius = true;
    overrides.horizontalRadius = r->asDouble();
    if (overrides.horizontalRadius < 0.0) {
      r->fail("expected a non-negative radius in [m]");
    }
  }
  if (const ConfigNode* b = node.get("bottom_offset")) {
    overrides.hasBottomOffset = true;
    overrides.bottomOffset = b->asVector3();
  }
  if (const ConfigNode* t = node.get("top_offset")) {
    overrides.hasTopOffset = true;
    overrides.topOffset = t->asVector3();
  }
  Eigen::Quaterniond init = Eigen::Quaterniond::Identity();
  if (const ConfigNode* q = node.get("init_orientation")) {
    init = parseQuaternion(*q);
  }
  std::vector<Shape> shapes{shape};
  return makeObject(name, std::move(shapes), init, overrides);
}

}  // namespace placement_samplers
