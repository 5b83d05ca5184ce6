#pragma once

#include <interactive_markers/interactive_marker_server.h>
#include <interactive_markers/menu_handler.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <Eigen/Core>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "placement_samplers/ros/region_params.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {
namespace ros_interface {

/// One shape the handles show: a uniform sampler's region or keep-out zone.
struct ShownShape {
  std::string sampler;
  HandleShape shape;
  /// The shape frame's origin in frame_id: the sampler's resolved reference (the world origin
  /// for a world zone) at the region's height (reference z + z_offset) [m].
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
};

/// The shapes of every uniform sampler whose region the configuration alone places: samplers
/// whose reference is their reference_pos, a point or a configured fixture (an object placed
/// in each scene moves its region with it), neither hidden nor drawing on support surfaces.
std::vector<ShownShape> handleShapes(const SceneGenerator& generator);

/// An interactive-marker server (`<node>/region_handles`) with handles for the regions and
/// keep-out zones of handleShapes(): each shape moves in x-y, turns about z where that
/// changes it (rectangles, polygons), and has resize handles where it has a size (sides,
/// radii). Releasing a handle hands the edited shape to Apply, which writes the sampler's
/// parameters and serves them; a refused edit puts the handles back. Every shape's menu has
/// "sample now".
class RegionHandles {
 public:
  /// Serves the configuration with @p edited written into sampler @p sampler's parameters;
  /// false with the configuration's error when it is refused.
  using Apply =
      std::function<bool(const std::string& sampler, const HandleShape& edited, std::string&)>;

  /// @param topicNamespace the server's topics: <ns>/update, <ns>/feedback, ...
  /// @param edits the queue Apply and @p sampleNow are run from (not the server's thread)
  RegionHandles(const std::string& topicNamespace, ros::CallbackQueue* edits, Apply apply,
                std::function<void()> sampleNow);
  ~RegionHandles();

  /// Shows the handles of @p generator's configuration, replacing what was shown.
  void show(const std::shared_ptr<const SceneGenerator>& generator);
  /// Serves the handles again (after a master restart), from the edits' queue.
  void restart();

 private:
  struct Marker {
    ShownShape shown;
    std::string handle;  ///< "" = the shape itself (move, turn); else a sizeHandles() name
  };

  void onFeedback(const visualization_msgs::InteractiveMarkerFeedbackConstPtr& feedback);
  void edit(const std::string& sampler, const HandleShape& edited);
  void insert(const std::string& name, const Marker& marker, const std::string& frameId);

  std::string topicNamespace_;
  ros::CallbackQueue* edits_;
  Apply apply_;
  std::function<void()> sampleNow_;
  std::unique_ptr<interactive_markers::InteractiveMarkerServer> server_;
  interactive_markers::MenuHandler menu_;

  std::mutex mutex_;  // guards what follows: feedback comes on the server's thread
  std::map<std::string, Marker> markers_;
  std::shared_ptr<const SceneGenerator> generator_;
};

}  // namespace ros_interface
}  // namespace placement_samplers
