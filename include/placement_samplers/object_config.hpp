#pragma once

#include <string>

#include "placement_samplers/config_node.hpp"
#include "placement_samplers/object_model.hpp"

namespace placement_samplers {

/// Builds the object @p name from its configuration entry: a primitive (`shape: box | cylinder |
/// sphere | capsule` with its sizes), plus optional overrides and init_orientation [x, y, z, w].
/// @throw ConfigError naming the parameter and what was expected
ObjectModel parseObject(const std::string& name, const ConfigNode& node);

/// A unit quaternion from [x, y, z, w]; its norm must be 1 within 1e-3, and it is normalized.
/// @throw ConfigError naming @p node otherwise
Eigen::Quaterniond parseQuaternion(const ConfigNode& node);

/// Checks a primitive's sizes: finite and positive.
/// @throw std::invalid_argument saying which size is wrong
void validateShape(const Shape& shape);

}  // namespace placement_samplers
