#include "placement_samplers/output/scene_json.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <limits>

#include "placement_samplers/sampling/sequential_composite_sampler.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"
#include "output/json_numbers.hpp"
#include "output/relation_json.hpp"
#include "output/surface_json.hpp"

namespace placement_samplers {
namespace {

using detail::appendInteger;
using detail::appendNumber;
using detail::appendVector;

void appendBounds(std::string& out, const ObjectModel& object) {
  out += "\"horizontal_radius\": ";
  appendNumber(out, object.horizontalRadius);
  out += ", \"bottom_offset\": ";
  appendVector(out, object.bottomOffset.data(), 3);
  out += ", \"top_offset\": ";
  appendVector(out, object.topOffset.data(), 3);
  // What physics counts as clearance: the geometry ends above the bottom offset / below the top.
  out += ", \"bottom_gap\": ";
  appendNumber(out, object.bottomGap);
  out += ", \"top_gap\": ";
  appendNumber(out, object.topGap);
}

void appendSampler(std::string& out, const PlacementSampler& sampler);

/// {"shape": kind, and its parameters under their configuration names}.
void appendShape(std::string& out, const RegionShape& s, const char* frame) {
  out += "{\"shape\": \"";
  out += shapeKindName(s.kind);
  out += '"';
  const auto key = [&](const char* name) {
    out += ", \"";
    out += name;
    out += "\": ";
  };
  switch (s.kind) {
    case RegionShape::Kind::Rectangle:
      key("x_range");
      appendVector(out, s.xRange.data(), 2);
      key("y_range");
      appendVector(out, s.yRange.data(), 2);
      break;
    case RegionShape::Kind::RotatedRectangle:
      key("center");
      appendVector(out, s.centre.data(), 2);
      key("size");
      appendVector(out, s.size.data(), 2);
      key("yaw");
      appendNumber(out, s.yaw);
      break;
    case RegionShape::Kind::Disk:
      key("center");
      appendVector(out, s.centre.data(), 2);
      key("radius");
      appendNumber(out, s.radius);
      break;
    case RegionShape::Kind::Annulus:
      key("center");
      appendVector(out, s.centre.data(), 2);
      key("inner_radius");
      appendNumber(out, s.innerRadius);
      key("outer_radius");
      appendNumber(out, s.radius);
      break;
    case RegionShape::Kind::Polygon:
      key("vertices");
      out += '[';
      for (std::size_t i = 0; i < s.vertices.size(); ++i) {
        out += i == 0 ? "" : ", ";
        appendVector(out, s.vertices[i].data(), 2);
      }
      out += ']';
      break;
  }
  if (frame != nullptr) {
    key("frame");
    out += '"';
    out += frame;
    out += '"';
  }
  out += '}';
}

void appendSampleArgs(std::string& out, const SampleArgs& args) {
  out += '{';
  bool first = true;
  if (args.reference && args.reference->kind != Reference::Kind::Default) {
    out += "\"reference\": ";
    if (args.reference->kind == Reference::Kind::Name) {
      appendJsonString(out, args.reference->name);
    } else {
      appendVector(out, args.reference->point.data(), 3);
    }
    first = false;
  }
  if (args.onTop) {
    out += first ? "" : ", ";
    out += *args.onTop ? "\"on_top\": true" : "\"on_top\": false";
  }
  out += '}';
}

/// "resting": "stable", "min_probability", "allow_rolling" and each object's resting poses:
/// "resting_poses": {name: [{"index", "orientation" [x, y, z, w], "probability",
/// "bottom_offset", "top_offset", "horizontal_radius"}]} (empty for one placed as configured).
void appendResting(std::string& out, const UniformRandomSampler& sampler) {
  const UniformSamplerParams& p = sampler.params();
  out += ", \"resting\": \"stable\", \"min_probability\": ";
  appendNumber(out, p.minProbability);
  out += p.allowRolling ? ", \"allow_rolling\": true" : ", \"allow_rolling\": false";
  out += ", \"resting_poses\": {";
  const std::vector<ObjectPtr> objects = sampler.objects();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    out += i == 0 ? "" : ", ";
    appendJsonString(out, objects[i]->name);
    out += ": [";
    bool first = true;
    for (const UniformRandomSampler::RestingChoice& c : sampler.restingChoices(*objects[i])) {
      out += first ? "{\"index\": " : ", {\"index\": ";
      first = false;
      appendInteger(out, static_cast<std::uint64_t>(c.index));
      out += ", \"orientation\": ";
      appendVector(out, c.object->initOrientation.coeffs().data(), 4);
      out += ", \"probability\": ";
      appendNumber(out, c.probability);
      out += ", \"bottom_offset\": ";
      appendNumber(out, c.object->bottomOffset.z());
      out += ", \"top_offset\": ";
      appendNumber(out, c.object->topOffset.z());
      out += ", \"horizontal_radius\": ";
      appendNumber(out, c.object->horizontalRadius);
      out += '}';
    }
    out += ']';
  }
  out += '}';
}

void appendUniform(std::string& out, const UniformRandomSampler& sampler) {
  const UniformSamplerParams& p = sampler.params();
  out += "{\"type\": \"uniform\", \"name\": ";
  appendJsonString(out, sampler.name());
  out += ", \"objects\": [";
  const std::vector<ObjectPtr> objects = sampler.objects();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    out += i == 0 ? "" : ", ";
    appendJsonString(out, objects[i]->name);
  }
  out += "], \"x_range\": ";
  appendVector(out, p.xRange.data(), 2);
  out += ", \"y_range\": ";
  appendVector(out, p.yRange.data(), 2);
  out += ", \"rotation\": ";
  if (p.rotation.kind == RotationSpec::Kind::Full) {
    out += "null";
  } else if (p.rotation.kind == RotationSpec::Kind::Fixed) {
    appendNumber(out, p.rotation.low);
  } else {
    const double range[2] = {p.rotation.low, p.rotation.high};
    appendVector(out, range, 2);
  }
  out += ", \"rotation_axis\": \"";
  out += "xyz"[p.rotationAxis];
  out += p.ensureObjectBoundaryInRange ? "\", \"ensure_object_boundary_in_range\": true"
                                       : "\", \"ensure_object_boundary_in_range\": false";
  out += p.ensureValidPlacement ? ", \"ensure_valid_placement\": true"
                                : ", \"ensure_valid_placement\": false";
  out += ", \"reference_pos\": ";
  appendVector(out, p.referencePos.data(), 3);
  out += ", \"z_offset\": ";
  appendNumber(out, p.zOffset);
  out += ", \"max_attempts\": ";
  appendInteger(out, p.maxAttempts);
  if (p.strategy == UniformSamplerParams::Strategy::FreeSpace) {
    out += ", \"strategy\": \"free_space\"";
  } else if (p.strategy == UniformSamplerParams::Strategy::Dense) {
    out += ", \"strategy\": \"dense\"";
  }
  if (p.region) {
    out += ", \"region\": ";
    appendShape(out, *p.region, nullptr);
  }
  if (p.surface) {
    out += ", \"region\": ";
    detail::appendSurfaceRegion(out, sampler);
  }
  if (p.resting == UniformSamplerParams::Resting::Stable) {
    appendResting(out, sampler);
  }
  if (!p.keepOut.empty()) {
    out += ", \"keep_out\": [";
    for (std::size_t i = 0; i < p.keepOut.size(); ++i) {
      out += i == 0 ? "" : ", ";
      appendShape(out, p.keepOut[i].shape, p.keepOut[i].world ? "world" : "sampler");
    }
    out += ']';
  }
  detail::appendRelations(out, p.relations);
  out += p.hides ? ", \"hides\": true}" : ", \"hides\": false}";
}

