#pragma once

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/TransformStamped.h>
#include <shape_msgs/SolidPrimitive.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "placement_samplers/SamplePlacements.h"
#include "placement_samplers/Scene.h"
#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {
namespace ros_interface {

/// Every conversion between the core types and the messages, in one place.

geometry_msgs::Pose toPoseMsg(const Eigen::Vector3d& position,
                              const Eigen::Quaterniond& orientation);

/// A unit quaternion from a message.
/// @throw RequestError naming @p field when it is not a unit quaternion (isUnitQuaternion())
Eigen::Quaterniond fromQuaternionMsg(const geometry_msgs::Quaternion& q, const std::string& field);

/// A primitive from shape_msgs/SolidPrimitive (box, sphere, cylinder).
/// @throw RequestError naming @p field for cones, unknown types or wrong dimensions
Shape fromSolidPrimitive(const shape_msgs::SolidPrimitive& primitive, const std::string& field);

/// The core request for a service request (everything but seed, num_scenes and dry_run).
/// @throw RequestError for unknown enum values, NaN, non-unit quaternions, bad shapes
SampleRequest toSampleRequest(const SamplePlacements::Request& request);

/// A scene message from a result: its success and message; per placement `sampled_pose` (the
/// pose itself unless the scene settled) and the physics fields, which only simulated
/// placements (a simulated scene, not hidden) fill, with `simulated` saying so.
placement_samplers::Scene toSceneMsg(const SceneResult& scene);

/// A fixture message: a configured object's name, or (for a request's primitive) its shape.
placement_samplers::Fixture toFixtureMsg(const FixtureSpec& fixture);

/// The tf frames of a scene: each fixture and each placement as <tfPrefix><name> under frameId.
std::vector<geometry_msgs::TransformStamped> toTransforms(const SceneResult& scene,
                                                          const std::vector<FixtureSpec>& fixtures,
                                                          const std::string& frameId,
                                                          const std::string& tfPrefix,
                                                          const ros::Time& stamp);

}  // namespace ros_interface
}  // namespace placement_samplers
