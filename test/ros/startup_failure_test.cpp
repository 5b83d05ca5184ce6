// A bad configuration at start-up: the node exits non-zero and names the parameter.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace {

struct NodeRun {
  int status = -1;
  std::string output;
};

NodeRun runNode(const std::string& name) {
  const std::string command =
      std::string("timeout 30 ") + PLACEMENT_SERVER_BIN + " __name:=" + name + " 2>&1";
  NodeRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    return run;
  }
  std::array<char, 512> buffer;
  while (fgets(buffer.data(), buffer.size(), pipe) != nullptr) {
    run.output += buffer.data();
  }
  const int status = pclose(pipe);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

TEST(PlacementServerStartup, ReversedRangeExitsNonZeroNamingTheParameter) {
  ros::NodeHandle nh;
  XmlRpc::XmlRpcValue sampler;
  sampler["name"] = "S";
  sampler["x_range"][0] = 0.3;
  sampler["x_range"][1] = -0.3;
  XmlRpc::XmlRpcValue samplers;
  samplers[0] = sampler;
  nh.setParam("/bad_server/samplers", samplers);
  const NodeRun run = runNode("bad_server");
  EXPECT_EQ(run.status, 1) << run.output;
  // Named after the node as it runs, not the name it was compiled with.
  EXPECT_NE(run.output.find("/bad_server: invalid configuration: /bad_server/samplers[0]/x_range: "
                            "expected [min, max] with min <= max, got [0.3, -0.3]"),
            std::string::npos)
      << run.output;
  EXPECT_EQ(run.output.find("placement_server:"), std::string::npos) << run.output;
}

TEST(PlacementServerStartup, UnknownKeyExitsNonZeroNamingIt) {
  ros::NodeHandle nh;
  nh.setParam("/typo_server/objects/cube/shape", std::string("box"));
  nh.setParam("/typo_server/objects/cube/size", std::vector<double>{0.1, 0.1, 0.1});
  nh.setParam("/typo_server/max_atempts", 10);
  const NodeRun run = runNode("typo_server");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("/typo_server: unknown key 'max_atempts'"), std::string::npos)
      << run.output;
}

TEST(PlacementServerStartup, NoParametersExitsNonZero) {
  const NodeRun run = runNode("empty_server");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("/empty_server: no configuration parameters here"), std::string::npos)
      << run.output;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "startup_failure_test");
  return RUN_ALL_TESTS();
}
