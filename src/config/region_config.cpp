#include "config/region_config.hpp"

#include "config/builder_parts.hpp"
#include <cmath>

#include "placement_samplers/limits.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers::detail {
namespace {

Eigen::Vector2d vector2(const ConfigNode& n) {
  const std::vector<double> v = n.asNumbers(2);
  return Eigen::Vector2d(v[0], v[1]);
}

/// The shape's `center`, or its British spelling `centre` (kept as an alias); not both.
const ConfigNode* centerNode(const ConfigNode& node) {
  const ConfigNode* center = node.get("center");
  const ConfigNode* centre = node.get("centre");
  if (center && centre) {
    centre->fail("'centre' is an alias of 'center': give one of them");
  }
  return center ? center : centre;
}

/// `center` for the shapes that have one; `centre` is listed only when the user wrote it.
void addCenterKeys(const ConfigNode& node, std::vector<std::string>& keys) {
  keys.push_back("center");
  if (node.get("centre")) {
    keys.push_back("centre");
  }
}

Eigen::Vector2d centerOf(const ConfigNode& node) {
  const ConfigNode* c = centerNode(node);
  return c ? vector2(*c) : Eigen::Vector2d::Zero();
}

RegionShape parseShape(const ConfigNode& node, bool keepOut) {
  if (!node.isMap()) {
    node.fail(std::string("expected a shape: a map with shape: rectangle, rotated_rectangle, disk, "
                          "annulus") +
              (keepOut ? " or polygon" : ", polygon or surface") + " and its sizes");
  }
  const ConfigNode& kind = node.at("shape");
  const std::string& name = kind.asString();
  std::vector<std::string> keys{"shape"};
  if (keepOut) {
    keys.push_back("frame");
  }
  RegionShape s;
  if (name == "rectangle") {
    keys.insert(keys.end(), {"x_range", "y_range"});
    node.checkKeys(keys);
    s = RegionShape::rectangle(parseRange(node.at("x_range")), parseRange(node.at("y_range")));
  } else if (name == "rotated_rectangle") {
    addCenterKeys(node, keys);
    keys.insert(keys.end(), {"size", "yaw"});
    node.checkKeys(keys);
    s = RegionShape::rotatedRectangle(centerOf(node), vector2(node.at("size")),
                                      node.get("yaw") ? node.at("yaw").asDouble() : 0.0);
  } else if (name == "disk") {
    addCenterKeys(node, keys);
    keys.insert(keys.end(), {"radius"});
    node.checkKeys(keys);
    s = RegionShape::disk(centerOf(node), node.at("radius").asDouble());
  } else if (name == "annulus") {
    addCenterKeys(node, keys);
    keys.insert(keys.end(), {"inner_radius", "outer_radius"});
    node.checkKeys(keys);
    s = RegionShape::annulus(centerOf(node), node.at("inner_radius").asDouble(),
                             node.at("outer_radius").asDouble());
  } else if (name == "polygon") {
    keys.insert(keys.end(), {"vertices"});
    node.checkKeys(keys);
    const ConfigNode& list = node.at("vertices");
    std::vector<Eigen::Vector2d> vertices;
    for (const ConfigNode& v : list.elements()) {
      vertices.push_back(vector2(v));
    }
    s = RegionShape::polygon(std::move(vertices));
  } else {
    kind.fail(std::string("expected rectangle, rotated_rectangle, disk, annulus") +
              (keepOut ? " or polygon" : ", polygon or surface") + ", got " + quoteText(name));
  }
  if (const auto problem = findShapeProblem(s)) {
    const ConfigNode* where = problem->key == "center" ? centerNode(node) : node.get(problem->key);
    (where ? *where : node).fail(problem->message);
  }
  return s;
}

}  // namespace

RegionShape parseRegionShape(const ConfigNode& node) { return parseShape(node, false); }

bool isSurfaceRegion(const ConfigNode& node) {
  const ConfigNode* kind = node.isMap() ? node.get("shape") : nullptr;
  return kind != nullptr && kind->isString() && kind->asString() == "surface";
}

SurfaceRegion parseSurfaceRegion(const ConfigNode& node) {
  node.checkKeys({"shape", "of", "select", "min_area", "normal_tolerance", "margin"});
  SurfaceRegion r;
  const ConfigNode& of = node.at("of");
  r.of = of.asString();
  if (r.of.empty()) {
    of.fail("expected the name of a fixture or of an object placed by an earlier sampler");
  }
  if (const ConfigNode* n = node.get("select")) {
    if (n->isList()) {
      r.select = SurfaceRegion::Select::Indices;
      for (const ConfigNode& i : n->elements()) {
        r.indices.push_back(static_cast<std::size_t>(i.asInt(0, 1000000)));
      }
      if (r.indices.empty()) {
        n->fail("expected all, top or a non-empty list of surface indices");
      }
    } else if (n->isString() && n->asString() == "all") {
      r.select = SurfaceRegion::Select::All;
    } else if (n->isString() && n->asString() == "top") {
      r.select = SurfaceRegion::Select::Top;
    } else {
      n->fail("expected all, top or a list of surface indices (as --describe lists them)");
    }
  }
  const auto number = [&](const char* key, double& value, double max, const char* what) {
    if (const ConfigNode* n = node.get(key)) {
      value = n->asDouble();
      if (!std::isfinite(value) || value < 0.0 || value >= max) {
        n->fail(what);
      }
    }
  };
  number("min_area", r.minArea, limits::kCoordinate * limits::kCoordinate,
         "expected an area >= 0 [m^2]");
  number("normal_tolerance", r.normalTolerance, M_PI_2, "expected an angle in [0, pi/2) [rad]");
  number("margin", r.margin, limits::kCoordinate, "expected a distance >= 0 [m]");
  return r;
}

std::vector<KeepOutZone> parseKeepOut(const ConfigNode& node) {
  std::vector<KeepOutZone> zones;
  for (const ConfigNode& item : node.elements()) {
    KeepOutZone zone;
    zone.shape = parseShape(item, true);
    if (const ConfigNode* frame = item.get("frame")) {
      const std::string& f = frame->asString();
      if (f != "sampler" && f != "world") {
        frame->fail("expected sampler (around the sampler's reference) or world, got " +
                    quoteText(f));
      }
      zone.world = f == "world";
    }
    zones.push_back(std::move(zone));
  }
  return zones;
}

}  // namespace placement_samplers::detail
