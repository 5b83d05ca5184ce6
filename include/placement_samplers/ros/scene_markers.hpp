#pragma once

#include <geometry_msgs/PoseArray.h>
#include <ros/time.h>
#include <std_msgs/ColorRGBA.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <string_view>

#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {
namespace ros_interface {

/// Markers of one scene in @p frameId: a DELETEALL first, then each placed object's collision
/// shapes (namespace "objects", in the colour of its name), each fixture's ("fixtures", grey),
/// the name of each above it ("labels"; "mug (pose 2)" for an object in a resting pose), each
/// uniform sampler's region ("regions": a thin translucent box for x_range/y_range, a TRIANGLE_LIST
/// for other shapes) and its keep-out zones
/// ("keep_out", red triangles), the support surfaces of surface regions ("surfaces", blue
/// triangles with a label giving each one's index and clearance), and a line from each object
/// to the target of each of its relations ("relations": green when the relation holds, red when
/// not). Hidden objects are left out.
///
/// A simulated object that fell, or moved or turned by the physics tolerances or more, gets a
/// red wire box around it ("physics") and a red label saying so ("cube: fell, moved 0.412 m,
/// turned 1.57 rad"); under settle also a faint copy at its sampled pose ("sampled") and an
/// arrow from there to its settled position ("physics"), and a fallen object's label stays
/// above its sampled pose. With the configuration's ground_z, a thin slab ("ground") under the
/// objects and regions shows the plane.
visualization_msgs::MarkerArray makeSceneMarkers(const PreparedRequest& request,
                                                 const SceneResult& scene,
                                                 const std::string& frameId,
                                                 const ros::Time& stamp);

/// The poses of @p scene's placed objects in sampling order (hidden objects left out), for
/// tools that show or take a geometry_msgs/PoseArray.
geometry_msgs::PoseArray makeScenePoses(const SceneResult& scene, const std::string& frameId,
                                        const ros::Time& stamp);

/// The colour of the object called @p name: a hue from a hash of the name, so an object keeps
/// its colour from call to call and run to run.
std_msgs::ColorRGBA objectColour(std::string_view name);

/// A DELETEALL alone: removes every marker of the previous scene.
visualization_msgs::MarkerArray makeClearMarkers();

}  // namespace ros_interface
}  // namespace placement_samplers
