#include <limits>
#include <sstream>

#include "config/builder_parts.hpp"
#include "config/region_config.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers::detail {

UniformSamplerParams parseUniformParams(const ConfigNode& s, std::uint32_t maxAttempts,
                                        const std::string& name) {
  UniformSamplerParams p;
  p.maxAttempts = maxAttempts;
  if (const ConfigNode* n = s.get("x_range")) {
    p.xRange = parseRange(*n);
  }
  if (const ConfigNode* n = s.get("y_range")) {
    p.yRange = parseRange(*n);
  }
  if (const ConfigNode* n = s.get("region")) {
    for (const char* key : {"x_range", "y_range"}) {
      if (s.get(key) != nullptr) {
        s.at(key).fail(std::string("region replaces ") + key + ": give one or the other");
      }
    }
    if (isSurfaceRegion(*n)) {
      p.surface = parseSurfaceRegion(*n);
    } else {
      p.region = parseRegionShape(*n);
    }
  }
  if (const ConfigNode* n = s.get("keep_out")) {
    p.keepOut = parseKeepOut(*n);
  }
  if (const ConfigNode* n = s.get("strategy")) {
    const std::string& strategy = n->asString();
    if (strategy != "rejection" && strategy != "free_space" && strategy != "dense") {
      n->fail("expected rejection, free_space or dense, got " + quoteText(strategy));
    }
    if (strategy == "free_space") {
      p.strategy = UniformSamplerParams::Strategy::FreeSpace;
    } else if (strategy == "dense") {
      p.strategy = UniformSamplerParams::Strategy::Dense;
    }
  }
  if (const ConfigNode* n = s.get("rotation")) {
    if (n->type() == ConfigNode::Type::Null) {
      p.rotation = RotationSpec::full();
    } else if (n->isList()) {
      const std::vector<double> v = n->asNumbers(2);
      p.rotation = RotationSpec::range(v[0], v[1]);
    } else if (n->isNumber()) {
      p.rotation = RotationSpec::fixed(n->asDouble());
    } else {
      n->fail("expected an angle in [rad], a pair [min, max] in [rad], or nothing for U(0, 2pi)");
    }
  }
  if (const ConfigNode* n = s.get("rotation_axis")) {
    const std::string& axis = n->asString();
    if (axis != "x" && axis != "y" && axis != "z") {
      n->fail("expected x, y or z, got " + quoteText(axis));
    }
    p.rotationAxis = axis[0] - 'x';
  }
  if (const ConfigNode* n = s.get("ensure_object_boundary_in_range")) {
    p.ensureObjectBoundaryInRange = n->asBool();
  }
  if (const ConfigNode* n = s.get("ensure_valid_placement")) {
    p.ensureValidPlacement = n->asBool();
  }
  if (const ConfigNode* n = s.get("reference_pos")) {
    p.referencePos = n->asVector3();
  }
  if (const ConfigNode* n = s.get("z_offset")) {
    p.zOffset = n->asDouble();
  }
  if (const ConfigNode* n = s.get("max_attempts")) {
    p.maxAttempts =
        static_cast<std::uint32_t>(n->asInt(1, std::numeric_limits<std::uint32_t>::max()));
  }
  if (const ConfigNode* n = s.get("resting")) {
    const std::string& resting = n->asString();
    if (resting != "upright" && resting != "stable") {
      n->fail(
          "expected upright (the objects as configured, robosuite's) or stable (every pose "
          "they rest in), got " +
          quoteText(resting));
    }
    p.resting = resting == "stable" ? UniformSamplerParams::Resting::Stable
                                    : UniformSamplerParams::Resting::Upright;
  }
  for (const char* key : {"min_probability", "allow_rolling"}) {
    if (s.get(key) != nullptr && p.resting != UniformSamplerParams::Resting::Stable) {
      s.at(key).fail(std::string(key) + " applies to resting: stable only");
    }
  }
  if (const ConfigNode* n = s.get("min_probability")) {
    p.minProbability = n->asDouble();
    if (!(p.minProbability >= 0.0 && p.minProbability < 1.0)) {
      n->fail("expected a probability in [0, 1)");
    }
  }
  if (const ConfigNode* n = s.get("allow_rolling")) {
    p.allowRolling = n->asBool();
  }
  if (const ConfigNode* n = s.get("relations")) {
    p.relations = parseRelations(*n, name);
  }
  return p;
}

Eigen::Vector2d parseRange(const ConfigNode& n) {
  const std::vector<double> v = n.asNumbers(2);
  if (v[0] > v[1]) {
    std::ostringstream out;
    out << "expected [min, max] with min <= max, got [" << v[0] << ", " << v[1] << "]";
    n.fail(out.str());
  }
  return Eigen::Vector2d(v[0], v[1]);
}

}  // namespace placement_samplers::detail
