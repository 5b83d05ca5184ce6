// The real node through its real interfaces: service calls, tf frames, markers, reload.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <roscpp/GetLoggers.h>
#include <roscpp/SetLoggerLevel.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <future>
#include <limits>
#include <map>
#include <regex>
#include <sstream>

#include "placement_samplers/SamplePlacements.h"
#include "cli/sample_scenes_cli.hpp"
#include "node_test_helpers.hpp"

namespace {

using placement_samplers::SamplePlacements;

const char* const kService = "/placement_server/sample_placements";
const std::string kConfig =
    std::string(PLACEMENT_SAMPLERS_SOURCE_DIR) + "/test/data/server_test.yaml";

SamplePlacements call(const SamplePlacements::Request& request) {
  return placement_samplers::test::callService(kService, request);
}

using placement_samplers::test::byName;
using placement_samplers::test::seeded;
using placement_samplers::test::tableCoveringWall;

double horizontalDistance(const geometry_msgs::Pose& a, const geometry_msgs::Pose& b) {
  return std::hypot(a.position.x - b.position.x, a.position.y - b.position.y);
}

class PlacementServerTest : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(ros::service::waitForService(kService, ros::Duration(30.0)));
  }
};

TEST_F(PlacementServerTest, EmptyRequestSamplesOneScene) {
  const SamplePlacements srv = call(SamplePlacements::Request());
  EXPECT_TRUE(srv.response.success) << srv.response.message;
  EXPECT_EQ(srv.response.message, "");
  EXPECT_NE(srv.response.seed, 0u);
  EXPECT_EQ(srv.response.frame_id, "world");
  ASSERT_EQ(srv.response.scenes.size(), 1u);
  const auto placed = byName(srv.response.scenes[0]);
  for (const char* name : {"plate", "cup", "cube", "can", "ball", "pill"}) {
    EXPECT_EQ(placed.count(name), 1u) << name;
  }
  EXPECT_EQ(placed.at("cube").sampler, "TableSampler");
  EXPECT_GE(placed.at("cube").attempts, 1u);
}

// Positions lie in their shrunk regions around the table top, z follows on_top, the cup sits on
// the plate, nothing overlaps under robosuite's test, the hidden object is far away.
TEST_F(PlacementServerTest, PlacementsRespectRegionsStackingAndRadiusTest) {
  const SamplePlacements srv = call(seeded(99, 100));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  ASSERT_EQ(srv.response.scenes.size(), 100u);
  const std::map<std::string, double> radius{
      {"plate", 0.09}, {"cube", std::sqrt(2.0) * 0.021}, {"can", 0.033}, {"ball", 0.03}};
  const std::map<std::string, double> bottom{
      {"plate", -0.01}, {"cube", -0.021}, {"can", -0.06}, {"ball", -0.03}};
  const std::map<std::string, double> top{
      {"plate", 0.01}, {"cube", 0.021}, {"can", 0.06}, {"ball", 0.03}};
  const double tableTop = 0.775 + 0.025;
  for (const auto& scene : srv.response.scenes) {
    const auto placed = byName(scene);
    for (const auto& entry : radius) {
      const auto& pose = placed.at(entry.first).pose;
      const double half = entry.first == "plate" ? 0.3 : 0.35;
      EXPECT_LE(std::abs(pose.position.x), half - entry.second + 1e-12) << entry.first;
      EXPECT_LE(std::abs(pose.position.y), half - entry.second + 1e-12) << entry.first;
      EXPECT_NEAR(pose.position.z, tableTop + 0.01 - bottom.at(entry.first), 1e-12) << entry.first;
    }
    const auto& plate = placed.at("plate").pose;
    const auto& cup = placed.at("cup").pose;
    EXPECT_NEAR(cup.position.x, plate.position.x, 1e-12);
    EXPECT_NEAR(cup.position.y, plate.position.y, 1e-12);
    EXPECT_NEAR(cup.position.z, plate.position.z + 0.01 + 0.045, 1e-12);
    for (const auto& a : radius) {
      for (const auto& b : radius) {
        if (a.first < b.first) {
          const auto& pa = placed.at(a.first).pose;
          const auto& pb = placed.at(b.first).pose;
          // Same table height: robosuite's z condition holds, so circles must not touch.
          const bool zClash = pb.position.z - pa.position.z <= top.at(a.first) - bottom.at(b.first);
          if (zClash) {
            EXPECT_GT(horizontalDistance(pa, pb), a.second + b.second) << a.first << " " << b.first;
          }
        }
      }
    }
    const auto& pill = placed.at("pill").pose;
    EXPECT_GE(pill.position.x, -20.0);
    EXPECT_LE(pill.position.x, -10.0);
    EXPECT_NEAR(pill.position.z, 10.0 + 0.06, 1e-12);
  }
}

