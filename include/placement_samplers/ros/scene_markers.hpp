#pragma once

#include <ros/time.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>

#include "placement_samplers/scene_generator.hpp"

namespace placement_samplers {
namespace ros_interface {

/// Markers of one scene in @p frameId: a DELETEALL first, then each placed object's collision
/// shapes (namespace "objects", one colour per object), each fixture's ("fixtures", grey) and
/// each uniform sampler's region as a thin translucent box ("regions"). Hidden objects are left
/// out.
visualization_msgs::MarkerArray makeSceneMarkers(const PreparedRequest& request,
                                                 const SceneResult& scene,
                                                 const std::string& frameId,
                                                 const ros::Time& stamp);

}  // namespace ros_interface
}  // namespace placement_samplers
