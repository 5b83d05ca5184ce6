#include "placement_samplers/ros/param_reader.hpp"

#include <cstdint>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

/// Recursive, so bounded: a tree nested deeper than the builder accepts is refused here.
void convert(XmlRpc::XmlRpcValue& in, ConfigNode& out, int depth) {
  if (depth > limits::kConfigDepth) {
    out.fail("nested too deep (more than " + std::to_string(limits::kConfigDepth) + " levels)");
  }
  switch (in.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      out.setBool(static_cast<bool>(in));
      return;
    case XmlRpc::XmlRpcValue::TypeInt:
      out.setInt(static_cast<int>(in));
      return;
    case XmlRpc::XmlRpcValue::TypeDouble:
      out.setDouble(static_cast<double>(in));
      return;
    case XmlRpc::XmlRpcValue::TypeString:
      out.setString(static_cast<std::string>(in));
      return;
    case XmlRpc::XmlRpcValue::TypeArray:
      out.setList();
      for (int i = 0; i < in.size(); ++i) {
        convert(in[i], out.append(), depth + 1);
      }
      return;
    case XmlRpc::XmlRpcValue::TypeStruct:
      out.setMap();
      for (auto& entry : in) {
        convert(entry.second, out.add(entry.first), depth + 1);
      }
      return;
    case XmlRpc::XmlRpcValue::TypeInvalid:
      out.setNull();
      return;
    default:
      out.fail("expected a boolean, number, string, list or map, got a date or binary value");
  }
}

}  // namespace

ConfigNode toConfigNode(XmlRpc::XmlRpcValue& value, const std::string& path) {
  ConfigNode root = ConfigNode::makeRoot(path, '/');
  convert(value, root, 1);
  return root;
}

XmlRpc::XmlRpcValue readParameterTree(const ros::NodeHandle& nodeHandle) {
  const std::string ns = nodeHandle.getNamespace();
  XmlRpc::XmlRpcValue value;
  if (!nodeHandle.getParam(ns, value) || value.getType() != XmlRpc::XmlRpcValue::TypeStruct ||
      value.size() == 0) {
    throw ConfigError(ns +
                      ": no configuration parameters here; load one first, for example with "
                      "`rosparam load config/default.yaml " +
                      ns + "` or launch/placement_server.launch");
  }
  return value;
}

ConfigNode readParameters(const ros::NodeHandle& nodeHandle) {
  XmlRpc::XmlRpcValue value = readParameterTree(nodeHandle);
  return toConfigNode(value, nodeHandle.getNamespace());
}

std::string treeDigest(XmlRpc::XmlRpcValue& tree) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const char c : tree.toXml()) {
    hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  }
  static const char* const kHex = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 15; i >= 0; --i, hash >>= 4) {
    out[static_cast<std::size_t>(i)] = kHex[hash & 15u];
  }
  return out;
}

}  // namespace ros_interface
}  // namespace placement_samplers