TEST_F(PlacementServerTest, SameSeedSameAnswerAndSceneIndependentOfCount) {
  const SamplePlacements a = call(seeded(777, 5));
  const SamplePlacements b = call(seeded(777, 5));
  const SamplePlacements one = call(seeded(777, 1));
  ASSERT_TRUE(a.response.success && b.response.success && one.response.success);
  EXPECT_EQ(a.response.seed, 777u);
  ASSERT_EQ(a.response.scenes.size(), 5u);
  EXPECT_EQ(a.response.scenes, b.response.scenes);
  EXPECT_EQ(a.response.scenes[0], one.response.scenes[0]);
  EXPECT_NE(a.response.scenes[0], a.response.scenes[1]);
}

// first_scene: calls that each take a piece answer the scenes of one call, in order; the last
// index of uint64 still works, one beyond it is refused with the reason.
TEST_F(PlacementServerTest, FirstSceneGivesPiecesOfTheSameScenes) {
  const SamplePlacements whole = call(seeded(4343, 6));
  ASSERT_TRUE(whole.response.success);
  ASSERT_EQ(whole.response.scenes.size(), 6u);
  for (const std::uint64_t first : {0u, 2u, 4u}) {
    SamplePlacements::Request request = seeded(4343, 2);
    request.first_scene = first;
    const SamplePlacements piece = call(request);
    ASSERT_TRUE(piece.response.success) << piece.response.message;
    EXPECT_EQ(piece.response.seed, 4343u);
    ASSERT_EQ(piece.response.scenes.size(), 2u);
    EXPECT_EQ(piece.response.scenes[0], whole.response.scenes[first]);
    EXPECT_EQ(piece.response.scenes[1], whole.response.scenes[first + 1]);
  }
  SamplePlacements::Request request = seeded(4343, 1);
  request.first_scene = std::numeric_limits<std::uint64_t>::max();
  const SamplePlacements last = call(request);
  EXPECT_TRUE(last.response.success) << last.response.message;
  request.num_scenes = 2;
  const SamplePlacements beyond = call(request);
  EXPECT_FALSE(beyond.response.success);
  EXPECT_NE(beyond.response.message.find("scene indices must stay below 2^64"), std::string::npos)
      << beyond.response.message;
}

TEST_F(PlacementServerTest, ReturnedSeedReproducesTheScene) {
  const SamplePlacements first = call(SamplePlacements::Request());
  ASSERT_TRUE(first.response.success);
  const SamplePlacements again = call(seeded(first.response.seed));
  EXPECT_EQ(first.response.scenes, again.response.scenes);
}

// The node and the CLI give the same scenes for the same seed, to the last bit.
TEST_F(PlacementServerTest, MatchesTheCommandLineTool) {
  const SamplePlacements srv = call(seeded(4242, 3));
  ASSERT_TRUE(srv.response.success);
  std::ostringstream out, err;
  ASSERT_EQ(placement_samplers::runSampleScenes(
                {"--config", kConfig, "--seed", "4242", "--scenes", "3"}, out, err),
            0)
      << err.str();
  std::istringstream lines(out.str());
  std::string line;
  std::size_t scene = 0;
  const std::regex placementRe(
      "\"name\": \"([^\"]+)\", \"sampler\": \"[^\"]+\", \"position\": \\[([^\\]]+)\\], "
      "\"orientation\": \\[([^\\]]+)\\], \"attempts\": ([0-9]+)");
  while (std::getline(lines, line)) {
    ASSERT_LT(scene, srv.response.scenes.size());
    const auto& placements = srv.response.scenes[scene].placements;
    std::size_t i = 0;
    for (auto it = std::sregex_iterator(line.begin(), line.end(), placementRe);
         it != std::sregex_iterator(); ++it, ++i) {
      ASSERT_LT(i, placements.size());
      const auto& p = placements[i];
      EXPECT_EQ((*it)[1].str(), p.name);
      double x, y, z, qx, qy, qz, qw;
      ASSERT_EQ(std::sscanf((*it)[2].str().c_str(), "%lf, %lf, %lf", &x, &y, &z), 3);
      ASSERT_EQ(std::sscanf((*it)[3].str().c_str(), "%lf, %lf, %lf, %lf", &qx, &qy, &qz, &qw), 4);
      EXPECT_EQ(x, p.pose.position.x);
      EXPECT_EQ(y, p.pose.position.y);
      EXPECT_EQ(z, p.pose.position.z);
      EXPECT_EQ(qz, p.pose.orientation.z);
      EXPECT_EQ(qw, p.pose.orientation.w);
      EXPECT_EQ(std::stoul((*it)[4].str()), p.attempts);
    }
    EXPECT_EQ(i, placements.size());
    ++scene;
  }
  EXPECT_EQ(scene, 3u);
}

