#pragma once

#include <XmlRpcValue.h>
#include <ros/node_handle.h>

#include <string>

#include "placement_samplers/config/config_node.hpp"

namespace placement_samplers {
namespace ros_interface {

/// Converts an XmlRpc value (a rosparam tree) into a ConfigNode whose paths are parameter names:
/// children of @p path are "<path>/<key>" and "<path>[i]".
/// @throw ConfigError for value types rosparam cannot hold in a configuration (dates, binary)
ConfigNode toConfigNode(XmlRpc::XmlRpcValue& value, const std::string& path);

/// Reads the whole private namespace of @p nodeHandle as a configuration tree.
/// @throw ConfigError when the namespace holds no parameters
ConfigNode readParameters(const ros::NodeHandle& nodeHandle);

}  // namespace ros_interface
}  // namespace placement_samplers
