// The node's live interfaces through a real master: the ~sample action (feedback, result,
// cancel, side by side and preemption), /diagnostics' levels, dynamic_reconfigure and the
// region handles' interactive markers.
#include <actionlib/client/simple_action_client.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>

#include <cmath>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "placement_samplers/PlacedScene.h"
#include "placement_samplers/SamplePlacements.h"
#include "placement_samplers/SampleScenesAction.h"
#include "node_test_helpers.hpp"

namespace {

using placement_samplers::SamplePlacements;
using placement_samplers::SampleScenesAction;
using placement_samplers::SampleScenesFeedback;
using placement_samplers::SampleScenesFeedbackConstPtr;
using placement_samplers::SampleScenesGoal;
using placement_samplers::test::callService;
using placement_samplers::test::waitFor;
using Client = actionlib::SimpleActionClient<SampleScenesAction>;
using State = actionlib::SimpleClientGoalState;

/// A client of @p node's ~sample that records the feedback of its goal.
class Goal {
 public:
  explicit Goal(const std::string& node) : client_("/" + node + "/sample", false) {
    EXPECT_TRUE(client_.waitForServer(ros::Duration(30.0)));
  }
  void send(const SampleScenesGoal& goal) {
    client_.sendGoal(goal, Client::SimpleDoneCallback(), Client::SimpleActiveCallback(),
                     [this](const SampleScenesFeedbackConstPtr& f) {
                       std::lock_guard<std::mutex> lock(mutex_);
                       feedback_.push_back(*f);
                     });
  }
  std::vector<SampleScenesFeedback> feedback() {
    std::lock_guard<std::mutex> lock(mutex_);
    return feedback_;
  }
  std::uint64_t done() {
    std::lock_guard<std::mutex> lock(mutex_);
    return feedback_.empty() ? 0 : feedback_.back().scenes_done;
  }
  Client& client() { return client_; }

