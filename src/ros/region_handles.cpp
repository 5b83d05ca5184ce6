#include "placement_samplers/ros/region_handles.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "ros/post_callback.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

using visualization_msgs::InteractiveMarker;
using visualization_msgs::InteractiveMarkerControl;
using visualization_msgs::InteractiveMarkerFeedback;

constexpr double kLift = 0.003;  // [m] above the region, so the handles show over its marker

geometry_msgs::Quaternion yawQuaternion(double yaw) {
  geometry_msgs::Quaternion q;
  q.z = std::sin(0.5 * yaw);
  q.w = std::cos(0.5 * yaw);
  return q;
}

double yawOf(const geometry_msgs::Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

/// A control's orientation: its x axis along @p axis (0 = x, 1 = y, 2 = z).
geometry_msgs::Quaternion controlAxis(int axis) {
  geometry_msgs::Quaternion q;
  q.w = std::sqrt(0.5);
  (axis == 0 ? q.x : axis == 1 ? q.z : q.y) = std::sqrt(0.5);
  return q;
}

std_msgs::ColorRGBA colour(float r, float g, float b, float a) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

/// The shape at its own centre, unturned: what the marker draws in its frame.
RegionShape localShape(const RegionShape& shape) {
  const ShapePose pose = shapePose(shape);
  switch (shape.kind) {
    case RegionShape::Kind::Rectangle: {
      const Eigen::Vector2d half(0.5 * (shape.xRange[1] - shape.xRange[0]),
                                 0.5 * (shape.yRange[1] - shape.yRange[0]));
      return RegionShape::rectangle(Eigen::Vector2d(-half.x(), half.x()),
                                    Eigen::Vector2d(-half.y(), half.y()));
    }
    case RegionShape::Kind::RotatedRectangle:
      return RegionShape::rotatedRectangle(Eigen::Vector2d::Zero(), shape.size, 0.0);
    case RegionShape::Kind::Disk:
    case RegionShape::Kind::Annulus: {
      RegionShape out = shape;
      out.centre.setZero();
      return out;
    }
    case RegionShape::Kind::Polygon: {
      RegionShape out = shape;
      for (Eigen::Vector2d& v : out.vertices) {
        v -= pose.centre;
      }
      return out;
    }
  }
  return shape;
}

}  // namespace

std::vector<ShownShape> handleShapes(const SceneGenerator& generator) {
  std::vector<ShownShape> out;
  const SceneConfig& config = generator.config();
  config.root->forEachUniform(
      Reference(), true,
      [&](const UniformRandomSampler& sampler, const Reference& reference, bool onTop) {
        const UniformSamplerParams& p = sampler.params();
        if (p.hides || p.surface) {
          return;
        }
        const Eigen::Vector3d* position = nullptr;
        const ObjectModel* object = nullptr;
        if (reference.kind == Reference::Kind::Name) {
          for (const FixtureSpec& f : config.fixtures) {
            if (f.name == reference.name) {
              position = &f.position;
              object = f.object.get();
            }
          }
          if (position == nullptr) {
            return;  // an object: its region moves with it from scene to scene
          }
        }
        const std::optional<Eigen::Vector3d> base =
            sampler.base(reference, onTop, position, object);
        if (!base) {
          return;
        }
        ShownShape region;
        region.sampler = sampler.name();
        region.origin = *base + Eigen::Vector3d(0.0, 0.0, p.zOffset);
        region.shape.shape = p.region ? *p.region : RegionShape::rectangle(p.xRange, p.yRange);
        region.shape.ranges = !p.region;
        out.push_back(region);
        for (std::size_t i = 0; i < p.keepOut.size(); ++i) {
          ShownShape zone = region;
          zone.shape.shape = p.keepOut[i].shape;
          zone.shape.ranges = false;
          zone.shape.keepOut = i;
          zone.shape.world = p.keepOut[i].world;
          if (zone.shape.world) {
            zone.origin.head<2>().setZero();
          }
          out.push_back(zone);
        }
      });
  return out;
}

RegionHandles::RegionHandles(const std::string& topicNamespace, ros::CallbackQueue* edits,
                             Apply apply, std::function<void()> sampleNow)
    : topicNamespace_(topicNamespace),
      edits_(edits),
      apply_(std::move(apply)),
      sampleNow_(std::move(sampleNow)) {
  // Its own thread: feedback is read while every other thread is busy.
  server_ =
      std::make_unique<interactive_markers::InteractiveMarkerServer>(topicNamespace_, "", true);
  menu_.insert("sample now", [this](const visualization_msgs::InteractiveMarkerFeedbackConstPtr&) {
    sampleNow_();
  });
}

RegionHandles::~RegionHandles() { server_.reset(); }

void RegionHandles::restart() {
  server_.reset();
  server_ =
      std::make_unique<interactive_markers::InteractiveMarkerServer>(topicNamespace_, "", true);
  std::shared_ptr<const SceneGenerator> generator;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    generator = generator_;
  }
  if (generator) {
    show(generator);
  }
}

void RegionHandles::show(const std::shared_ptr<const SceneGenerator>& generator) {
  std::map<std::string, Marker> markers;
  for (const ShownShape& shown : handleShapes(*generator)) {
    const std::string name =
        shown.sampler + (shown.shape.keepOut ? "/keep_out_" + std::to_string(*shown.shape.keepOut)
                                             : std::string("/region"));
    markers[name] = Marker{shown, ""};
    for (const std::string& handle : sizeHandles(shown.shape.shape)) {
      markers[name + "/" + handle] = Marker{shown, handle};
    }
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    markers_ = markers;
    generator_ = generator;
  }
  // Outside mutex_: the server calls onFeedback() with its own lock held.
  server_->clear();
  for (const auto& entry : markers) {
    insert(entry.first, entry.second, generator->config().frameId);
  }
  server_->applyChanges();
}

