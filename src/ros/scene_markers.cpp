#include "placement_samplers/ros/scene_markers.hpp"

#include <array>

#include "placement_samplers/ros/conversions.hpp"
#include "placement_samplers/sampler_regions.hpp"

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

std_msgs::ColorRGBA paletteColour(std::size_t i) {
  static const std::array<std::array<float, 3>, 8> palette{{{0.90f, 0.30f, 0.24f},
                                                            {0.20f, 0.60f, 0.86f},
                                                            {0.18f, 0.80f, 0.44f},
                                                            {0.95f, 0.77f, 0.06f},
                                                            {0.61f, 0.35f, 0.71f},
                                                            {0.90f, 0.49f, 0.13f},
                                                            {0.10f, 0.74f, 0.61f},
                                                            {0.91f, 0.30f, 0.60f}}};
  const auto& c = palette[i % palette.size()];
  return colour(c[0], c[1], c[2], 1.0f);
}

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
    // A zero-width range still shows as a thin line.
    const Eigen::Vector3d size(std::max(region.size.x(), 0.002), std::max(region.size.y(), 0.002),
                               0.002);
    add("regions", Marker::CUBE, Eigen::Isometry3d(Eigen::Translation3d(region.centre)), size,
        colour(0.2f, 0.9f, 0.2f, 0.25f));
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

  Marker prototype_;
  visualization_msgs::MarkerArray array_;
};

}  // namespace

visualization_msgs::MarkerArray makeSceneMarkers(const PreparedRequest& request,
                                                 const SceneResult& scene,
                                                 const std::string& frameId,
                                                 const ros::Time& stamp) {
  MarkerBuilder builder(frameId, stamp);
  for (const FixtureSpec& f : request.fixtures) {
    builder.object("fixtures", *f.object, f.position, f.orientation,
                   colour(0.55f, 0.55f, 0.55f, 0.6f));
  }
  for (std::size_t i = 0; i < scene.placements.size(); ++i) {
    const ObjectPlacement& p = scene.placements[i];
    if (!p.hidden) {
      builder.object("objects", *p.object, p.position, p.orientation, paletteColour(i));
    }
  }
  for (const SamplerRegion& region : samplerRegions(request, scene)) {
    builder.region(region);
  }
  return builder.take();
}

}  // namespace ros_interface
}  // namespace placement_samplers
