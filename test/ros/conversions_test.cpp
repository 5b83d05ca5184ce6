// The message conversions of the ROS layer, without a master: quaternions (the one unit test of
// unit_quaternion.hpp, the hint for an all-zero one), primitives and poses.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/ros/conversions.hpp"
#include "placement_samplers/geometry/unit_quaternion.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

geometry_msgs::Quaternion quaternion(double x, double y, double z, double w) {
  geometry_msgs::Quaternion q;
  q.x = x;
  q.y = y;
  q.z = z;
  q.w = w;
  return q;
}

std::string requestError(const geometry_msgs::Quaternion& q) {
  try {
    fromQuaternionMsg(q, "fixtures[0].pose.orientation");
  } catch (const RequestError& e) {
    return e.what();
  }
  return "";
}

TEST(Conversions, QuaternionsWithinTheToleranceAreNormalised) {
  const double s = 1.0 + 0.5 * kUnitQuaternionTolerance;
  const Eigen::Quaterniond q = fromQuaternionMsg(quaternion(0.0, 0.0, 0.0, s), "q");
  EXPECT_DOUBLE_EQ(q.w(), 1.0);
  EXPECT_DOUBLE_EQ(q.norm(), 1.0);
  const Eigen::Quaterniond turned =
      fromQuaternionMsg(quaternion(0.0, 0.0, std::sqrt(0.5), std::sqrt(0.5)), "q");
  EXPECT_NEAR(turned.z(), std::sqrt(0.5), 1e-15);
}

TEST(Conversions, NonUnitAndNonFiniteQuaternionsAreRefusedWithTheField) {
  const double off = 1.0 + 2.0 * kUnitQuaternionTolerance;
  EXPECT_EQ(requestError(quaternion(0.0, 0.0, 0.0, off)),
            "fixtures[0].pose.orientation must be a unit quaternion, got (x 0, y 0, z 0, w " +
                std::to_string(off).substr(0, 5) + ")");
  EXPECT_NE(requestError(quaternion(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0, 1.0)), "");
  EXPECT_NE(requestError(quaternion(0.0, 0.0, 0.0, std::numeric_limits<double>::infinity())), "");
  EXPECT_EQ(requestError(quaternion(0.0, 0.0, 0.0, 0.0)),
            "fixtures[0].pose.orientation must be a unit quaternion, got (x 0, y 0, z 0, w 0); "
            "use w: 1 for no rotation");
}

TEST(Conversions, PrimitivesNeedTheirDimensions) {
  shape_msgs::SolidPrimitive box;
  box.type = shape_msgs::SolidPrimitive::BOX;
  box.dimensions = {0.1, 0.2, 0.3};
  const Shape shape = fromSolidPrimitive(box, "f");
  EXPECT_EQ(shape.type, ShapeType::Box);
  EXPECT_EQ(shape.size, Eigen::Vector3d(0.1, 0.2, 0.3));
  box.dimensions = {0.1};
  EXPECT_THROW(fromSolidPrimitive(box, "f"), RequestError);
  shape_msgs::SolidPrimitive cone;
  cone.type = shape_msgs::SolidPrimitive::CONE;
  cone.dimensions = {0.1, 0.1};
  EXPECT_THROW(fromSolidPrimitive(cone, "f"), RequestError);
}

TEST(Conversions, PosesKeepEveryComponent) {
  const Eigen::Quaterniond q(0.5, 0.5, -0.5, 0.5);
  const geometry_msgs::Pose pose = toPoseMsg(Eigen::Vector3d(1.0, -2.0, 3.5), q);
  EXPECT_EQ(pose.position.x, 1.0);
  EXPECT_EQ(pose.position.y, -2.0);
  EXPECT_EQ(pose.position.z, 3.5);
  EXPECT_EQ(pose.orientation.x, 0.5);
  EXPECT_EQ(pose.orientation.y, -0.5);
  EXPECT_EQ(pose.orientation.z, 0.5);
  EXPECT_EQ(pose.orientation.w, 0.5);
}

SceneResult twoPlacements() {
  SceneResult scene;
  scene.success = true;
  const Eigen::Quaterniond turned(std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5));
  scene.placements.emplace_back("cube", "TableSampler", turned, Eigen::Vector3d(0.1, 0.2, 0.83),
                                nullptr, 3, false);
  scene.placements.emplace_back("pill", "HideSampler", Eigen::Quaterniond::Identity(),
                                Eigen::Vector3d(-15.0, -15.0, 10.06), nullptr, 1, true);
  return scene;
}

TEST(Conversions, UnsimulatedScenesSayItAndCarryTheirPosesAsSampled) {
  const placement_samplers::Scene msg = toSceneMsg(twoPlacements());
  EXPECT_TRUE(msg.success);
  EXPECT_EQ(msg.message, "");
  EXPECT_FALSE(msg.simulated);
  EXPECT_FALSE(msg.stable);
  ASSERT_EQ(msg.placements.size(), 2u);
  for (const placement_samplers::Placement& p : msg.placements) {
    EXPECT_FALSE(p.simulated) << p.name;
    EXPECT_EQ(p.sampled_pose, p.pose) << p.name;  // a unit quaternion, not zeros
    EXPECT_EQ(p.moved, 0.0);
    EXPECT_EQ(p.turned, 0.0);
    EXPECT_FALSE(p.fallen);
  }
  EXPECT_DOUBLE_EQ(msg.placements[0].sampled_pose.orientation.w, std::sqrt(0.5));
  EXPECT_EQ(msg.placements[1].sampled_pose.orientation.w, 1.0);
}

TEST(Conversions, EachSceneCarriesItsOwnSuccessAndMessage) {
  SceneResult failed = twoPlacements();
  failed.success = false;
  failed.message = "could not place object 'ball' with sampler 'TableSampler' in 1 attempt";
  failed.placements.pop_back();
  const placement_samplers::Scene msg = toSceneMsg(failed);
  EXPECT_FALSE(msg.success);
  EXPECT_EQ(msg.message, failed.message);
  EXPECT_EQ(msg.placements.size(), 1u);
}

TEST(Conversions, SimulatedPlacementsButHiddenOnesAreMarkedSimulated) {
  SceneResult scene = twoPlacements();
  scene.simulated = true;
  scene.stable = true;
  scene.physics.resize(2);
  scene.physics[0].moved = 0.002;
  scene.physics[0].turned = 0.01;
  scene.physics[0].sampledPosition = Eigen::Vector3d(0.1, 0.2, 0.84);
  scene.physics[0].sampledOrientation = scene.placements[0].orientation;
  scene.physics[1].sampledPosition = scene.placements[1].position;
  const placement_samplers::Scene msg = toSceneMsg(scene);
  EXPECT_TRUE(msg.simulated);
  EXPECT_TRUE(msg.stable);
  EXPECT_TRUE(msg.placements[0].simulated);
  EXPECT_EQ(msg.placements[0].moved, 0.002);
  EXPECT_EQ(msg.placements[0].turned, 0.01);
  EXPECT_EQ(msg.placements[0].sampled_pose.position.z, 0.84);  // settled: pose is 0.83
  EXPECT_EQ(msg.placements[0].pose.position.z, 0.83);
  EXPECT_FALSE(msg.placements[1].simulated);  // hidden: out of the simulation
  EXPECT_EQ(msg.placements[1].sampled_pose, msg.placements[1].pose);
}

}  // namespace
}  // namespace ros_interface
}  // namespace placement_samplers
