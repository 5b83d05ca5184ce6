#include "placement_samplers/ros/region_params.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

using Kind = RegionShape::Kind;

Eigen::Vector2d rotated(const Eigen::Vector2d& v, double angle) {
  return Eigen::Rotation2Dd(angle) * v;
}

XmlRpc::XmlRpcValue pair(double a, double b) {
  XmlRpc::XmlRpcValue out;
  out.setSize(2);
  out[0] = a;
  out[1] = b;
  return out;
}

XmlRpc::XmlRpcValue pair(const Eigen::Vector2d& v) { return pair(v.x(), v.y()); }

bool isMap(const XmlRpc::XmlRpcValue& v) { return v.getType() == XmlRpc::XmlRpcValue::TypeStruct; }

bool isList(const XmlRpc::XmlRpcValue& v) { return v.getType() == XmlRpc::XmlRpcValue::TypeArray; }

bool isString(const XmlRpc::XmlRpcValue& v) {
  return v.getType() == XmlRpc::XmlRpcValue::TypeString;
}

/// The name a list item gives its sampler, "" for none.
std::string itemName(XmlRpc::XmlRpcValue& item) {
  if (isString(item)) {
    return static_cast<std::string>(item);
  }
  if (isMap(item) && item.hasMember("name") && isString(item["name"])) {
    return static_cast<std::string>(item["name"]);
  }
  return "";
}

/// True for an item that only names its sampler ({name: N} or {name: N, type: T}).
bool namesOnly(XmlRpc::XmlRpcValue& item) {
  if (isString(item)) {
    return true;
  }
  for (auto& entry : item) {
    if (entry.first != "name" && entry.first != "type") {
      return false;
    }
  }
  return true;
}

/// Finds sampler @p name in @p list (and the lists of composites below it) and moves it into
/// the map form; the map's address, or nullptr.
XmlRpc::XmlRpcValue* findIn(XmlRpc::XmlRpcValue& tree, XmlRpc::XmlRpcValue& list,
                            const std::string& name, int depth) {
  if (!isList(list) || depth > 100) {
    return nullptr;
  }
  for (int i = 0; i < list.size(); ++i) {
    XmlRpc::XmlRpcValue& item = list[i];
    const std::string itemNamed = itemName(item);
    const bool named = !itemNamed.empty() && namesOnly(item) && tree.hasMember(itemNamed);
    XmlRpc::XmlRpcValue* params = named ? &tree[itemNamed] : (isMap(item) ? &item : nullptr);
    if (params == nullptr || !isMap(*params)) {
      continue;
    }
    if (itemNamed == name) {
      if (named) {
        return params;
      }
      XmlRpc::XmlRpcValue map;
      map.begin();  // an empty map, not an invalid value
      for (auto& entry : item) {
        if (entry.first != "name") {
          map[entry.first] = entry.second;
        }
      }
      tree[name] = map;
      list[i] = name;
      return &tree[name];
    }
    if (params->hasMember("samplers")) {
      if (XmlRpc::XmlRpcValue* found = findIn(tree, (*params)["samplers"], name, depth + 1)) {
        return found;
      }
    }
  }
  return nullptr;
}

}  // namespace

ShapePose shapePose(const RegionShape& shape) {
  ShapePose pose;
  switch (shape.kind) {
    case Kind::Rectangle:
      pose.centre = Eigen::Vector2d(0.5 * (shape.xRange[0] + shape.xRange[1]),
                                    0.5 * (shape.yRange[0] + shape.yRange[1]));
      break;
    case Kind::RotatedRectangle:
      pose.centre = shape.centre;
      pose.yaw = shape.yaw;
      break;
    case Kind::Disk:
    case Kind::Annulus:
      pose.centre = shape.centre;
      break;
    case Kind::Polygon:
      for (const Eigen::Vector2d& v : shape.vertices) {
        pose.centre += v;
      }
      pose.centre /= static_cast<double>(std::max<std::size_t>(1, shape.vertices.size()));
      break;
  }
  return pose;
}

bool turns(const RegionShape& shape) {
  return shape.kind == Kind::Rectangle || shape.kind == Kind::RotatedRectangle ||
         shape.kind == Kind::Polygon;
}

std::vector<std::string> sizeHandles(const RegionShape& shape) {
  switch (shape.kind) {
    case Kind::Rectangle:
    case Kind::RotatedRectangle:
      return {"size_x", "size_y"};
    case Kind::Disk:
      return {"radius"};
    case Kind::Annulus:
      return {"inner_radius", "outer_radius"};
    case Kind::Polygon:
      break;
  }
  return {};
}

Eigen::Vector2d handlePosition(const RegionShape& shape, const std::string& handle) {
  const ShapePose pose = shapePose(shape);
  if (handle == "size_x" || handle == "size_y") {
    const Eigen::Vector2d size =
        shape.kind == Kind::Rectangle
            ? Eigen::Vector2d(shape.xRange[1] - shape.xRange[0], shape.yRange[1] - shape.yRange[0])
            : shape.size;
    const Eigen::Vector2d local = handle == "size_x" ? Eigen::Vector2d(0.5 * size.x(), 0.0)
                                                     : Eigen::Vector2d(0.0, 0.5 * size.y());
    return pose.centre + rotated(local, pose.yaw);
  }
  if (handle == "inner_radius") {
    return pose.centre + Eigen::Vector2d(0.0, shape.innerRadius);
  }
  return pose.centre + Eigen::Vector2d(shape.radius, 0.0);  // radius, outer_radius
}

