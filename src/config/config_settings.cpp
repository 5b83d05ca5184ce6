#include <iterator>
#include <limits>
#include <sstream>

#include "config/builder_parts.hpp"
#include "placement_samplers/collision/make_collision_checker.hpp"
#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {

CollisionMode parseCollisionMode(const ConfigNode& node) {
  const std::string& mode = node.asString();
  if (const std::optional<CollisionMode> parsed = collisionModeFromName(mode)) {
    return *parsed;
  }
  node.fail("expected radius, fcl or radius_and_fcl, got " + quoteText(mode));
}

namespace detail {
namespace {

/// The keys of the configuration's top level, besides the named samplers' maps.
constexpr const char* kTopLevelKeys[] = {"frame_id",
                                         "tf_prefix",
                                         "seed",
                                         "collision_check",
                                         "collision_margin",
                                         "max_attempts",
                                         "objects",
                                         "fixtures",
                                         "samplers",
                                         "hide",
                                         "threads",
                                         "max_scenes_per_request",
                                         "max_request_seconds",
                                         "max_fixtures_per_request",
                                         "max_placements_per_request",
                                         "tf_static",
                                         "tf_rate",
                                         "physics",
                                         "physics_seconds",
                                         "physics_timestep",
                                         "physics_position_tolerance",
                                         "physics_rotation_tolerance",
                                         "physics_retry",
                                         "physics_max_draws",
                                         "physics_max_memory_mb",
                                         "ground_z",
                                         "density"};

}  // namespace

bool isTopLevelKey(const std::string& key) {
  for (const char* k : kTopLevelKeys) {
    if (key == k) {
      return true;
    }
  }
  return false;
}

std::vector<std::string> allowedTopLevelKeys(const ConfigNode& root) {
  std::vector<std::string> allowed(std::begin(kTopLevelKeys), std::end(kTopLevelKeys));
  if (const ConfigNode* n = root.get("samplers")) {
    collectNamedSamplers(root, *n, allowed);
  }
  return allowed;
}

// Walks the tree without recursion.
void checkTreeSize(const ConfigNode& root) {
  std::vector<std::pair<const ConfigNode*, int>> stack{{&root, 1}};
  std::size_t values = 0;
  while (!stack.empty()) {
    const ConfigNode& node = *stack.back().first;
    const int depth = stack.back().second;
    stack.pop_back();
    if (++values > limits::kConfigValues) {
      root.fail("more than " + std::to_string(limits::kConfigValues) +
                " values (maps, lists and scalars)");
    }
    if (depth > limits::kConfigDepth) {
      node.fail("nested too deep (more than " + std::to_string(limits::kConfigDepth) + " levels)");
    }
    if (node.isMap()) {
      for (const auto& entry : node.entries()) {
        stack.emplace_back(&entry.second, depth + 1);
      }
    } else if (node.isList()) {
      for (const ConfigNode& element : node.elements()) {
        stack.emplace_back(&element, depth + 1);
      }
    }
  }
}

void readSettings(const ConfigNode& root, SceneConfig& config) {
  if (const ConfigNode* n = root.get("frame_id")) {
    config.frameId = n->asString();
    if (config.frameId.empty()) {
      n->fail("expected a non-empty frame name");
    }
  }
  if (const ConfigNode* n = root.get("tf_prefix")) {
    config.tfPrefix = n->asString();
    if (!config.tfPrefix->empty() && config.tfPrefix->front() == '/') {
      n->fail("expected a prefix without a leading '/' (tf2 frame names have none), got '" +
              *config.tfPrefix + "'");
    }
  }
  if (const ConfigNode* n = root.get("seed")) {
    config.seed = n->asUInt64();
  }
  if (const ConfigNode* n = root.get("collision_check")) {
    config.collisionCheck = parseCollisionMode(*n);
  }
  if (const ConfigNode* n = root.get("collision_margin")) {
    config.collisionMargin = n->asDouble();
    try {
      checkCollisionMargin(config.collisionMargin);
    } catch (const ConfigError& e) {
      n->fail(e.what());
    }
  }
  if (const ConfigNode* n = root.get("max_attempts")) {
    config.maxAttempts =
        static_cast<std::uint32_t>(n->asInt(1, std::numeric_limits<std::uint32_t>::max()));
  }
  if (const ConfigNode* n = root.get("threads")) {
    config.threads = static_cast<unsigned>(n->asInt(1, 64));
  }
  if (const ConfigNode* n = root.get("max_scenes_per_request")) {
    config.maxScenesPerRequest = static_cast<std::uint32_t>(n->asInt(1, 100000000));
  }
  if (const ConfigNode* n = root.get("max_request_seconds")) {
    config.maxRequestSeconds = n->asDouble();
    // Bounded, so that now + the limit is a time point the clock can hold.
    if (config.maxRequestSeconds <= 0.0) {
      n->fail("expected a positive duration in [s]");
    }
    if (config.maxRequestSeconds > limits::kRequestSeconds) {
      std::ostringstream out;
      out << "expected a positive duration in [s] of at most " << limits::kRequestSeconds
          << ", got " << config.maxRequestSeconds;
      n->fail(out.str());
    }
  }
  if (const ConfigNode* n = root.get("max_fixtures_per_request")) {
    config.maxFixturesPerRequest = static_cast<std::uint32_t>(n->asInt(0, 1000000));
  }
  if (const ConfigNode* n = root.get("max_placements_per_request")) {
    config.maxPlacementsPerRequest = static_cast<std::uint64_t>(n->asInt(1, 1000000000));
  }
  if (const ConfigNode* n = root.get("tf_static")) {
    config.tfStatic = n->asBool();
  }
  if (const ConfigNode* n = root.get("tf_rate")) {
    config.tfRate = n->asDouble();
    if (!(config.tfRate >= 0.1 && config.tfRate <= 1000.0)) {
      n->fail("expected a rate in [0.1, 1000] [Hz]");
    }
  }
  readPhysicsSettings(root, config.physics);
}

}  // namespace detail
}  // namespace placement_samplers
