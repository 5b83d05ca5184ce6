#include "placement_samplers/config/object_config.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "config/builder_parts.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/geometry/mjcf_geometry.hpp"
#include "placement_samplers/text.hpp"
#include "placement_samplers/geometry/unit_quaternion.hpp"
#include "placement_samplers/geometry/urdf_geometry.hpp"

namespace placement_samplers {
namespace {

/// Keys of an object besides its shape's: what the offsets and orientation of the whole are.
const std::vector<std::string> kObjectKeys{"horizontal_radius", "bottom_offset", "top_offset",
                                           "init_orientation", "density"};
/// Keys of one part of a composite object besides its shape's: its pose in the object frame.
const std::vector<std::string> kPartKeys{"position", "orientation"};

/// @p shapeKeys followed by @p context: the keys a shape's map may hold.
void checkShapeKeys(const ConfigNode& node, std::vector<std::string> shapeKeys,
                    const std::vector<std::string>& context) {
  shapeKeys.insert(shapeKeys.end(), context.begin(), context.end());
  node.checkKeys(shapeKeys);
}

/// @p shape checked by validateShape(), an error pointing at @p node.
Shape checked(Shape shape, const ConfigNode& node) {
  try {
    validateShape(shape);
  } catch (const ConfigError& e) {
    node.fail(e.what());
  }
  return shape;
}

/// Why @p shapes under @p orientation reach beyond limits::kCoordinate from the origin (or are
/// not finite), or "" when they do not: a mesh's vertices, a URDF's joint origins can be
/// anything, and the derived offsets end up in every pose.
std::string geometryProblem(const std::vector<Shape>& shapes,
                            const Eigen::Quaterniond& orientation) {
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const Shape& shape = shapes[i];
    const Bounds b = shapeBounds(shape, orientation);
    // Each compared on its own: a comparison with NaN is false.
    const bool inside = std::abs(b.bottomZ) <= limits::kCoordinate &&
                        std::abs(b.topZ) <= limits::kCoordinate &&
                        b.horizontalRadius <= limits::kCoordinate;
    if (!shape.pose.matrix().allFinite() || !inside) {
      std::ostringstream out;
      out << "its geometry (" << shapeTypeName(shape.type) << " " << i << ") must lie within "
          << limits::kCoordinate << " m of its origin, got bottom " << b.bottomZ << ", top "
          << b.topZ << ", horizontal radius " << b.horizontalRadius;
      return out.str();
    }
  }
  return "";
}

Shape parseMesh(const std::string& name, const ConfigNode& node, MeshLoader& meshes,
                const std::vector<std::string>& context) {
  checkShapeKeys(node, {"shape", "mesh", "scale"}, context);
  const ConfigNode& uri = node.at("mesh");
  const std::string& uriText = uri.asString();
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  if (const ConfigNode* s = node.get("scale")) {
    scale = s->asVector3();
    if ((scale.array() <= 0.0).any()) {
      s->fail("expected three positive scale factors [sx, sy, sz]");
    }
  }
  Shape shape;
  shape.type = ShapeType::Mesh;
  try {
    shape.mesh = meshes.load(uriText, scale);
  } catch (const ConfigError& e) {
    uri.fail("object " + quoteText(name) + ": " + e.what());
  }
  return shape;
}

/// The shapes of a `urdf_file` or `urdf_param` object.
std::vector<Shape> parseUrdf(const std::string& name, const ConfigNode& node,
                             const BuildOptions& options, MeshLoader& meshes) {
  node.checkKeys({"urdf_file", "urdf_param", "link", "horizontal_radius", "bottom_offset",
                  "top_offset", "init_orientation", "density"});
  const ConfigNode* file = node.get("urdf_file");
  const ConfigNode* param = node.get("urdf_param");
  if (file != nullptr && param != nullptr) {
    node.fail("give either urdf_file or urdf_param, not both");
  }
  const ConfigNode& source = file != nullptr ? *file : *param;
  std::string link;
  if (const ConfigNode* l = node.get("link")) {
    link = l->asString();
    if (link.empty()) {
      l->fail("expected a link name");
    }
  }
  const std::string object = "object " + quoteText(name) + ": ";
  std::string text;
  std::string label;
  std::string meshBase;
  if (file != nullptr) {
    const std::string& uri = file->asString();
    std::string path;
    try {
      path = meshes.resolve(uri);
    } catch (const ConfigError& e) {
      file->fail(object + "urdf_file " + e.what());
    }
    label = "urdf_file " + quoteText(uri) + (path != uri ? " (" + escapeText(path) + ")" : "");
    try {
      text = readTextFile(path);
    } catch (const ConfigError& e) {
      file->fail(object + label + ": " + e.what());
    }
    // A relative mesh path in a URDF file is relative to the file.
    meshBase = std::filesystem::path(path).parent_path().string();
  } else {
    const std::string& paramName = param->asString();
    label = "urdf_param " + quoteText(paramName);
    if (!options.urdfParam) {
      param->fail(object + "urdf_param is only available in the node (use urdf_file here)");
    }
    try {
      text = options.urdfParam(paramName);
    } catch (const std::exception& e) {
      param->fail(object + label + ": " + e.what());
    }
  }
  try {
    return urdfCollisionShapes(text, link, meshes, meshBase);
  } catch (const ConfigError& e) {
    source.fail(object + label + ": " + e.what());
  }
}

/// @p mjcf with "@p label: " before each warning.
MjcfObject labelWarnings(MjcfObject mjcf, const std::string& label) {
  for (std::string& warning : mjcf.warnings) {
    warning = label + ": " + warning;
  }
  return mjcf;
}

/// The collision geometry and sites of an `mjcf_file` object (robosuite's MujocoXMLObject).
MjcfObject parseMjcf(const std::string& name, const ConfigNode& node, const BuildOptions& options,
                     MeshLoader& meshes) {
  const std::string object = "object " + quoteText(name) + ": ";
  if (const ConfigNode* param = node.get("mjcf_param")) {
    std::vector<std::string> keys{"mjcf_param"};
    keys.insert(keys.end(), kObjectKeys.begin(), kObjectKeys.end());
    node.checkKeys(keys);
    const std::string& paramName = param->asString();
    const std::string label = "mjcf_param " + quoteText(paramName);
    if (!options.mjcfParam) {
      param->fail(object + "mjcf_param is only available in the node (use mjcf_file here)");
    }
    std::string text;
    try {
      text = options.mjcfParam(paramName);
    } catch (const std::exception& e) {
      param->fail(object + label + ": " + e.what());
    }
    try {
      return labelWarnings(loadMjcfText(text, limits::kMeshTriangles), object + label);
    } catch (const ConfigError& e) {
      param->fail(object + label + ": " + e.what());
    }
  }
  std::vector<std::string> keys{"mjcf_file"};
  keys.insert(keys.end(), kObjectKeys.begin(), kObjectKeys.end());
  node.checkKeys(keys);
  const ConfigNode& file = node.at("mjcf_file");
  const std::string& uri = file.asString();
  std::string path;
  try {
    path = meshes.resolve(uri);
  } catch (const ConfigError& e) {
    file.fail(object + "mjcf_file " + e.what());
  }
  const std::string label =
      "mjcf_file " + quoteText(uri) + (path != uri ? " (" + escapeText(path) + ")" : "");
  try {
    return labelWarnings(loadMjcfObject(path, limits::kMeshTriangles), object + label);
  } catch (const ConfigError& e) {
    file.fail(object + label + ": " + e.what());
  }
}

/// One shape: an object's (with @p context kObjectKeys) or a composite's part (kPartKeys).
Shape parsePrimitive(const std::string& name, const ConfigNode& node, MeshLoader& meshes,
                     const std::vector<std::string>& context) {
  const ConfigNode& shapeNode = node.at("shape");
  const std::string& type = shapeNode.asString();
  if (type == "mesh") {
    return parseMesh(name, node, meshes, context);
  }
  if (type == "box") {
    checkShapeKeys(node, {"shape", "size"}, context);
    const ConfigNode& size = node.at("size");
    return checked(Shape::box(size.asVector3()), size);
  }
  if (type == "cylinder" || type == "capsule") {
    checkShapeKeys(node, {"shape", "radius", "length"}, context);
    const ConfigNode& radius = node.at("radius");
    const ConfigNode& length = node.at("length");
    const Shape shape = type == "cylinder" ? Shape::cylinder(radius.asDouble(), length.asDouble())
                                           : Shape::capsule(radius.asDouble(), length.asDouble());
    // The error points at the size it names.
    try {
      validateShape(shape);
    } catch (const ConfigError& e) {
      (std::string(e.what()).find(" length ") != std::string::npos ? length : radius)
          .fail(e.what());
    }
    return shape;
  }
  if (type == "sphere") {
    checkShapeKeys(node, {"shape", "radius"}, context);
    return checked(Shape::sphere(node.at("radius").asDouble()), node.at("radius"));
  }
  shapeNode.fail("expected one of box, cylinder, sphere, capsule, mesh, got " + quoteText(type));
}

/// The parts of a composite object (`shapes:`), as robosuite's CompositeObject: each a
/// primitive or a mesh at its position and orientation in the object frame.
std::vector<Shape> parseComposite(const std::string& name, const ConfigNode& node,
                                  MeshLoader& meshes) {
  std::vector<std::string> keys{"shapes"};
  keys.insert(keys.end(), kObjectKeys.begin(), kObjectKeys.end());
  node.checkKeys(keys);
  const ConfigNode& list = node.at("shapes");
  if (!list.isList() || list.elements().empty()) {
    list.fail(
        "expected a non-empty list of shapes, each a map with shape, its sizes, position "
        "and orientation");
  }
  std::vector<Shape> shapes;
  for (const ConfigNode& part : list.elements()) {
    if (!part.isMap() || part.get("shape") == nullptr) {
      part.fail("expected a map with the key 'shape' (box, cylinder, sphere, capsule or mesh)");
    }
    Shape shape = parsePrimitive(name, part, meshes, kPartKeys);
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
    if (const ConfigNode* p = part.get("position")) {
      position = parseBoundedVector(*p, "values");
    }
    if (const ConfigNode* q = part.get("orientation")) {
      orientation = parseQuaternion(*q);
    }
    shape.pose = Eigen::Translation3d(position) * orientation * shape.pose;
    shapes.push_back(std::move(shape));
  }
  return shapes;
}

}  // namespace

