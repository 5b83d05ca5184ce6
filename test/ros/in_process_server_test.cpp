// A PlacementServer inside the test process, so that a hook can hold a call at an exact point:
// a call that samples before a ~reload and ends after it does not show its scene.
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <future>
#include <mutex>
#include <optional>

#include "node_test_helpers.hpp"
#include "placement_samplers/PlacedScene.h"
#include "placement_samplers/ros/placement_server.hpp"

namespace {

using namespace placement_samplers;
using placement_samplers::ros_interface::PlacementServer;
using placement_samplers::test::seeded;
using placement_samplers::test::waitFor;

class SceneCounter {
 public:
  explicit SceneCounter(const std::string& topic)
      : subscriber_(
            handle_.subscribe<PlacedScene>(topic, 10, [this](const PlacedScene::ConstPtr& m) {
              std::lock_guard<std::mutex> lock(mutex_);
              seeds_.push_back(m->seed);
            })) {}
  std::vector<std::uint64_t> seeds() {
    std::lock_guard<std::mutex> lock(mutex_);
    return seeds_;
  }

 private:
  ros::NodeHandle handle_;
  ros::Subscriber subscriber_;
  std::mutex mutex_;
  std::vector<std::uint64_t> seeds_;
};

TEST(InProcessServer, ACallThatOutlivesAReloadDoesNotShowItsScene) {
  PlacementServer server(ros::NodeHandle("/in_process_server"));
  server.start();
  SceneCounter scenes("/in_process_server/scene");

  // The hook holds the call after sampling, before its scene is queued, until the reload ran.
  std::promise<void> entered;
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  bool first = true;
  server.setBeforeShowHook([&] {
    if (first) {
      first = false;
      entered.set_value();
      released.wait();
    }
  });
  SamplePlacements::Request request = seeded(11);
  SamplePlacements::Response response;
  auto call = std::async(std::launch::async, [&] { server.sample(request, response); });
  ASSERT_EQ(entered.get_future().wait_for(std::chrono::seconds(20)), std::future_status::ready);
  std_srvs::Trigger::Request reloadRequest;
  std_srvs::Trigger::Response reloadResponse;
  server.reload(reloadRequest, reloadResponse);
  ASSERT_TRUE(reloadResponse.success) << reloadResponse.message;
  release.set_value();
  call.get();
  EXPECT_TRUE(response.success);
  EXPECT_EQ(response.message, "not shown: the configuration was reloaded during the call");
  ros::WallDuration(1.0).sleep();
  // The reload's empty scene (seed 0) only: the held call's scene (seed 11) was not shown.
  EXPECT_EQ(scenes.seeds(), std::vector<std::uint64_t>{0}) << "a scene of the old configuration "
                                                              "was shown";

  // The next call belongs to the new configuration and is shown.
  SamplePlacements::Request next = seeded(12);
  SamplePlacements::Response nextResponse;
  server.sample(next, nextResponse);
  EXPECT_TRUE(nextResponse.success);
  EXPECT_EQ(nextResponse.message, "");
  EXPECT_TRUE(waitFor([&] { return scenes.seeds().size() == 2; }, 10.0));
  EXPECT_EQ(scenes.seeds(), (std::vector<std::uint64_t>{0, 12}));
}

}  // namespace

int main(int argc, char** argv) {
  return placement_samplers::test::runNodeTests(argc, argv, "in_process_server_test");
}
