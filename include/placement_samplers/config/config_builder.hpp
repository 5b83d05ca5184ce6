#pragma once

#include <functional>
#include <memory>
#include <string>

#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/config/object_config.hpp"
#include "placement_samplers/sampling/scene_config.hpp"

namespace placement_samplers {

/// Builds a SceneConfig from the configuration schema (see README, "Configuration").
/// Validates everything once: types, ranges, names, references; unknown keys are errors.
/// @throw ConfigError naming the full parameter path and what was expected
std::shared_ptr<SceneConfig> buildSceneConfig(const ConfigNode& root);

/// buildSceneConfig with the sources of URDF parameters, packages and relative paths: the node
/// passes a urdfParam reader, the CLI the configuration file's directory. Each mesh file is
/// read once per build.
/// @throw ConfigError naming the full parameter path and what was expected
std::shared_ptr<SceneConfig> buildSceneConfig(const ConfigNode& root, const BuildOptions& options);

/// Parses a collision mode name.
/// @throw ConfigError naming @p node when it is not radius, fcl or radius_and_fcl
CollisionMode parseCollisionMode(const ConfigNode& node);

/// Parses a physics mode name.
/// @throw ConfigError naming @p node when it is not none, check or settle
PhysicsMode parsePhysicsMode(const ConfigNode& node);

}  // namespace placement_samplers