TEST_F(PlacementServerTest, SubSamplerAndCallLevelReference) {
  SamplePlacements::Request r = seeded(5);
  r.sampler = "TableSampler";
  const SamplePlacements table = call(r);
  ASSERT_TRUE(table.response.success) << table.response.message;
  ASSERT_EQ(table.response.scenes[0].placements.size(), 3u);
  EXPECT_EQ(table.response.scenes[0].placements[0].name, "cube");

  // A request fixture used as reference: the cube is placed around it, on top of it.
  r = seeded(6);
  r.sampler = "TableSampler";
  placement_samplers::Fixture box;
  box.name = "crate";
  box.shape.type = shape_msgs::SolidPrimitive::BOX;
  box.shape.dimensions = {0.5, 0.5, 0.2};
  box.pose.position.x = 5.0;
  box.pose.position.z = 0.1;
  box.pose.orientation.w = 1.0;
  r.fixtures.push_back(box);
  // TableSampler names the table itself, so the call-level reference does not apply to it...
  r.reference = "crate";
  const SamplePlacements kept = call(r);
  ASSERT_TRUE(kept.response.success) << kept.response.message;
  // ...and the answer says so.
  EXPECT_EQ(kept.response.message,
            "the call's reference was not used: every sampler it would reach sets its own in "
            "sample_args");
  EXPECT_LT(std::abs(kept.response.scenes[0].placements[0].pose.position.x), 1.0);
  // ...but a point reference with a sampler that sets none is used, on_top false keeps z.
  r = seeded(7);
  r.sampler = "PlateSampler";
  r.use_reference_point = true;
  r.reference_point.x = 3.0;
  r.reference_point.z = 1.0;
  const SamplePlacements plate = call(r);
  ASSERT_TRUE(plate.response.success);
  // PlateSampler sets its own reference (table): the call's point does not override it.
  EXPECT_LT(std::abs(plate.response.scenes[0].placements[0].pose.position.x), 1.0);
}

TEST_F(PlacementServerTest, FailureNamesObjectSamplerAndBlocker) {
  SamplePlacements::Request r = seeded(11);
  r.sampler = "TableSampler";
  r.max_attempts = 3;
  r.fixtures.push_back(tableCoveringWall());
  const SamplePlacements srv = call(r);
  EXPECT_FALSE(srv.response.success);
  EXPECT_EQ(srv.response.message,
            "could not place object 'cube' with sampler 'TableSampler' in 3 attempts: 3 of them "
            "overlapped fixture 'wall'");
}

// In a batch, each scene says whether it was placed and why not; the answer's message is the
// first failed scene's, with the count.
TEST_F(PlacementServerTest, EachSceneOfABatchSaysWhetherItWasPlacedAndWhy) {
  SamplePlacements::Request r = seeded(21, 40);
  r.sampler = "TableSampler";
  r.max_attempts = 1;
  r.dry_run = true;
  placement_samplers::Fixture ball;  // blocks a good part of the table: some scenes fail
  ball.name = "boulder";
  ball.shape.type = shape_msgs::SolidPrimitive::SPHERE;
  ball.shape.dimensions = {0.2};
  ball.pose.position.z = 0.9;
  ball.pose.orientation.w = 1.0;
  r.fixtures.push_back(ball);
  const SamplePlacements srv = call(r);
  EXPECT_FALSE(srv.response.success);
  ASSERT_EQ(srv.response.scenes.size(), 40u);
  std::size_t failed = 0;
  std::size_t first = 40;
  for (std::size_t i = 0; i < 40; ++i) {
    const auto& scene = srv.response.scenes[i];
    if (scene.success) {
      EXPECT_EQ(scene.message, "") << i;
      EXPECT_EQ(scene.placements.size(), 3u) << i;
      continue;
    }
    ++failed;
    first = std::min(first, i);
    EXPECT_LT(scene.placements.size(), 3u) << i;
    EXPECT_EQ(scene.message.rfind("could not place object '", 0), 0u) << scene.message;
    EXPECT_NE(scene.message.find("in 1 attempt: 1 of them overlapped fixture 'boulder'"),
              std::string::npos)
        << scene.message;
  }
  ASSERT_GT(failed, 0u);
  ASSERT_LT(failed, 40u);
  EXPECT_EQ(srv.response.message, "scene " + std::to_string(first) + ": " +
                                      srv.response.scenes[first].message + " (" +
                                      std::to_string(failed) + " of 40 scenes failed)");
}