 private:
  Client client_;
  std::mutex mutex_;
  std::vector<SampleScenesFeedback> feedback_;
};

SampleScenesGoal physicsGoal(std::uint64_t seed, std::uint32_t scenes) {
  SampleScenesGoal goal;
  goal.seed = seed;
  goal.num_scenes = scenes;
  goal.physics = SampleScenesGoal::PHYSICS_CHECK;
  goal.dry_run = true;
  return goal;
}

/// The service request with the goal's fields.
SamplePlacements::Request asRequest(const SampleScenesGoal& goal) {
  SamplePlacements::Request r;
  r.seed = goal.seed;
  r.num_scenes = goal.num_scenes;
  r.first_scene = goal.first_scene;
  r.physics = goal.physics;
  r.dry_run = goal.dry_run;
  return r;
}

TEST(SampleAction, FeedbackIsMonotonicAndTheResultIsTheServiceAnswer) {
  Goal goal("action_server");
  const SampleScenesGoal sent = physicsGoal(77, 100);
  goal.send(sent);
  ASSERT_TRUE(goal.client().waitForResult(ros::Duration(180.0)));
  EXPECT_EQ(goal.client().getState(), State::SUCCEEDED);
  const auto result = goal.client().getResult();
  const SamplePlacements srv = callService("/action_server/sample_placements", asRequest(sent));
  EXPECT_EQ(result->success, srv.response.success);
  EXPECT_EQ(result->message, srv.response.message);
  EXPECT_EQ(result->seed, 77u);
  EXPECT_EQ(result->frame_id, srv.response.frame_id);
  ASSERT_EQ(result->scenes.size(), 100u);
  EXPECT_TRUE(result->scenes == srv.response.scenes);
  EXPECT_TRUE(result->scenes[0].simulated);

  const std::vector<SampleScenesFeedback> feedback = goal.feedback();
  ASSERT_GE(feedback.size(), 2u);  // a hundred simulated scenes take far longer than 0.1 s
  for (std::size_t i = 0; i < feedback.size(); ++i) {
    EXPECT_LE(feedback[i].scenes_done, 100u);
    EXPECT_LE(feedback[i].scenes_failed, feedback[i].scenes_done);
    EXPECT_EQ(feedback[i].remaining < 0.0, feedback[i].scenes_done == 0);
    if (i > 0) {
      EXPECT_GE(feedback[i].scenes_done, feedback[i - 1].scenes_done);
      EXPECT_GE(feedback[i].scenes_failed, feedback[i - 1].scenes_failed);
      EXPECT_GT(feedback[i].elapsed, feedback[i - 1].elapsed);
    }
  }
  EXPECT_GT(feedback.back().scenes_done, 0u);
}

TEST(SampleAction, CancelReturnsTheScenesDoneAtOnce) {
  Goal goal("action_server");
  const SampleScenesGoal sent = physicsGoal(5, 5000);
  goal.send(sent);
  ASSERT_TRUE(waitFor([&] { return goal.done() >= 10; }, 120.0));
  const ros::WallTime cancelled = ros::WallTime::now();
  goal.client().cancelGoal();
  ASSERT_TRUE(goal.client().waitForResult(ros::Duration(30.0)));
  const double took = (ros::WallTime::now() - cancelled).toSec();
  EXPECT_LT(took, 1.0) << "the result came " << took << " s after the cancel";
  EXPECT_EQ(goal.client().getState(), State::PREEMPTED);
  const auto result = goal.client().getResult();
  EXPECT_FALSE(result->success);
  const std::size_t n = result->scenes.size();
  EXPECT_GE(n, 5u);
  EXPECT_LT(n, 5000u);
  EXPECT_EQ(result->message.rfind("cancelled after " + std::to_string(n) + " of 5000 scenes", 0),
            0u)
      << result->message;
  // The scenes done are the service's first n scenes of the seed.
  SamplePlacements::Request first = asRequest(sent);
  first.num_scenes = static_cast<std::uint32_t>(n);
  const SamplePlacements srv = callService("/action_server/sample_placements", first);
  EXPECT_TRUE(result->scenes == srv.response.scenes);
}

TEST(SampleAction, GoalsRunSideBySideWithSeveralThreads) {
  Goal longGoal("action_server");
  longGoal.send(physicsGoal(6, 5000));
  ASSERT_TRUE(waitFor([&] { return longGoal.done() >= 1; }, 120.0));
  Goal shortGoal("action_server");
  shortGoal.send(physicsGoal(7, 2));
  ASSERT_TRUE(shortGoal.client().waitForResult(ros::Duration(60.0)));
  EXPECT_EQ(shortGoal.client().getState(), State::SUCCEEDED);
  EXPECT_EQ(longGoal.client().getState(), State::ACTIVE);
  longGoal.client().cancelGoal();
  ASSERT_TRUE(longGoal.client().waitForResult(ros::Duration(30.0)));
  EXPECT_EQ(longGoal.client().getState(), State::PREEMPTED);
}

TEST(SampleAction, ANewGoalPreemptsTheRunningOneWithOneThread) {
  Goal first("single_server");
  first.send(physicsGoal(8, 5000));
  ASSERT_TRUE(waitFor([&] { return first.done() >= 2; }, 120.0));
  Goal second("single_server");
  second.send(physicsGoal(9, 2));
  ASSERT_TRUE(first.client().waitForResult(ros::Duration(30.0)));
  EXPECT_EQ(first.client().getState(), State::PREEMPTED);
  const auto preempted = first.client().getResult();
  EXPECT_FALSE(preempted->success);
  EXPECT_GE(preempted->scenes.size(), 2u);
  EXPECT_EQ(
      preempted->message.rfind("preempted by a newer goal (threads is 1); cancelled after ", 0), 0u)
      << preempted->message;
  ASSERT_TRUE(second.client().waitForResult(ros::Duration(60.0)));
  EXPECT_EQ(second.client().getState(), State::SUCCEEDED);
  EXPECT_EQ(second.client().getResult()->scenes.size(), 2u);
}

/// The latest status of @p node on /diagnostics.
class Diagnostics {
 public:
  explicit Diagnostics(const std::string& node) : name_(node + ": placement server") {
    subscriber_ = ros::NodeHandle().subscribe<diagnostic_msgs::DiagnosticArray>(
        "/diagnostics", 10, [this](const diagnostic_msgs::DiagnosticArrayConstPtr& array) {
          for (const auto& status : array->status) {
            if (status.name == name_) {
              std::lock_guard<std::mutex> lock(mutex_);
              latest_ = status;
              seen_ = true;
            }
          }
        });
  }
  /// Waits for a status at @p level (no older than the call) and returns it.
  diagnostic_msgs::DiagnosticStatus waitForLevel(int level) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      seen_ = false;
    }
    diagnostic_msgs::DiagnosticStatus out;
    const bool ok = waitFor(
        [&] {
          std::lock_guard<std::mutex> lock(mutex_);
          out = latest_;
          return seen_ && latest_.level == level;
        },
        15.0);
    EXPECT_TRUE(ok) << "level " << level << " not seen; the last: " << int(out.level) << " "
                    << out.message;
    return out;
  }

 private:
  std::string name_;
  ros::Subscriber subscriber_;
  std::mutex mutex_;
  diagnostic_msgs::DiagnosticStatus latest_;
  bool seen_ = false;
};

