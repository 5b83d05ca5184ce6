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

}  // namespace
}  // namespace ros_interface
}  // namespace placement_samplers