void appendSampler(std::string& out, const PlacementSampler& sampler) {
  if (const auto* uniform = dynamic_cast<const UniformRandomSampler*>(&sampler)) {
    appendUniform(out, *uniform);
    return;
  }
  const auto& composite = dynamic_cast<const SequentialCompositeSampler&>(sampler);
  out += "{\"type\": \"sequential\", \"name\": ";
  appendJsonString(out, composite.name());
  out += ", \"samplers\": [";
  bool first = true;
  for (const SequentialCompositeSampler::Child& child : composite.children()) {
    out += first ? "{\"sampler\": " : ", {\"sampler\": ";
    first = false;
    appendSampler(out, *child.sampler);
    out += ", \"sample_args\": ";
    appendSampleArgs(out, child.args);
    out += '}';
  }
  out += "]}";
}

/// ", \"physics\": {...}" with the settings that are set or differ from the defaults; nothing
/// when none do, so that a configuration without physics keys describes as before.
void appendPhysics(std::string& out, const PhysicsSettings& p) {
  const PhysicsSettings defaults;
  std::string keys;
  const auto number = [&](const char* name, double value, double fallback) {
    if (value != fallback) {
      keys += keys.empty() ? "\"" : ", \"";
      keys += name;
      keys += "\": ";
      appendNumber(keys, value);
    }
  };
  if (p.mode != defaults.mode) {
    keys += "\"physics\": \"";
    keys += physicsModeName(p.mode);
    keys += '"';
  }
  number("physics_seconds", p.seconds, defaults.seconds);
  number("physics_timestep", p.timestep, defaults.timestep);
  number("physics_position_tolerance", p.positionTolerance, defaults.positionTolerance);
  number("physics_rotation_tolerance", p.rotationTolerance, defaults.rotationTolerance);
  if (p.retry != defaults.retry) {
    keys += keys.empty() ? "\"physics_retry\": true" : ", \"physics_retry\": true";
  }
  number("physics_max_draws", p.maxDraws, defaults.maxDraws);
  number("physics_max_memory_mb", p.maxMemoryMb, defaults.maxMemoryMb);
  if (p.groundZ) {
    number("ground_z", *p.groundZ, std::numeric_limits<double>::quiet_NaN());
  }
  number("density", p.density, defaults.density);
  if (!keys.empty()) {
    out += ", \"physics\": {" + keys + "}";
  }
}

}  // namespace