// Without physics nothing says simulated, and sampled_pose is the pose (a unit quaternion);
// with physics check every placed object is simulated but the hidden one.
TEST_F(PlacementServerTest, PhysicsFieldsFollowSimulated) {
  SamplePlacements::Request r = seeded(31);
  r.dry_run = true;
  const SamplePlacements plain = call(r);
  ASSERT_TRUE(plain.response.success) << plain.response.message;
  const auto& scene = plain.response.scenes.at(0);
  EXPECT_TRUE(scene.success);
  EXPECT_FALSE(scene.simulated);
  EXPECT_FALSE(scene.stable);
  for (const auto& p : scene.placements) {
    EXPECT_FALSE(p.simulated) << p.name;
    EXPECT_EQ(p.sampled_pose, p.pose) << p.name;
    EXPECT_EQ(p.moved, 0.0) << p.name;
  }
  r.physics = SamplePlacements::Request::PHYSICS_CHECK;
  const SamplePlacements checked = call(r);
  ASSERT_TRUE(checked.response.success) << checked.response.message;
  const auto& simulated = checked.response.scenes.at(0);
  EXPECT_TRUE(simulated.simulated);
  ASSERT_EQ(simulated.placements.size(), 6u);
  for (const auto& p : simulated.placements) {
    EXPECT_EQ(p.simulated, p.name != "pill") << p.name;
    EXPECT_EQ(p.sampled_pose, p.pose) << p.name;  // check keeps the sampled poses
  }
}

// max_request_seconds (2 s in the test configuration) bounds an absurd max_attempts. With the
// radius test the node proves there is no room (next test); the exact test alone it cannot.
TEST_F(PlacementServerTest, TimeLimitStopsAHopelessRequest) {
  SamplePlacements::Request r = seeded(12);
  r.sampler = "TableSampler";
  r.max_attempts = 4000000000u;
  r.collision_check = SamplePlacements::Request::CHECK_FCL;
  r.fixtures.push_back(tableCoveringWall());
  const ros::WallTime start = ros::WallTime::now();
  const SamplePlacements srv = call(r);
  const double seconds = (ros::WallTime::now() - start).toSec();
  EXPECT_FALSE(srv.response.success);
  EXPECT_EQ(srv.response.message.rfind(
                "stopped placing object 'cube' with sampler 'TableSampler' after ", 0),
            0u)
      << srv.response.message;
  const std::string suffix = " attempts: the request ran out of time";
  ASSERT_GT(srv.response.message.size(), suffix.size());
  EXPECT_EQ(srv.response.message.substr(srv.response.message.size() - suffix.size()), suffix);
  EXPECT_LT(seconds, 6.0);
  // What was achieved comes back: the scene, with the objects placed before the stop (none).
  ASSERT_EQ(srv.response.scenes.size(), 1u);
}

// A wall over the table with an absurd max_attempts: after the probe's attempts the radius test
// proves that no position is left, and the call ends long before its time limit.
TEST_F(PlacementServerTest, NoRoomIsToldBeforeTheTimeLimit) {
  SamplePlacements::Request r = seeded(13);
  r.sampler = "TableSampler";
  r.max_attempts = 4000000000u;
  r.fixtures.push_back(tableCoveringWall());
  const ros::WallTime start = ros::WallTime::now();
  const SamplePlacements srv = call(r);
  const double seconds = (ros::WallTime::now() - start).toSec();
  EXPECT_FALSE(srv.response.success);
  EXPECT_EQ(srv.response.message,
            "could not place object 'cube' with sampler 'TableSampler': after 131071 attempts, no "
            "position is left (every position of its range overlaps a fixture or an object "
            "placed before it)");
  EXPECT_LT(seconds, 1.5);  // the limit is 2 s: a generous bound that still tells them apart
}

// Exact checks per request: objects resting on the table (z_offset 0.01) pass, and no two
// placed objects' boxes/cylinders/spheres intersect (their circles may).
TEST_F(PlacementServerTest, FclModePerRequest) {
  for (std::uint8_t mode :
       {SamplePlacements::Request::CHECK_FCL, SamplePlacements::Request::CHECK_RADIUS_AND_FCL}) {
    SamplePlacements::Request r = seeded(21, 20);
    r.collision_check = mode;
    r.dry_run = true;
    const SamplePlacements srv = call(r);
    EXPECT_TRUE(srv.response.success) << srv.response.message;
    EXPECT_EQ(srv.response.scenes.size(), 20u);
  }
}