void RegionHandles::insert(const std::string& name, const Marker& marker,
                           const std::string& frameId) {
  const RegionShape& shape = marker.shown.shape.shape;
  const ShapePose pose = shapePose(shape);
  InteractiveMarker im;
  im.header.frame_id = frameId;
  im.name = name;
  im.pose.position.z = marker.shown.origin.z() + kLift;
  InteractiveMarkerControl control;
  control.always_visible = true;
  visualization_msgs::Marker visual;
  visual.pose.orientation.w = 1.0;
  if (marker.handle.empty()) {
    const Eigen::Vector2d at = marker.shown.origin.head<2>() + pose.centre;
    im.pose.position.x = at.x();
    im.pose.position.y = at.y();
    im.pose.orientation = yawQuaternion(pose.yaw);
    im.scale = 0.15;
    im.description = marker.shown.sampler + (marker.shown.shape.keepOut ? " keep_out" : "");
    visual.type = visualization_msgs::Marker::TRIANGLE_LIST;
    visual.scale.x = visual.scale.y = visual.scale.z = 1.0;
    visual.color = marker.shown.shape.keepOut ? colour(0.9f, 0.15f, 0.15f, 0.45f)
                                              : colour(0.2f, 0.8f, 0.3f, 0.45f);
    for (const Eigen::Vector2d& v : shapeTriangles(localShape(shape))) {
      geometry_msgs::Point p;
      p.x = v.x();
      p.y = v.y();
      visual.points.push_back(p);
    }
    // Dragging the shape moves it in x-y; the ring turns it.
    control.name = "move";
    control.orientation = controlAxis(2);
    control.interaction_mode = InteractiveMarkerControl::MOVE_PLANE;
    control.markers.push_back(visual);
    im.controls.push_back(control);
    if (turns(shape)) {
      InteractiveMarkerControl turn;
      turn.name = "turn";
      turn.orientation = controlAxis(2);
      turn.interaction_mode = InteractiveMarkerControl::ROTATE_AXIS;
      im.controls.push_back(turn);
    }
  } else {
    const Eigen::Vector2d at = marker.shown.origin.head<2>() + handlePosition(shape, marker.handle);
    im.pose.position.x = at.x();
    im.pose.position.y = at.y();
    im.pose.orientation = yawQuaternion(pose.yaw);
    im.scale = 0.06;
    im.description = marker.handle;
    visual.type = visualization_msgs::Marker::CUBE;
    visual.scale.x = visual.scale.y = visual.scale.z = 0.03;
    visual.color = colour(1.0f, 0.8f, 0.1f, 0.9f);
    // Along the side it sizes: x for size_x and radii, y for size_y and the inner radius.
    control.name = "resize";
    control.orientation =
        controlAxis(marker.handle == "size_y" || marker.handle == "inner_radius" ? 1 : 0);
    control.interaction_mode = InteractiveMarkerControl::MOVE_AXIS;
    control.markers.push_back(visual);
    im.controls.push_back(control);
  }
  server_->insert(im, [this](const visualization_msgs::InteractiveMarkerFeedbackConstPtr& f) {
    onFeedback(f);
  });
  menu_.apply(*server_, name);
}

void RegionHandles::onFeedback(
    const visualization_msgs::InteractiveMarkerFeedbackConstPtr& feedback) {
  if (feedback->event_type != InteractiveMarkerFeedback::MOUSE_UP) {
    return;
  }
  std::string sampler;
  HandleShape edited;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = markers_.find(feedback->marker_name);
    if (it == markers_.end()) {
      return;
    }
    const Marker& marker = it->second;
    const RegionShape& shape = marker.shown.shape.shape;
    const Eigen::Vector2d at =
        Eigen::Vector2d(feedback->pose.position.x, feedback->pose.position.y) -
        marker.shown.origin.head<2>();
    const ShapePose pose = shapePose(shape);
    const double yaw = yawOf(feedback->pose.orientation);
    const Eigen::Vector2d was =
        marker.handle.empty() ? pose.centre : handlePosition(shape, marker.handle);
    const bool turned = marker.handle.empty() && turns(shape) &&
                        std::abs(std::remainder(yaw - pose.yaw, 2.0 * M_PI)) > 1e-9;
    if ((at - was).norm() < 1e-9 && !turned) {
      return;  // a click, not a drag
    }
    sampler = marker.shown.sampler;
    edited = marker.shown.shape;
    edited.shape = marker.handle.empty() ? moveShape(shape, ShapePose{at, turned ? yaw : pose.yaw})
                                         : resizeShape(shape, marker.handle, at);
  }
  // Not on the server's thread: serving a configuration shows the handles again.
  postCallback(edits_, [this, sampler, edited] { edit(sampler, edited); });
}

void RegionHandles::edit(const std::string& sampler, const HandleShape& edited) {
  std::string error;
  if (apply_(sampler, edited, error)) {
    return;  // served: show() has put the handles where the new configuration has them
  }
  ROS_ERROR_STREAM(ros::this_node::getName()
                   << ": region handles: the change of sampler '" << sampler
                   << "' was refused, its parameters stay: " << error);
  std::shared_ptr<const SceneGenerator> generator;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    generator = generator_;
  }
  if (generator) {
    show(generator);  // back where they were
  }
}

}  // namespace ros_interface
}  // namespace placement_samplers