Eigen::Vector3d parseBoundedVector(const ConfigNode& node, const char* what) {
  const Eigen::Vector3d v = node.asVector3();
  if ((v.array().abs() > limits::kCoordinate).any()) {
    std::ostringstream out;
    out << "expected " << what << " within [-" << limits::kCoordinate << ", " << limits::kCoordinate
        << "] m, got [" << v.x() << ", " << v.y() << ", " << v.z() << "]";
    node.fail(out.str());
  }
  return v;
}

Eigen::Quaterniond parseQuaternion(const ConfigNode& node) {
  const std::vector<double> v = node.asNumbers(4);
  const Eigen::Quaterniond q(v[3], v[0], v[1], v[2]);
  if (!isUnitQuaternion(q)) {
    std::ostringstream out;
    out << "expected a unit quaternion [x, y, z, w], got one of norm " << q.norm();
    node.fail(out.str());
  }
  return q.normalized();
}

ObjectModel parseObject(const std::string& name, const ConfigNode& node) {
  MeshLoader meshes;
  return parseObject(name, node, BuildOptions(), meshes);
}

ObjectModel parseObject(const std::string& name, const ConfigNode& node,
                        const BuildOptions& options, MeshLoader& meshes,
                        std::vector<std::string>* warnings) {
  if (!node.isMap()) {
    node.fail("expected a map with the object's shape and sizes, got " +
              std::string(ConfigNode::typeName(node.type())));
  }
  std::vector<Shape> shapes;
  ObjectOverrides overrides;
  bool siteOffsets = false;  // the offsets are an MJCF file's sites
  if (node.get("mjcf_file") != nullptr || node.get("mjcf_param") != nullptr) {
    if (node.get("mjcf_file") != nullptr && node.get("mjcf_param") != nullptr) {
      node.fail("give either mjcf_file or mjcf_param, not both");
    }
    // robosuite's values are the sites' positions: they take the place of derived ones. Under
    // an init_orientation the offsets turn with the object, as derived ones would; the radius,
    // robosuite's number, stays.
    MjcfObject mjcf = parseMjcf(name, node, options, meshes);
    if (warnings != nullptr) {
      warnings->insert(warnings->end(), mjcf.warnings.begin(), mjcf.warnings.end());
    }
    shapes = std::move(mjcf.shapes);
    siteOffsets = true;  // turned below, once init_orientation is read
    overrides.hasBottomOffset = overrides.hasTopOffset = overrides.hasHorizontalRadius = true;
    overrides.bottomOffset = mjcf.bottomOffset;
    overrides.topOffset = mjcf.topOffset;
    overrides.horizontalRadius = mjcf.horizontalRadius;
  } else if (node.get("urdf_file") != nullptr || node.get("urdf_param") != nullptr) {
    shapes = parseUrdf(name, node, options, meshes);
  } else if (node.get("shapes") != nullptr) {
    if (node.get("shape") != nullptr) {
      node.fail("give either shape or shapes (a composite object), not both");
    }
    shapes = parseComposite(name, node, meshes);
  } else {
    if (node.get("shape") == nullptr) {
      node.fail(
          "missing required key 'shape' (box, cylinder, sphere, capsule or mesh), or shapes, "
          "mjcf_file, urdf_file or urdf_param");
    }
    shapes.push_back(parsePrimitive(name, node, meshes, kObjectKeys));
  }

  if (const ConfigNode* r = node.get("horizontal_radius")) {
    overrides.hasHorizontalRadius = true;
    overrides.horizontalRadius = r->asDouble();
    if (overrides.horizontalRadius < 0.0) {
      r->fail("expected a non-negative radius in [m]");
    }
    if (overrides.horizontalRadius > limits::kCoordinate) {
      std::ostringstream out;
      out << "expected a non-negative radius in [m] of at most " << limits::kCoordinate << ", got "
          << overrides.horizontalRadius;
      r->fail(out.str());
    }
  }
  if (const ConfigNode* b = node.get("bottom_offset")) {
    overrides.hasBottomOffset = true;
    overrides.bottomOffset = parseBoundedVector(*b, "values");
  }
  if (const ConfigNode* t = node.get("top_offset")) {
    overrides.hasTopOffset = true;
    overrides.topOffset = parseBoundedVector(*t, "values");
  }
  Eigen::Quaterniond init = Eigen::Quaterniond::Identity();
  if (const ConfigNode* q = node.get("init_orientation")) {
    init = parseQuaternion(*q);
  }
  if (siteOffsets) {
    // Given overrides replace the sites: they are taken as they are.
    if (node.get("bottom_offset") == nullptr) {
      overrides.bottomOffset = init * overrides.bottomOffset;
    }
    if (node.get("top_offset") == nullptr) {
      overrides.topOffset = init * overrides.topOffset;
    }
  }
  const std::string problem = geometryProblem(shapes, init);
  if (!problem.empty()) {
    node.fail("object " + quoteText(name) + ": " + problem);
  }
  ObjectModel object = makeObject(name, std::move(shapes), init, overrides);
  if (const ConfigNode* d = node.get("density")) {
    object.density = detail::parseDensity(*d);
  }
  return object;
}

}  // namespace placement_samplers