std::string configToJson(const SceneConfig& config) {
  std::string out = "{\"objects\": {";
  for (std::size_t i = 0; i < config.objects.size(); ++i) {
    const ObjectModel& object = *config.objects[i];
    out += i == 0 ? "" : ", ";
    appendJsonString(out, object.name);
    out += ": {";
    appendBounds(out, object);
    out += ", \"init_orientation\": ";
    appendVector(out, object.initOrientation.coeffs().data(), 4);
    if (object.density > 0.0) {
      out += ", \"density\": ";
      appendNumber(out, object.density);
    }
    out += '}';
  }
  out += "}, \"fixtures\": [";
  for (std::size_t i = 0; i < config.fixtures.size(); ++i) {
    const FixtureSpec& f = config.fixtures[i];
    out += i == 0 ? "{\"name\": " : ", {\"name\": ";
    appendJsonString(out, f.name);
    out += ", \"position\": ";
    appendVector(out, f.position.data(), 3);
    out += ", \"orientation\": ";
    appendVector(out, f.orientation.coeffs().data(), 4);
    out += ", ";
    appendBounds(out, *f.object);
    out += '}';
  }
  out += "], \"hidden\": [";
  for (std::size_t i = 0; i < config.hidden.size(); ++i) {
    out += i == 0 ? "" : ", ";
    appendJsonString(out, config.hidden[i]);
  }
  out += "], \"sampler\": ";
  appendSampler(out, *config.root);
  appendPhysics(out, config.physics);
  out += '}';
  return out;
}

void appendJsonString(std::string& out, std::string_view text) {
  out += '"';
  // Names are plain almost always: one append when nothing needs escaping.
  const bool plain = std::all_of(text.begin(), text.end(), [](char c) {
    const auto byte = static_cast<unsigned char>(c);
    return byte >= 0x20 && byte < 0x80 && c != '"' && c != '\\';
  });
  if (plain) {
    out.append(text);
    out += '"';
    return;
  }
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (static_cast<unsigned char>(c) >= 0x80) {
      // Valid UTF-8 as it is; a byte that starts no valid sequence becomes U+FFFD, so that
      // every line stays JSON whatever a name read from input holds.
      const std::size_t n = utf8Sequence(text, i);
      if (n > 0) {
        out.append(text.substr(i, n));
        i += n - 1;
      } else {
        out += "\xef\xbf\xbd";
      }
      continue;
    }
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
          out += buffer;
        } else {
          out += c;
        }
    }
  }
  out += '"';
}

void appendSceneJson(std::string& out, const SceneResult& scene) {
  out += "{\"scene\": ";
  appendInteger(out, scene.index);
  out += ", \"seed\": ";
  appendInteger(out, scene.seed);
  out += scene.success ? ", \"success\": true" : ", \"success\": false";
  if (scene.physicsMode != PhysicsMode::None) {
    out += scene.stable ? ", \"stable\": true" : ", \"stable\": false";
  }
  out += ", \"message\": ";
  appendJsonString(out, scene.message);
  out += ", \"placements\": [";
  for (std::size_t i = 0; i < scene.placements.size(); ++i) {
    const ObjectPlacement& p = scene.placements[i];
    out += i == 0 ? "{\"name\": " : ", {\"name\": ";
    appendJsonString(out, p.name);
    out += ", \"sampler\": ";
    appendJsonString(out, p.sampler);
    out += ", \"position\": [";
    for (int k = 0; k < 3; ++k) {
      if (k > 0) {
        out += ", ";
      }
      appendNumber(out, p.position[k]);
    }
    out += "], \"orientation\": [";
    const Eigen::Vector4d q = p.orientation.coeffs();  // x, y, z, w
    for (int k = 0; k < 4; ++k) {
      if (k > 0) {
        out += ", ";
      }
      appendNumber(out, q[k]);
    }
    out += ']';
    const bool simulated = scene.simulated && i < scene.physics.size();
    if (simulated && scene.physicsMode == PhysicsMode::Settle) {
      const PhysicsOutcome& o = scene.physics[i];
      out += ", \"sampled_position\": ";
      appendVector(out, o.sampledPosition.data(), 3);
      out += ", \"sampled_orientation\": ";
      appendVector(out, o.sampledOrientation.coeffs().data(), 4);
    }
    out += ", \"attempts\": ";
    appendInteger(out, p.attempts);
    if (p.restPose != ObjectPlacement::kUpright) {
      out += ", \"rest_pose\": ";
      appendInteger(out, static_cast<std::uint64_t>(p.restPose));
    }
    if (simulated) {
      const PhysicsOutcome& o = scene.physics[i];
      out += ", \"moved\": ";
      appendNumber(out, o.moved);
      out += ", \"turned\": ";
      appendNumber(out, o.turned);
      out += o.fallen ? ", \"fallen\": true" : ", \"fallen\": false";
    }
    out += '}';
  }
  out += "]}";
}

std::string sceneToJson(const SceneResult& scene) {
  std::string out;
  appendSceneJson(out, scene);
  return out;
}

}  // namespace placement_samplers
