#pragma once
// Pieces of the configuration builder (config_builder.cpp), one file each: the top-level
// settings, the items of a samplers list, a uniform sampler's parameters. Private to the core.

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/sampling/scene_config.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"

namespace placement_samplers::detail {

/// True for a key of the configuration's top level (not a named sampler's map).
bool isTopLevelKey(const std::string& key);

/// The allowed top-level keys: the fixed ones and the names of the named samplers.
std::vector<std::string> allowedTopLevelKeys(const ConfigNode& root);

/// Refuses a tree (from rosparam or YAML) of more than limits::kConfigValues values or nested
/// more than limits::kConfigDepth levels.
void checkTreeSize(const ConfigNode& root);

/// Reads the top-level settings (frame_id, seed, collision_check, limits, tf options) into
/// @p config; objects, fixtures and samplers are the builder's.
void readSettings(const ConfigNode& root, SceneConfig& config);

/// Bounds of the physics settings (README, "Physics").
constexpr double kMaxPhysicsSeconds = 60.0;   ///< simulated time per scene [s]
constexpr double kMaxPhysicsTimestep = 0.1;   ///< [s]
constexpr double kMinPhysicsTimestep = 1e-4;  ///< [s]
/// [kg/m^3]: about air's (1.2); anything lighter would float away rather than rest. It keeps
/// MuJoCo's body masses finite and positive (MuJoCo refuses bodies lighter than 1e-15 kg).
constexpr double kMinDensity = 1.0;
constexpr double kMaxDensity = 1e5;  ///< [kg/m^3] (osmium: 22,590)
/// MuJoCo data of one request's simulations [MiB] (physics_max_memory_mb).
constexpr std::int64_t kMinPhysicsMemoryMb = 16;
constexpr std::int64_t kMaxPhysicsMemoryMb = 1 << 20;

/// Reads the physics keys (physics, physics_seconds, physics_timestep, the tolerances,
/// physics_retry, physics_max_draws, physics_max_memory_mb, ground_z, density) into @p physics.
void readPhysicsSettings(const ConfigNode& root, PhysicsSettings& physics);

/// A density in [kMinDensity, kMaxDensity] [kg/m^3]: the top-level default or an object's own.
double parseDensity(const ConfigNode& node);

/// Adds to @p names the names of samplers in @p list (and nested lists) whose parameters live
/// in a top-level map of their own.
void collectNamedSamplers(const ConfigNode& root, const ConfigNode& list,
                          std::vector<std::string>& names);

/// One item of a samplers list: where its parameters are read and what names it.
struct SamplerItem {
  const ConfigNode* params;    ///< the inline map, or the top-level map of its name
  const ConfigNode* nameNode;  ///< errors about the name point here
  const ConfigNode* typeNode;  ///< `type` given in the list item of the named form, or null
  bool named;                  ///< parameters in a top-level map of its name
  std::string name;
};

/// Where the parameters of list item @p item are: inline, or in the top-level map of its name.
SamplerItem resolveSamplerItem(const ConfigNode& root, const ConfigNode& item);

/// Unknown keys are typos; `name` is the map's key in the named form.
void checkSamplerKeys(const SamplerItem& s, std::vector<std::string> allowed);

/// A uniform sampler's own parameters (ranges, rotation, flags); @p maxAttempts is the
/// configuration's default.
UniformSamplerParams parseUniformParams(const ConfigNode& s, std::uint32_t maxAttempts,
                                        const std::string& name = "");

/// A uniform sampler's `relations:` list (README, "Relations"): each item's keys and values.
std::vector<Relation> parseRelations(const ConfigNode& list, const std::string& sampler);

/// Checks the targets of @p relations (read from @p list) of sampler @p sampler placing
/// @p objects in that order: a configured fixture, an object an earlier sampler places
/// (@p available) or one of @p objects before each object a relation applies to; objects:
/// lists name @p objects. Errors name the relation and say what was expected; a target placed
/// after its object is a cycle when the relations lead back.
void checkRelationTargets(const ConfigNode& list, const std::vector<Relation>& relations,
                          const std::string& sampler, const std::vector<ObjectPtr>& objects,
                          const std::set<std::string>& available, const SceneConfig& config);

/// A [min, max] pair with min <= max.
Eigen::Vector2d parseRange(const ConfigNode& n);

}  // namespace placement_samplers::detail