TEST_F(PlacementServerTest, BadRequestsAnswerWithTheReason) {
  struct Case {
    std::string what;
    std::function<void(SamplePlacements::Request&)> edit;
    std::string message;
  };
  placement_samplers::Fixture ok;
  ok.name = "box1";
  ok.shape.type = shape_msgs::SolidPrimitive::BOX;
  ok.shape.dimensions = {0.1, 0.1, 0.1};
  ok.pose.orientation.w = 1.0;
  const std::vector<Case> cases{
      {"fixture named like a configured fixture",
       [&](auto& r) {
         r.fixtures = {ok};
         r.fixtures[0].name = "far_bin";
       },
       "fixture 'far_bin': the name is used twice"},
      {"unknown sampler", [](auto& r) { r.sampler = "Nope"; },
       "unknown sampler 'Nope' (configured: root, PlateSampler, CupSampler, TableSampler, "
       "HideSampler)"},
      {"unknown reference", [](auto& r) { r.reference = "ghost"; },
       "unknown reference 'ghost' (not a configured object or a fixture)"},
      {"unknown fixture object",
       [&](auto& r) {
         r.fixtures = {ok};
         r.fixtures[0].object = "anvil";
       },
       "fixture 'box1': unknown object 'anvil'"},
      {"duplicate fixtures",
       [&](auto& r) {
         r.fixtures = {ok, ok};
       },
       "fixture 'box1': the name is used twice"},
      {"fixture named like the configured one",
       [&](auto& r) {
         r.fixtures = {ok};
         r.fixtures[0].name = "table";
       },
       "fixture 'table': the name is used twice"},
      {"fixture named like an object",
       [&](auto& r) {
         r.fixtures = {ok};
         r.fixtures[0].name = "cube";
       },
       "fixture 'cube': the name is already a configured object"},
      {"NaN position",
       [&](auto& r) {
         r.fixtures = {ok};
         r.fixtures[0].pose.position.y = std::numeric_limits<double>::quiet_NaN();
       },
       "fixtures[0].pose.position must be finite"},
      {"non-unit quaternion",
       [&](auto& r) {
         r.fixtures = {ok};
         r.fixtures[0].pose.orientation.w = 2.0;
       },
       "fixtures[0].pose.orientation must be a unit quaternion, got (x 0, y 0, z 0, w 2)"},
      {"zero quaternion",
       [&](auto& r) {
         r.fixtures = {ok};
         r.fixtures[0].pose.orientation.w = 0.0;
       },
       "fixtures[0].pose.orientation must be a unit quaternion, got (x 0, y 0, z 0, w 0); use "
       "w: 1 for no rotation"},
      {"cone",
       [&](auto& r) {
         r.fixtures = {ok};
         r.fixtures[0].shape.type = shape_msgs::SolidPrimitive::CONE;
       },
       "fixtures[0].shape: type must be BOX (1), SPHERE (2) or CYLINDER (3), got 4"},
      {"negative size",
       [&](auto& r) {
         r.fixtures = {ok};
         r.fixtures[0].shape.dimensions[1] = -1.0;
       },
       "fixture 'box1': box size y must be finite and positive, got -1"},
      {"wrong dimension count",
       [&](auto& r) {
         r.fixtures = {ok};
         r.fixtures[0].shape.dimensions = {0.1};
       },
       "fixtures[0].shape: a box needs 3 dimensions, got 1"},
      {"bad on_top", [](auto& r) { r.on_top = 7; },
       "on_top must be ON_TOP_DEFAULT (0), ON_TOP_TRUE (1) or ON_TOP_FALSE (2), got 7"},
      {"bad collision_check", [](auto& r) { r.collision_check = 9; },
       "collision_check must be CHECK_DEFAULT (0), CHECK_RADIUS (1), CHECK_FCL (2) or "
       "CHECK_RADIUS_AND_FCL (3), got 9"},
      {"bad physics", [](auto& r) { r.physics = 9; },
       "physics must be PHYSICS_DEFAULT (0), PHYSICS_NONE (1), PHYSICS_CHECK (2) or "
       "PHYSICS_SETTLE (3), got 9"},
      {"too many scenes", [](auto& r) { r.num_scenes = 501; },
       "num_scenes 501 exceeds max_scenes_per_request (500)"},
      {"reference and point",
       [](auto& r) {
         r.reference = "table";
         r.use_reference_point = true;
       },
       "give either reference or use_reference_point, not both"},
      {"NaN reference point",
       [](auto& r) {
         r.use_reference_point = true;
         r.reference_point.x = std::numeric_limits<double>::infinity();
       },
       "reference_point must be finite"},
  };
  for (const Case& c : cases) {
    SamplePlacements::Request r = seeded(3);
    c.edit(r);
    const SamplePlacements srv = call(r);
    EXPECT_FALSE(srv.response.success) << c.what;
    EXPECT_EQ(srv.response.message, c.message) << c.what;
    EXPECT_TRUE(srv.response.scenes.empty()) << c.what;
  }
  // Still serving.
  EXPECT_TRUE(call(seeded(3)).response.success);
}