RegionShape moveShape(const RegionShape& shape, const ShapePose& pose) {
  const ShapePose old = shapePose(shape);
  const double turn = turns(shape) ? pose.yaw - old.yaw : 0.0;
  RegionShape out = shape;
  switch (shape.kind) {
    case Kind::Rectangle: {
      const Eigen::Vector2d size(shape.xRange[1] - shape.xRange[0],
                                 shape.yRange[1] - shape.yRange[0]);
      if (std::abs(std::remainder(pose.yaw, 2.0 * M_PI)) > 1e-9) {
        return RegionShape::rotatedRectangle(pose.centre, size, pose.yaw);
      }
      const Eigen::Vector2d d = pose.centre - old.centre;
      return RegionShape::rectangle(shape.xRange + Eigen::Vector2d::Constant(d.x()),
                                    shape.yRange + Eigen::Vector2d::Constant(d.y()));
    }
    case Kind::RotatedRectangle:
      out.centre = pose.centre;
      out.yaw = turns(shape) ? pose.yaw : shape.yaw;
      return out;
    case Kind::Disk:
    case Kind::Annulus:
      out.centre = pose.centre;
      return out;
    case Kind::Polygon:
      for (Eigen::Vector2d& v : out.vertices) {
        v = pose.centre + rotated(v - old.centre, turn);
      }
      return out;
  }
  return out;
}

RegionShape resizeShape(const RegionShape& shape, const std::string& handle,
                        const Eigen::Vector2d& at) {
  const ShapePose pose = shapePose(shape);
  RegionShape out = shape;
  const Eigen::Vector2d local = rotated(at - pose.centre, -pose.yaw);
  if (handle == "size_x" || handle == "size_y") {
    const int axis = handle == "size_x" ? 0 : 1;
    const double half = std::abs(local[axis]);
    if (shape.kind == Kind::Rectangle) {
      Eigen::Vector2d& range = axis == 0 ? out.xRange : out.yRange;
      range = Eigen::Vector2d(pose.centre[axis] - half, pose.centre[axis] + half);
    } else {
      out.size[axis] = 2.0 * half;
    }
  } else if (handle == "inner_radius") {
    out.innerRadius = local.norm();
  } else if (handle == "radius" || handle == "outer_radius") {
    out.radius = local.norm();
  }
  return out;
}

XmlRpc::XmlRpcValue shapeParams(const RegionShape& shape) {
  XmlRpc::XmlRpcValue out;
  out["shape"] = std::string(shapeKindName(shape.kind));
  switch (shape.kind) {
    case Kind::Rectangle:
      out["x_range"] = pair(shape.xRange);
      out["y_range"] = pair(shape.yRange);
      break;
    case Kind::RotatedRectangle:
      out["center"] = pair(shape.centre);
      out["size"] = pair(shape.size);
      out["yaw"] = shape.yaw;
      break;
    case Kind::Disk:
      out["center"] = pair(shape.centre);
      out["radius"] = shape.radius;
      break;
    case Kind::Annulus:
      out["center"] = pair(shape.centre);
      out["inner_radius"] = shape.innerRadius;
      out["outer_radius"] = shape.radius;
      break;
    case Kind::Polygon: {
      XmlRpc::XmlRpcValue vertices;
      vertices.setSize(static_cast<int>(shape.vertices.size()));
      for (std::size_t i = 0; i < shape.vertices.size(); ++i) {
        vertices[static_cast<int>(i)] = pair(shape.vertices[i]);
      }
      out["vertices"] = vertices;
      break;
    }
  }
  return out;
}

XmlRpc::XmlRpcValue& samplerParams(XmlRpc::XmlRpcValue& tree, const std::string& name) {
  XmlRpc::XmlRpcValue* found = nullptr;
  if (isMap(tree) && tree.hasMember("samplers")) {
    found = findIn(tree, tree["samplers"], name, 0);
  }
  if (found == nullptr) {
    throw ConfigError("no samplers list holds a sampler called " + quoteText(name));
  }
  return *found;
}

void writeShape(XmlRpc::XmlRpcValue& params, const HandleShape& edited) {
  if (edited.keepOut) {
    const int index = static_cast<int>(*edited.keepOut);
    if (!params.hasMember("keep_out") || !isList(params["keep_out"]) ||
        index >= params["keep_out"].size()) {
      throw ConfigError("the sampler has no keep_out zone " + std::to_string(index));
    }
    XmlRpc::XmlRpcValue zone = shapeParams(edited.shape);
    XmlRpc::XmlRpcValue& old = params["keep_out"][index];
    if (isMap(old) && old.hasMember("frame")) {
      zone["frame"] = old["frame"];
    }
    old = zone;
    return;
  }
  // A `region: {shape: rectangle}` is built into the ranges too: it stays a region.
  if (edited.ranges && edited.shape.kind == Kind::Rectangle && !params.hasMember("region")) {
    params["x_range"] = pair(edited.shape.xRange);
    params["y_range"] = pair(edited.shape.yRange);
    return;
  }
  // A region replaces the ranges (the configuration refuses both).
  for (const char* key : {"x_range", "y_range"}) {
    if (params.hasMember(key)) {
      XmlRpc::XmlRpcValue kept;
      kept.begin();
      for (auto& entry : params) {
        if (entry.first != key) {
          kept[entry.first] = entry.second;
        }
      }
      params = kept;
    }
  }
  params["region"] = shapeParams(edited.shape);
}

std::vector<std::string> changedKeys(XmlRpc::XmlRpcValue& before, XmlRpc::XmlRpcValue& after) {
  std::vector<std::string> out;
  for (auto& entry : after) {
    if (!before.hasMember(entry.first) || before[entry.first].toXml() != entry.second.toXml()) {
      out.push_back(entry.first);
    }
  }
  return out;
}

}  // namespace ros_interface
}  // namespace placement_samplers
