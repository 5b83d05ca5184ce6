// /diagnostics' status without a master: levels, their messages and the values; and the
// action's goal and result as the service's request and response.

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "placement_samplers/ros/node_diagnostics.hpp"
#include "placement_samplers/ros/sample_action.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

using Status = diagnostic_msgs::DiagnosticStatus;

struct Seen {
  int level = -1;
  std::string message;
  std::map<std::string, std::string> values;
};

Seen seen(const NodeDiagnostics& diagnostics) {
  diagnostic_updater::DiagnosticStatusWrapper status;
  diagnostics.fill(status);
  Seen out;
  out.level = status.level;
  out.message = status.message;
  for (const auto& kv : status.values) {
    out.values[kv.key] = kv.value;
  }
  return out;
}

CallRecord scenes(std::size_t total, std::size_t failed, double seconds = 0.01) {
  CallRecord call;
  call.seconds = seconds;
  for (std::size_t i = 0; i < total; ++i) {
    call.sceneFailed.push_back(i < failed);
  }
  return call;
}

TEST(NodeDiagnostics, OkWithItsValues) {
  NodeDiagnostics d(4);
  d.served("0123456789abcdef", false);
  Seen s = seen(d);
  EXPECT_EQ(s.level, Status::OK);
  EXPECT_EQ(s.message, "serving");
  EXPECT_EQ(s.values.at("calls"), "0");
  EXPECT_EQ(s.values.at("threads busy"), "0 of 4");
  EXPECT_EQ(s.values.at("configuration digest"), "0123456789abcdef");
  EXPECT_EQ(s.values.at("last error"), "");
  d.callStarted();
  EXPECT_EQ(seen(d).values.at("threads busy"), "1 of 4");
  d.callFinished(scenes(100, 10));  // 10 % is not above the limit
  s = seen(d);
  EXPECT_EQ(s.level, Status::OK);
  EXPECT_EQ(s.values.at("calls"), "1");
  EXPECT_EQ(s.values.at("scenes"), "100");
  EXPECT_EQ(s.values.at("failure rate (last 100 scenes)"), "0.100");
  EXPECT_EQ(s.values.at("threads busy"), "0 of 4");
}

TEST(NodeDiagnostics, LatencyPercentiles) {
  NodeDiagnostics d(1);
  for (int i = 1; i <= 100; ++i) {
    d.callFinished(scenes(1, 0, i * 0.001));
  }
  const Seen s = seen(d);
  EXPECT_EQ(s.values.at("latency p50 [s]"), "0.050000");
  EXPECT_EQ(s.values.at("latency p99 [s]"), "0.099000");
}

TEST(NodeDiagnostics, WarnsOnFailuresOfTheLastHundredScenes) {
  NodeDiagnostics d(1);
  d.callFinished(scenes(1000, 0));
  d.callFinished(scenes(100, 11));
  Seen s = seen(d);
  EXPECT_EQ(s.level, Status::WARN);
  EXPECT_EQ(s.message, "11 of the last 100 scenes failed");
  // Only the last hundred count: 100 placed scenes end the warning.
  d.callFinished(scenes(100, 0));
  EXPECT_EQ(seen(d).level, Status::OK);
}

TEST(NodeDiagnostics, WarnsOnARequestRefusedForItsSize) {
  NodeDiagnostics d(1);
  CallRecord refused;
  refused.refusedForSize = true;
  refused.error = "num_scenes 100000 exceeds max_scenes_per_request (500)";
  d.callFinished(refused);
  const Seen s = seen(d);
  EXPECT_EQ(s.level, Status::WARN);
  EXPECT_EQ(s.message, "a request was refused for its size 0 s ago");
  EXPECT_EQ(s.values.at("last error"), refused.error);
}

TEST(NodeDiagnostics, ErrorWhileTheLastReloadFailedOrTheMasterIsLost) {
  NodeDiagnostics d(1);
  d.callFinished(scenes(10, 5));
  d.reloadFailed("/n/max_attempts: expected an integer in [1, 4294967295], got 0");
  Seen s = seen(d);
  EXPECT_EQ(s.level, Status::ERROR);
  EXPECT_EQ(s.message,
            "5 of the last 10 scenes failed; the last reload failed: /n/max_attempts: expected an "
            "integer in [1, 4294967295], got 0");
  // A refused knob or handle leaves the node serving: the last error, no level.
  d.served("d2", false);
  EXPECT_EQ(seen(d).level, Status::ERROR);
  d.served("d2", true);
  EXPECT_EQ(seen(d).level, Status::WARN);
  d.refused("/n/collision_margin: bad");
  s = seen(d);
  EXPECT_EQ(s.level, Status::WARN);
  EXPECT_EQ(s.values.at("last error"), "/n/collision_margin: bad");
  d.setMasterUp(false);
  EXPECT_EQ(seen(d).level, Status::ERROR);
  d.setMasterUp(true);
  EXPECT_EQ(seen(d).level, Status::WARN);
}

TEST(SampleAction, GoalAndResultAreTheServiceFields) {
  SampleScenesGoal goal;
  goal.sampler = "TableSampler";
  goal.seed = 42;
  goal.num_scenes = 7;
  goal.first_scene = 3;
  goal.fixtures.resize(2);
  goal.fixtures[1].name = "box";
  goal.reference = "table";
  goal.reference_point.y = 0.5;
  goal.use_reference_point = true;
  goal.on_top = SampleScenesGoal::ON_TOP_FALSE;
  goal.collision_check = SampleScenesGoal::CHECK_FCL;
  goal.max_attempts = 11;
  goal.dry_run = true;
  goal.physics = SampleScenesGoal::PHYSICS_SETTLE;
  const SamplePlacements::Request r = toServiceRequest(goal);
  EXPECT_EQ(r.sampler, goal.sampler);
  EXPECT_EQ(r.seed, goal.seed);
  EXPECT_EQ(r.num_scenes, goal.num_scenes);
  EXPECT_EQ(r.first_scene, goal.first_scene);
  EXPECT_EQ(r.fixtures, goal.fixtures);
  EXPECT_EQ(r.reference, goal.reference);
  EXPECT_EQ(r.reference_point, goal.reference_point);
  EXPECT_EQ(r.use_reference_point, goal.use_reference_point);
  EXPECT_EQ(r.on_top, SamplePlacements::Request::ON_TOP_FALSE);
  EXPECT_EQ(r.collision_check, SamplePlacements::Request::CHECK_FCL);
  EXPECT_EQ(r.max_attempts, goal.max_attempts);
  EXPECT_EQ(r.dry_run, goal.dry_run);
  EXPECT_EQ(r.physics, SamplePlacements::Request::PHYSICS_SETTLE);

  SamplePlacements::Response response;
  response.success = true;
  response.message = "note";
  response.seed = 9;
  response.frame_id = "table";
  response.scenes.resize(3);
  response.scenes[2].message = "third";
  const SampleScenesResult result = toResult(response);
  EXPECT_EQ(result.success, response.success);
  EXPECT_EQ(result.message, response.message);
  EXPECT_EQ(result.seed, response.seed);
  EXPECT_EQ(result.frame_id, response.frame_id);
  EXPECT_EQ(result.scenes, response.scenes);
}

}  // namespace
}  // namespace ros_interface
}  // namespace placement_samplers