// physics settle per request: simulated scenes with the sampled poses kept, settled poses in
// the answer and in the tf frames; physics none (the configuration's) simulates nothing.
TEST_F(PlacementServerTest, PhysicsSettleReturnsSettledScenes) {
  SamplePlacements::Request r = seeded(515, 3);
  r.sampler = "TableSampler";
  r.physics = SamplePlacements::Request::PHYSICS_SETTLE;
  const SamplePlacements srv = call(r);
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  ASSERT_EQ(srv.response.scenes.size(), 3u);
  SamplePlacements::Request dry = seeded(515, 3);
  dry.dry_run = true;  // the frames keep showing the settled scene
  const SamplePlacements plain = call(dry);
  for (std::size_t s = 0; s < 3; ++s) {
    const auto& scene = srv.response.scenes[s];
    EXPECT_TRUE(scene.simulated);
    EXPECT_FALSE(plain.response.scenes[s].simulated);
    ASSERT_EQ(scene.placements.size(), 3u);
    for (const auto& p : scene.placements) {
      // Sampled 1 cm above the table (z_offset): settled on it, sampled pose kept.
      EXPECT_GT(p.sampled_pose.position.z - p.pose.position.z, 0.005) << p.name;
      EXPECT_NEAR(p.sampled_pose.position.x, p.pose.position.x, 0.01) << p.name;
      const auto& q = p.sampled_pose.orientation;
      EXPECT_NEAR(std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w), 1.0, 1e-9) << p.name;
      EXPECT_LT(p.moved, 0.01) << p.name;
      EXPECT_FALSE(p.fallen) << p.name;
    }
  }
  // The frames show the settled poses.
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  const auto& cube = byName(srv.response.scenes[0]).at("cube");
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(10.0);
  bool same = false;
  while (!same && ros::WallTime::now() < until) {
    try {
      const auto t = buffer.lookupTransform("world", "test/cube", ros::Time(0), ros::Duration(1.0));
      same = t.transform.translation.z == cube.pose.position.z;
    } catch (const tf2::TransformException&) {
    }
    ros::WallDuration(0.05).sleep();
  }
  EXPECT_TRUE(same);
}

TEST_F(PlacementServerTest, FramesReachATfListener) {
  ros::NodeHandle nh;
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  const SamplePlacements srv = call(seeded(31));
  ASSERT_TRUE(srv.response.success);
  for (const auto& p : srv.response.scenes[0].placements) {
    geometry_msgs::TransformStamped t;
    // Static frames of an earlier call may arrive first: wait for this scene's values.
    const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(10.0);
    bool same = false;
    while (!same && ros::WallTime::now() < until) {
      try {
        t = buffer.lookupTransform("world", "test/" + p.name, ros::Time(0), ros::Duration(1.0));
        same = t.transform.translation.x == p.pose.position.x &&
               t.transform.translation.y == p.pose.position.y &&
               t.transform.translation.z == p.pose.position.z &&
               t.transform.rotation.w == p.pose.orientation.w;
      } catch (const tf2::TransformException&) {
      }
      ros::WallDuration(0.05).sleep();
    }
    EXPECT_TRUE(same) << p.name;
  }
  const auto table =
      buffer.lookupTransform("world", "test/table", ros::Time(0), ros::Duration(5.0));
  EXPECT_DOUBLE_EQ(table.transform.translation.z, 0.775);
  const auto bin =
      buffer.lookupTransform("world", "test/far_bin", ros::Time(0), ros::Duration(5.0));
  EXPECT_DOUBLE_EQ(bin.transform.translation.x, 5.0);

  // A dry run broadcasts nothing: the frames keep the last scene.
  SamplePlacements::Request dry = seeded(32);
  dry.dry_run = true;
  ASSERT_TRUE(call(dry).response.success);
  ros::WallDuration(1.0).sleep();
  const auto& cube = byName(srv.response.scenes[0]).at("cube");
  const auto t = buffer.lookupTransform("world", "test/cube", ros::Time(0), ros::Duration(1.0));
  EXPECT_EQ(t.transform.translation.x, cube.pose.position.x);
}

TEST_F(PlacementServerTest, MarkersShowObjectsFixturesAndRegions) {
  ros::NodeHandle nh;
  std::promise<visualization_msgs::MarkerArray> received;
  bool done = false;
  std::mutex mutex;
  ros::Subscriber sub = nh.subscribe<visualization_msgs::MarkerArray>(
      "/placement_server/markers", 5, [&](const visualization_msgs::MarkerArray::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!done && m->markers.size() > 1 && m->markers[1].header.stamp.toSec() > 0) {
          // Wait for the markers of the call below (it is the one with seed 41's cube pose).
          for (const auto& marker : m->markers) {
            if (marker.ns == "objects" && marker.id > 0 && marker.pose.position.z > 0.0) {
              done = true;
              received.set_value(*m);
              return;
            }
          }
        }
      });
  const SamplePlacements srv = call(seeded(41));
  ASSERT_TRUE(srv.response.success);
  auto future = received.get_future();
  ASSERT_EQ(future.wait_for(std::chrono::seconds(10)), std::future_status::ready);
  const visualization_msgs::MarkerArray markers = future.get();
  ASSERT_FALSE(markers.markers.empty());
  EXPECT_EQ(markers.markers[0].action, visualization_msgs::Marker::DELETEALL);
  std::map<std::string, int> count;
  for (const auto& m : markers.markers) {
    count[m.ns]++;
    EXPECT_EQ(m.header.frame_id,
              m.action == visualization_msgs::Marker::DELETEALL ? m.header.frame_id : "world");
  }
  // plate, cup, cube, can, ball (the hidden pill is not drawn).
  EXPECT_EQ(count["objects"], 5);
  // The table, and the five boxes of the bin read from the URDF parameter.
  EXPECT_EQ(count["fixtures"], 6);
  EXPECT_EQ(count["regions"], 3);
}

