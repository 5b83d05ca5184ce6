// rosparam trees into ConfigNodes, without a master: value types, parameter-name paths in
// errors, date values refused, nesting bounded.

#include <gtest/gtest.h>

#include <XmlRpcValue.h>

#include <string>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/ros/param_reader.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

/// The message of the ConfigError @p f throws, or "" when it throws none.
template <typename F>
std::string configError(F f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ParamReader, KeepsEveryValueTypeAndNamesPathsAsParameters) {
  XmlRpc::XmlRpcValue root;
  root["seed"] = 7;
  root["collision_margin"] = 0.25;
  root["collision_check"] = std::string("fcl");
  root["flag"] = true;
  XmlRpc::XmlRpcValue sampler;
  sampler["name"] = std::string("TableSampler");
  sampler["x_range"][0] = -0.1;
  sampler["x_range"][1] = 0.1;
  root["samplers"][0] = sampler;

  const ConfigNode node = toConfigNode(root, "/placement_server");
  EXPECT_EQ(node.at("seed").asInt(0, 100), 7);
  EXPECT_EQ(node.at("collision_margin").asDouble(), 0.25);
  EXPECT_EQ(node.at("collision_check").asString(), "fcl");
  EXPECT_TRUE(node.at("flag").asBool());
  const ConfigNode& s = node.at("samplers").elements().at(0);
  EXPECT_EQ(s.at("name").asString(), "TableSampler");
  EXPECT_EQ(s.at("x_range").elements().size(), 2u);
  EXPECT_EQ(s.at("x_range").path(), "/placement_server/samplers[0]/x_range");
  const std::string error = configError([&] { s.at("name").asDouble(); });
  EXPECT_NE(error.find("/placement_server/samplers[0]/name"), std::string::npos) << error;
}

TEST(ParamReader, RefusesDatesAndTreesNestedTooDeep) {
  XmlRpc::XmlRpcValue root;
  struct tm when = {};
  root["when"] = XmlRpc::XmlRpcValue(&when);
  const std::string date = configError([&] { toConfigNode(root, "/ns"); });
  EXPECT_NE(date.find("/ns/when"), std::string::npos) << date;
  EXPECT_NE(date.find("date or binary"), std::string::npos) << date;

  XmlRpc::XmlRpcValue deep;
  XmlRpc::XmlRpcValue* level = &deep;
  for (int i = 0; i <= limits::kConfigDepth + 1; ++i) {
    level = &(*level)["a"];
  }
  *level = 1;
  const std::string nested = configError([&] { toConfigNode(deep, "/ns"); });
  EXPECT_NE(nested.find("nested too deep"), std::string::npos) << nested;
}

}  // namespace
}  // namespace ros_interface
}  // namespace placement_samplers