std::map<std::string, std::string> values(const diagnostic_msgs::DiagnosticStatus& status) {
  std::map<std::string, std::string> out;
  for (const auto& kv : status.values) {
    out[kv.key] = kv.value;
  }
  return out;
}

bool reload(const std::string& node) {
  std_srvs::Trigger trigger;
  EXPECT_TRUE(ros::service::call("/" + node + "/reload", trigger));
  return trigger.response.success;
}

TEST(NodeDiagnostics, EachLevelOnDiagnostics) {
  Diagnostics diagnostics("diag_server");
  auto status = diagnostics.waitForLevel(diagnostic_msgs::DiagnosticStatus::OK);
  EXPECT_EQ(status.message, "serving");
  EXPECT_EQ(status.hardware_id, "/diag_server");
  const std::string digest = values(status).at("configuration digest");
  EXPECT_EQ(digest.size(), 16u);
  EXPECT_EQ(values(status).at("threads busy"), "0 of 4");

  // Every scene fails under a wall over the table: the node gives up after 32 of them.
  SamplePlacements::Request walled = placement_samplers::test::seeded(3, 50);
  walled.fixtures.push_back(placement_samplers::test::tableCoveringWall());
  walled.dry_run = true;
  EXPECT_FALSE(callService("/diag_server/sample_placements", walled).response.success);
  status = diagnostics.waitForLevel(diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_EQ(status.message, "32 of the last 32 scenes failed");
  EXPECT_EQ(values(status).at("calls"), "1");
  EXPECT_EQ(values(status).at("scenes"), "32");
  EXPECT_EQ(values(status).at("last error").rfind("gave up: the first 32 of 50 scenes", 0), 0u);

  // A bad ~reload: ERROR until a good one.
  ros::param::set("/diag_server/max_attempts", 0);
  EXPECT_FALSE(reload("diag_server"));
  status = diagnostics.waitForLevel(diagnostic_msgs::DiagnosticStatus::ERROR);
  EXPECT_NE(status.message.find("the last reload failed: /diag_server/max_attempts: "),
            std::string::npos)
      << status.message;
  ros::param::set("/diag_server/max_attempts", 4000);
  EXPECT_TRUE(reload("diag_server"));
  status = diagnostics.waitForLevel(diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_NE(values(status).at("configuration digest"), digest);
}

/// Sets knobs of /knob_server through dynamic_reconfigure's service, as dynparam does.
dynamic_reconfigure::Config reconfigure(const std::map<std::string, std::string>& strings,
                                        const std::map<std::string, double>& doubles) {
  dynamic_reconfigure::Reconfigure srv;
  for (const auto& kv : strings) {
    dynamic_reconfigure::StrParameter p;
    p.name = kv.first;
    p.value = kv.second;
    srv.request.config.strs.push_back(p);
  }
  for (const auto& kv : doubles) {
    dynamic_reconfigure::DoubleParameter p;
    p.name = kv.first;
    p.value = kv.second;
    srv.request.config.doubles.push_back(p);
  }
  EXPECT_TRUE(ros::service::call("/knob_server/set_parameters", srv));
  return srv.response.config;
}

template <typename T, typename Param>
T valueIn(const std::vector<Param>& params, const std::string& name) {
  for (const Param& p : params) {
    if (p.name == name) {
      return p.value;
    }
  }
  ADD_FAILURE() << name << " is not in the answer";
  return T();
}

TEST(Reconfigure, AKnobChangesTheNextAnswerAndTheParameter) {
  ASSERT_TRUE(ros::service::waitForService("/knob_server/set_parameters", ros::Duration(30.0)));
  SamplePlacements::Request request = placement_samplers::test::seeded(4);
  request.dry_run = true;
  EXPECT_FALSE(
      callService("/knob_server/sample_placements", request).response.scenes.at(0).simulated);
  dynamic_reconfigure::Config config = reconfigure({{"physics", "check"}}, {});
  EXPECT_EQ(valueIn<std::string>(config.strs, "physics"), "check");
  std::string physics;
  EXPECT_TRUE(ros::param::get("/knob_server/physics", physics));
  EXPECT_EQ(physics, "check");
  EXPECT_TRUE(
      callService("/knob_server/sample_placements", request).response.scenes.at(0).simulated);

  // A value the configuration refuses: every knob stays, and the configuration's message is
  // the node's last error.
  Diagnostics diagnostics("knob_server");
  config = reconfigure({}, {{"collision_margin", -1.0}});
  EXPECT_EQ(valueIn<double>(config.doubles, "collision_margin"), 0.0);
  EXPECT_EQ(valueIn<std::string>(config.strs, "physics"), "check");
  double margin = -2.0;
  EXPECT_TRUE(ros::param::get("/knob_server/collision_margin", margin));
  EXPECT_EQ(margin, 0.0);
  const auto status = diagnostics.waitForLevel(diagnostic_msgs::DiagnosticStatus::OK);
  EXPECT_EQ(values(status).at("last error"),
            "/knob_server/collision_margin: expected a finite, non-negative clearance in [m] of "
            "at most 1e+06, got -1");
  EXPECT_TRUE(
      callService("/knob_server/sample_placements", request).response.scenes.at(0).simulated);
  reconfigure({{"physics", "none"}}, {});
  EXPECT_FALSE(
      callService("/knob_server/sample_placements", request).response.scenes.at(0).simulated);
}

/// Releases marker @p name of /knob_server's handles at (@p x, @p y), as rviz does.
void release(ros::Publisher& publisher, const std::string& name, double x, double y) {
  visualization_msgs::InteractiveMarkerFeedback feedback;
  feedback.header.frame_id = "world";
  feedback.client_id = "/live_node_test";
  feedback.marker_name = name;
  feedback.event_type = visualization_msgs::InteractiveMarkerFeedback::MOUSE_UP;
  feedback.pose.position.x = x;
  feedback.pose.position.y = y;
  feedback.pose.position.z = 0.81;
  feedback.pose.orientation.w = 1.0;
  publisher.publish(feedback);
}

std::vector<double> rangeParam(const std::string& name) {
  std::vector<double> range;
  ros::param::get(name, range);
  return range;
}

bool near(const std::vector<double>& a, std::vector<double> b) {
  return a.size() == b.size() && std::abs(a[0] - b[0]) < 1e-9 && std::abs(a[1] - b[1]) < 1e-9;
}

TEST(RegionHandles, ReleasingAHandleMovesTheRegion) {
  ros::Publisher publisher =
      ros::NodeHandle().advertise<visualization_msgs::InteractiveMarkerFeedback>(
          "/knob_server/region_handles/feedback", 10);
  ASSERT_TRUE(waitFor([&] { return publisher.getNumSubscribers() > 0; }, 30.0));
  // TableSampler's region, [-0.35, 0.35] around the table, moved by (0.1, 0.05).
  release(publisher, "TableSampler/region", 0.1, 0.05);
  ASSERT_TRUE(waitFor(
      [] {
        return near(rangeParam("/knob_server/TableSampler/x_range"), {-0.25, 0.45});
      },
      15.0));
  EXPECT_TRUE(near(rangeParam("/knob_server/TableSampler/y_range"), {-0.3, 0.4}));
  SamplePlacements::Request request = placement_samplers::test::seeded(3, 50);
  request.dry_run = true;
  const SamplePlacements srv = callService("/knob_server/sample_placements", request);
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  double largestX = -1.0;
  for (const auto& scene : srv.response.scenes) {
    for (const auto& p : scene.placements) {
      if (p.sampler == "TableSampler") {
        EXPECT_GE(p.pose.position.x, -0.25) << p.name;
        EXPECT_LE(p.pose.position.x, 0.45) << p.name;
        EXPECT_GE(p.pose.position.y, -0.3) << p.name;
        largestX = std::max(largestX, p.pose.position.x);
      }
    }
  }
  EXPECT_GT(largestX, 0.35);  // beyond the old range: 150 draws, one in seven lands there

  // Its side handle: the x side through the released point, about the same centre.
  release(publisher, "TableSampler/region/size_x", 0.2, 0.05);
  ASSERT_TRUE(waitFor(
      [] {
        return near(rangeParam("/knob_server/TableSampler/x_range"), {0.0, 0.2});
      },
      15.0));

  // PlateSampler is an item of the list itself: it moves into its own map.
  release(publisher, "PlateSampler/region", -0.1, 0.0);
  ASSERT_TRUE(waitFor(
      [] {
        return near(rangeParam("/knob_server/PlateSampler/x_range"), {-0.4, 0.2});
      },
      15.0));
  XmlRpc::XmlRpcValue samplers;
  ASSERT_TRUE(ros::param::get("/knob_server/samplers", samplers));
  EXPECT_EQ(static_cast<std::string>(samplers[0]), "PlateSampler");

  // A side of zero width leaves the plate no room: refused, the parameters stay.
  release(publisher, "PlateSampler/region/size_x", -0.1, 0.0);
  ros::WallDuration(1.0).sleep();
  EXPECT_TRUE(near(rangeParam("/knob_server/PlateSampler/x_range"), {-0.4, 0.2}));
  EXPECT_TRUE(reload("knob_server"));  // the parameters written are a valid configuration
}

TEST(RegionHandles, SampleNowFromTheMenu) {
  std::mutex mutex;
  std::uint64_t seed = 0;
  ros::Subscriber scenes = ros::NodeHandle().subscribe<placement_samplers::PlacedScene>(
      "/knob_server/scene", 1, [&](const placement_samplers::PlacedSceneConstPtr& scene) {
        std::lock_guard<std::mutex> lock(mutex);
        seed = scene->seed;
      });
  ros::Publisher publisher =
      ros::NodeHandle().advertise<visualization_msgs::InteractiveMarkerFeedback>(
          "/knob_server/region_handles/feedback", 10);
  ASSERT_TRUE(waitFor([&] { return publisher.getNumSubscribers() > 0; }, 30.0));
  ASSERT_TRUE(waitFor([&] { return scenes.getNumPublishers() > 0; }, 30.0));
  ros::WallDuration(0.5).sleep();  // the latched scene of an earlier test, if any
  std::uint64_t before = 0;
  {
    std::lock_guard<std::mutex> lock(mutex);
    before = seed;
  }
  visualization_msgs::InteractiveMarkerFeedback feedback;
  feedback.header.frame_id = "world";
  feedback.client_id = "/live_node_test";
  feedback.marker_name = "TableSampler/region";
  feedback.event_type = visualization_msgs::InteractiveMarkerFeedback::MENU_SELECT;
  feedback.menu_entry_id = 1;  // "sample now", the menu's only entry
  feedback.pose.orientation.w = 1.0;
  publisher.publish(feedback);
  EXPECT_TRUE(waitFor(
      [&] {
        std::lock_guard<std::mutex> lock(mutex);
        return seed != 0 && seed != before;
      },
      15.0));
}

}  // namespace

int main(int argc, char** argv) {
  return placement_samplers::test::runNodeTests(argc, argv, "live_node_test");
}