// TableSampler's parameters are in /placement_server/TableSampler (the named form of the
// samplers list): one parameter is changed with one setParam, as `rosparam set` does.
TEST_F(PlacementServerTest, ReloadAcceptsGoodAndRefusesBadConfiguration) {
  ros::NodeHandle nh;
  std_srvs::Trigger trigger;
  XmlRpc::XmlRpcValue original;
  ASSERT_TRUE(nh.getParam("/placement_server/TableSampler", original));
  XmlRpc::XmlRpcValue range;
  range[0] = 0.1;
  range[1] = 0.2;
  nh.setParam("/placement_server/TableSampler/x_range", range);
  nh.setParam("/placement_server/TableSampler/ensure_object_boundary_in_range", false);
  ASSERT_TRUE(ros::service::call("/placement_server/reload", trigger));
  EXPECT_TRUE(trigger.response.success) << trigger.response.message;
  SamplePlacements::Request r = seeded(8, 20);
  r.sampler = "TableSampler";
  const SamplePlacements narrow = call(r);
  ASSERT_TRUE(narrow.response.success) << narrow.response.message;
  for (const auto& scene : narrow.response.scenes) {
    for (const auto& p : scene.placements) {
      EXPECT_GE(p.pose.position.x, 0.1);
      EXPECT_LT(p.pose.position.x, 0.2);
    }
  }

  // A bad change is refused with its parameter path, and the previous configuration serves on.
  range[0] = 0.3;
  range[1] = -0.3;
  nh.setParam("/placement_server/TableSampler/x_range", range);
  ASSERT_TRUE(ros::service::call("/placement_server/reload", trigger));
  EXPECT_FALSE(trigger.response.success);
  EXPECT_EQ(trigger.response.message,
            "configuration refused, the previous one stays: /placement_server/TableSampler/"
            "x_range: expected [min, max] with min <= max, got [0.3, -0.3]");
  const SamplePlacements still = call(r);
  ASSERT_TRUE(still.response.success);
  EXPECT_EQ(still.response.scenes, narrow.response.scenes);

  nh.setParam("/placement_server/TableSampler", original);
  ASSERT_TRUE(ros::service::call("/placement_server/reload", trigger));
  EXPECT_TRUE(trigger.response.success) << trigger.response.message;
}

/// Adds objects to /placement_server/objects and reloads; puts the original back (and reloads)
/// when it goes out of scope.
class ObjectParams {
 public:
  ObjectParams() { EXPECT_TRUE(nh_.getParam("/placement_server/objects", original_)); }
  ~ObjectParams() {
    nh_.setParam("/placement_server/objects", original_);
    std_srvs::Trigger trigger;
    EXPECT_TRUE(ros::service::call("/placement_server/reload", trigger));
    EXPECT_TRUE(trigger.response.success) << trigger.response.message;
  }
  /// objects[@p name][@p key] = @p value, then ~reload: its answer.
  std_srvs::Trigger::Response add(const std::string& name, const std::string& key,
                                  const std::string& value) {
    XmlRpc::XmlRpcValue objects;
    EXPECT_TRUE(nh_.getParam("/placement_server/objects", objects));
    objects[name][key] = value;
    nh_.setParam("/placement_server/objects", objects);
    std_srvs::Trigger trigger;
    EXPECT_TRUE(ros::service::call("/placement_server/reload", trigger));
    return trigger.response;
  }

 private:
  ros::NodeHandle nh_;
  XmlRpc::XmlRpcValue original_;
};

/// A request of TableSampler with one fixture of configured object @p object at (0, 0, @p z).
SamplePlacements::Request withFixture(std::uint64_t seed, const std::string& object, double z) {
  SamplePlacements::Request r = seeded(seed);
  r.dry_run = true;
  placement_samplers::Fixture fixture;
  fixture.name = "fixture_" + object;
  fixture.object = object;
  fixture.pose.position.z = z;
  fixture.pose.orientation.w = 1.0;
  r.fixtures.push_back(fixture);
  r.sampler = "TableSampler";
  return r;
}

// An object whose URDF comes from a parameter (the .test file loads urdf/bin.urdf into
// /bin_description), added through a reload and used as a request fixture.
TEST_F(PlacementServerTest, UrdfParamObject) {
  ObjectParams params;
  const std_srvs::Trigger::Response added =
      params.add("param_bin", "urdf_param", "/bin_description");
  EXPECT_TRUE(added.success) << added.message;
  SamplePlacements::Request r = withFixture(17, "param_bin", 0.8);
  r.max_attempts = 200;
  // The bin stands on the table's middle: under robosuite's test its circle covers most of
  // the table, and objects are placed around it.
  const SamplePlacements srv = call(r);
  EXPECT_TRUE(srv.response.success) << srv.response.message;
  for (const auto& p : srv.response.scenes[0].placements) {
    EXPECT_GT(std::hypot(p.pose.position.x, p.pose.position.y), 0.25) << p.name;
  }
  const std_srvs::Trigger::Response broken =
      params.add("broken", "urdf_param", "/no_such_description");
  EXPECT_FALSE(broken.success);
  EXPECT_NE(broken.message.find("/no_such_description"), std::string::npos) << broken.message;
}

