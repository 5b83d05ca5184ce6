#include "placement_samplers/ros/scene_markers.hpp"

#include <array>
#include <cmath>
#include <cstdint>

#include "placement_samplers/ros/conversions.hpp"
#include "placement_samplers/sampling/sampler_regions.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

using visualization_msgs::Marker;

std_msgs::ColorRGBA colour(float r, float g, float b, float a) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

/// The ids of the label markers start here, so that an object's shapes and its label never
/// share an id within a namespace change.
constexpr int kLabelIdBase = 1 << 20;

}  // namespace

std_msgs::ColorRGBA objectColour(std::string_view name) {
  // FNV-1a of the name picks a hue: the same colour in every call and every run.
  std::uint32_t hash = 2166136261u;
  for (const char c : name) {
    hash = (hash ^ static_cast<unsigned char>(c)) * 16777619u;
  }
  const float hue = static_cast<float>(hash % 360u) / 60.0f;  // sector in [0, 6)
  const float saturation = 0.7f;
  const float value = 0.9f;
  const float chroma = value * saturation;
  const float x = chroma * (1.0f - std::fabs(std::fmod(hue, 2.0f) - 1.0f));
  const float m = value - chroma;
  static const std::array<std::array<int, 3>, 6> order{
      {{0, 1, 2}, {1, 0, 2}, {2, 0, 1}, {2, 1, 0}, {1, 2, 0}, {0, 2, 1}}};
  // Each sector of the hue circle: which channel gets chroma, x and 0.
  const auto& o = order[static_cast<std::size_t>(hue) % 6];
  const std::array<float, 3> parts{chroma, x, 0.0f};
  std::array<float, 3> rgb{};
  for (int k = 0; k < 3; ++k) {
    rgb[static_cast<std::size_t>(k)] = parts[static_cast<std::size_t>(o[k])] + m;
  }
  return colour(rgb[0], rgb[1], rgb[2], 1.0f);
}

visualization_msgs::MarkerArray makeClearMarkers() {
  visualization_msgs::MarkerArray array;
  Marker clear;
  clear.action = Marker::DELETEALL;
  array.markers.push_back(clear);
  return array;
}

namespace {

class MarkerBuilder {
 public:
  MarkerBuilder(const std::string& frameId, const ros::Time& stamp) {
    prototype_.header.frame_id = frameId;
    prototype_.header.stamp = stamp;
    prototype_.action = Marker::ADD;
    prototype_.pose.orientation.w = 1.0;
    Marker clear;
    clear.header = prototype_.header;
    clear.action = Marker::DELETEALL;
    array_.markers.push_back(clear);
  }

  void object(const std::string& ns, const ObjectModel& object, const Eigen::Vector3d& position,
              const Eigen::Quaterniond& orientation, const std_msgs::ColorRGBA& colour) {
    const Eigen::Isometry3d pose = Eigen::Translation3d(position) * orientation;
    for (const Shape& shape : object.shapes) {
      const Eigen::Isometry3d shapePose = pose * shape.pose;
      switch (shape.type) {
        case ShapeType::Box:
          add(ns, Marker::CUBE, shapePose, shape.size, colour);
          break;
        case ShapeType::Cylinder:
          add(ns, Marker::CYLINDER, shapePose,
              Eigen::Vector3d(2 * shape.radius, 2 * shape.radius, shape.length), colour);
          break;
        case ShapeType::Sphere:
          add(ns, Marker::SPHERE, shapePose, Eigen::Vector3d::Constant(2 * shape.radius), colour);
          break;
        case ShapeType::Capsule: {
          add(ns, Marker::CYLINDER, shapePose,
              Eigen::Vector3d(2 * shape.radius, 2 * shape.radius, shape.length), colour);
          for (double s : {-0.5, 0.5}) {
            add(ns, Marker::SPHERE, shapePose * Eigen::Translation3d(0.0, 0.0, s * shape.length),
                Eigen::Vector3d::Constant(2 * shape.radius), colour);
          }
          break;
        }
        case ShapeType::Mesh:
          mesh(ns, shapePose, *shape.mesh, colour);
          break;
      }
    }
  }

  void region(const SamplerRegion& region) {
    if (!region.triangles.empty()) {
      shapeRegion(region);
      return;
    }
    // A zero-width range still shows as a thin line.
    const Eigen::Vector3d size(std::max(region.size.x(), 0.002), std::max(region.size.y(), 0.002),
                               0.002);
    add("regions", Marker::CUBE, Eigen::Isometry3d(Eigen::Translation3d(region.centre)), size,
        colour(0.2f, 0.9f, 0.2f, 0.25f));
  }

