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

/// The private namespace of @p nodeHandle as rosparam holds it, to change before it is built
/// (toConfigNode() with the namespace as the path).
/// @throw ConfigError when the namespace holds no parameters
XmlRpc::XmlRpcValue readParameterTree(const ros::NodeHandle& nodeHandle);

/// A digest of a parameter tree: 16 hex digits of FNV-1a (64 bit) over its XML-RPC text, in
/// which maps are sorted by key. The same parameters give the same digest.
std::string treeDigest(XmlRpc::XmlRpcValue& tree);

}  // namespace ros_interface
}  // namespace placement_samplers