// An MJCF object from a parameter (the .test file loads config/robosuite_objects/can.xml into
// /can_mjcf), added through a reload: robosuite's values from its sites.
TEST_F(PlacementServerTest, MjcfParamObject) {
  ObjectParams params;
  const std_srvs::Trigger::Response added = params.add("param_can", "mjcf_param", "/can_mjcf");
  EXPECT_TRUE(added.success) << added.message;
  // The can stands on the table's centre as a request fixture; robosuite's test keeps every
  // object on the table out of its circle (radius 0.03 m from its site).
  const SamplePlacements srv = call(withFixture(18, "param_can", 0.85));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  for (const auto& p : srv.response.scenes[0].placements) {
    // 0.03 m plus the smallest radius of the three (the cube's, 0.0297 m).
    EXPECT_GT(std::hypot(p.pose.position.x, p.pose.position.y), 0.0597) << p.name;
  }
  const std_srvs::Trigger::Response broken = params.add("broken", "mjcf_param", "/no_such_mjcf");
  EXPECT_FALSE(broken.success);
  EXPECT_NE(broken.message.find("parameter '/no_such_mjcf' does not exist or does not hold MJCF "
                                "text"),
            std::string::npos)
      << broken.message;
}

std::map<std::string, std::string> loggerLevels() {
  roscpp::GetLoggers list;
  EXPECT_TRUE(ros::service::call("/placement_server/get_loggers", list));
  std::map<std::string, std::string> levels;
  for (const auto& logger : list.response.loggers) {
    levels[logger.name] = logger.level;
  }
  return levels;
}

bool setLoggerLevel(const std::string& logger, const std::string& level) {
  roscpp::SetLoggerLevel set;
  set.request.logger = logger;
  set.request.level = level;
  return ros::service::call("/placement_server/set_logger_level", set);
}

// rqt_logger_level's first steps: list the loggers, then set roscpp's own to debug. Debian 12's
// rosconsole frees log4cxx's loggers when it lists them, and roscpp's own get_loggers crashed
// the node at its next message (every connection logs at debug); the node's own does not.
TEST_F(PlacementServerTest, LoggerLevelsChangeWhileTheNodeKeepsServing) {
  std::map<std::string, std::string> levels = loggerLevels();
  ASSERT_EQ(levels.count("ros.roscpp"), 1u);
  EXPECT_EQ(levels.at("ros.roscpp"), "info");
  EXPECT_EQ(levels.at("ros.placement_samplers"), "info");
  ASSERT_TRUE(setLoggerLevel("ros.roscpp", "debug"));
  for (std::uint64_t seed = 60; seed < 63; ++seed) {
    const SamplePlacements srv = call(seeded(seed));  // a new connection each, logged at debug
    EXPECT_TRUE(srv.response.success) << srv.response.message;
  }
  levels = loggerLevels();
  EXPECT_EQ(levels.at("ros.roscpp"), "debug");
  EXPECT_EQ(levels.at("ros.roscpp.roscpp_internal"), "debug");  // inherited
  ASSERT_TRUE(setLoggerLevel("ros.roscpp", "info"));
  EXPECT_EQ(loggerLevels().at("ros.roscpp"), "info");
  EXPECT_TRUE(call(seeded(63)).response.success);
}

// Concurrent clients get, for each seed, the answer a lone client gets.
TEST_F(PlacementServerTest, ConcurrentCallsAreIndependent) {
  std::vector<SamplePlacements> alone;
  for (std::uint64_t seed = 100; seed < 108; ++seed) {
    alone.push_back(call(seeded(seed, 3)));
  }
  std::vector<std::future<SamplePlacements>> futures;
  for (int round = 0; round < 3; ++round) {
    for (std::uint64_t seed = 100; seed < 108; ++seed) {
      futures.push_back(std::async(std::launch::async, [seed] {
        SamplePlacements srv;
        srv.request = seeded(seed, 3);
        srv.request.dry_run = true;
        ros::service::call(kService, srv);
        return srv;
      }));
    }
  }
  for (std::size_t i = 0; i < futures.size(); ++i) {
    const SamplePlacements srv = futures[i].get();
    EXPECT_TRUE(srv.response.success) << srv.response.message;
    EXPECT_EQ(srv.response.scenes, alone[i % 8].response.scenes);
  }
}

}  // namespace

int main(int argc, char** argv) {
  return placement_samplers::test::runNodeTests(argc, argv, "placement_server_test");
}