  /// Any other region shape, green, or a keep-out zone, red (namespace "keep_out"), as
  /// triangles 1 mm above the regions so a zone shows over its sampler's region.
  void shapeRegion(const SamplerRegion& region) {
    const Eigen::Vector3d lift(0.0, 0.0, region.keepOut ? 0.001 : 0.0);
    Marker& m =
        add(region.keepOut ? "keep_out" : "regions", Marker::TRIANGLE_LIST,
            Eigen::Isometry3d::Identity(), Eigen::Vector3d::Ones(),
            region.keepOut ? colour(0.9f, 0.15f, 0.15f, 0.35f) : colour(0.2f, 0.9f, 0.2f, 0.25f));
    m.points.reserve(region.triangles.size());
    for (const Eigen::Vector3d& v : region.triangles) {
      geometry_msgs::Point p;
      p.x = v.x() + lift.x();
      p.y = v.y() + lift.y();
      p.z = v.z() + lift.z();
      m.points.push_back(p);
    }
  }

  /// The name above the object's top, in namespace "labels" (rviz can switch it off).
  void label(std::string_view name, const Eigen::Vector3d& position, double top) {
    Marker& m = add("labels", Marker::TEXT_VIEW_FACING,
                    Eigen::Isometry3d(Eigen::Translation3d(position + Eigen::Vector3d(0, 0, top))),
                    Eigen::Vector3d(0.0, 0.0, kLabelHeight), colour(1.0f, 1.0f, 1.0f, 0.9f));
    m.id = kLabelIdBase + labels_++;
    m.text = name;
  }

  visualization_msgs::MarkerArray take() { return std::move(array_); }

 private:
  Marker& add(const std::string& ns, int type, const Eigen::Isometry3d& pose,
              const Eigen::Vector3d& scale, const std_msgs::ColorRGBA& c) {
    Marker m = prototype_;
    m.ns = ns;
    m.id = static_cast<int>(array_.markers.size());
    m.type = type;
    m.pose = toPoseMsg(pose.translation(), Eigen::Quaterniond(pose.linear()));
    m.scale.x = scale.x();
    m.scale.y = scale.y();
    m.scale.z = scale.z();
    m.color = c;
    array_.markers.push_back(m);
    return array_.markers.back();
  }

  void mesh(const std::string& ns, const Eigen::Isometry3d& pose, const Mesh& mesh,
            const std_msgs::ColorRGBA& c) {
    Marker& m = add(ns, Marker::TRIANGLE_LIST, pose, Eigen::Vector3d::Ones(), c);
    m.points.reserve(mesh.triangles.size() * 3);
    for (const Eigen::Vector3i& t : mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d& v = mesh.vertices[static_cast<std::size_t>(t[k])];
        geometry_msgs::Point p;
        p.x = v.x();
        p.y = v.y();
        p.z = v.z();
        m.points.push_back(p);
      }
    }
  }

  static constexpr double kLabelHeight = 0.03;  ///< text height [m]: readable at 2 m
  Marker prototype_;
  visualization_msgs::MarkerArray array_;
  int labels_ = 0;
};

}  // namespace

visualization_msgs::MarkerArray makeSceneMarkers(const PreparedRequest& request,
                                                 const SceneResult& scene,
                                                 const std::string& frameId,
                                                 const ros::Time& stamp) {
  MarkerBuilder builder(frameId, stamp);
  // Labels float a little above the top of the geometry (its top offset after the pose).
  const double gap = 0.02;
  for (const FixtureSpec& f : request.fixtures) {
    builder.object("fixtures", *f.object, f.position, f.orientation,
                   colour(0.55f, 0.55f, 0.55f, 0.6f));
    builder.label(f.name, f.position, f.object->topOffset.z() + gap);
  }
  for (const ObjectPlacement& p : scene.placements) {
    if (!p.hidden) {
      builder.object("objects", *p.object, p.position, p.orientation, objectColour(p.name));
      builder.label(p.name, p.position, p.object->topOffset.z() + gap);
    }
  }
  for (const SamplerRegion& region : samplerRegions(request, scene)) {
    builder.region(region);
  }
  return builder.take();
}

}  // namespace ros_interface
}  // namespace placement_samplers
