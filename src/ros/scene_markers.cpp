#include "placement_samplers/ros/scene_markers.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <sstream>

#include "placement_samplers/geometry/shape.hpp"
#include "placement_samplers/ros/conversions.hpp"
#include "placement_samplers/sampling/relation_links.hpp"
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
  /// A support surface is blue (namespace "surfaces"), 2 mm above the board it lies on, with
  /// its label (index and clearance).
  void shapeRegion(const SamplerRegion& region) {
    const Eigen::Vector3d lift(0.0, 0.0, region.surface ? 0.002 : region.keepOut ? 0.001 : 0.0);
    const char* ns = region.surface ? "surfaces" : region.keepOut ? "keep_out" : "regions";
    const std_msgs::ColorRGBA c = region.surface   ? colour(0.2f, 0.5f, 1.0f, 0.35f)
                                  : region.keepOut ? colour(0.9f, 0.15f, 0.15f, 0.35f)
                                                   : colour(0.2f, 0.9f, 0.2f, 0.25f);
    if (!region.label.empty()) {
      label(region.label, region.centre + lift, 0.0, colour(0.6f, 0.8f, 1.0f, 0.9f));
    }
    Marker& m =
        add(ns, Marker::TRIANGLE_LIST, Eigen::Isometry3d::Identity(), Eigen::Vector3d::Ones(), c);
    m.points.reserve(region.triangles.size());
    for (const Eigen::Vector3d& v : region.triangles) {
      geometry_msgs::Point p;
      p.x = v.x() + lift.x();
      p.y = v.y() + lift.y();
      p.z = v.z() + lift.z();
      m.points.push_back(p);
    }
  }

  /// @p text above the object's top, in namespace "labels" (rviz can switch it off).
  void label(std::string_view text, const Eigen::Vector3d& position, double top,
             const std_msgs::ColorRGBA& c = colour(1.0f, 1.0f, 1.0f, 0.9f)) {
    Marker& m = add("labels", Marker::TEXT_VIEW_FACING,
                    Eigen::Isometry3d(Eigen::Translation3d(position + Eigen::Vector3d(0, 0, top))),
                    Eigen::Vector3d(0.0, 0.0, kLabelHeight), c);
    m.id = kLabelIdBase + labels_++;
    m.text = text;
  }

  /// A world-aligned wire box around @p bounds at @p position, in namespace "physics".
  void outline(const Eigen::Vector3d& position, const Bounds& bounds,
               const std_msgs::ColorRGBA& c) {
    const double margin = 0.005;
    const double r = bounds.horizontalRadius + margin;
    const Eigen::Vector3d lo(-r, -r, bounds.bottomZ - margin);
    const Eigen::Vector3d hi(r, r, bounds.topZ + margin);
    Marker& m = add("physics", Marker::LINE_LIST, Eigen::Isometry3d(Eigen::Translation3d(position)),
                    Eigen::Vector3d(0.003, 0.0, 0.0), c);  // scale.x: line width [m]
    const auto corner = [&](int k) {
      geometry_msgs::Point p;
      p.x = (k & 1) ? hi.x() : lo.x();
      p.y = (k & 2) ? hi.y() : lo.y();
      p.z = (k & 4) ? hi.z() : lo.z();
      return p;
    };
    // The 12 edges: corner pairs that differ in one coordinate bit.
    for (int k = 0; k < 8; ++k) {
      for (int bit : {1, 2, 4}) {
        if ((k & bit) == 0) {
          m.points.push_back(corner(k));
          m.points.push_back(corner(k | bit));
        }
      }
    }
  }

  /// An arrow from @p from to @p to, in namespace "physics".
  void arrow(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const std_msgs::ColorRGBA& c) {
    // scale: shaft diameter, head diameter, head length [m]
    Marker& m = add("physics", Marker::ARROW, Eigen::Isometry3d::Identity(),
                    Eigen::Vector3d(0.004, 0.01, 0.015), c);
    m.points.resize(2);
    m.points[0] = toPoseMsg(from, Eigen::Quaterniond::Identity()).position;
    m.points[1] = toPoseMsg(to, Eigen::Quaterniond::Identity()).position;
  }

  /// A relation from an object to its target (namespace "relations"): green when it holds,
  /// red when not.
  void relation(const RelationLink& link) {
    Marker& m =
        add("relations", Marker::LINE_LIST, Eigen::Isometry3d::Identity(),
            Eigen::Vector3d(0.004, 0.0, 0.0),  // scale.x: line width [m]
            link.satisfied ? colour(0.1f, 0.85f, 0.2f, 0.9f) : colour(1.0f, 0.1f, 0.1f, 0.9f));
    m.points.push_back(toPoseMsg(link.from, Eigen::Quaterniond::Identity()).position);
    m.points.push_back(toPoseMsg(link.to, Eigen::Quaterniond::Identity()).position);
  }

  /// The physics ground plane: a thin slab whose top is just below @p z (so that regions
  /// drawn at the same height stay visible), covering @p lo .. @p hi in x and y.
  void ground(double z, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
    const double thickness = 0.004;
    const Eigen::Vector2d centre = 0.5 * (lo + hi);
    add("ground", Marker::CUBE,
        Eigen::Isometry3d(Eigen::Translation3d(centre.x(), centre.y(), z - 0.0015 - thickness / 2)),
        Eigen::Vector3d(hi.x() - lo.x(), hi.y() - lo.y(), thickness),
        colour(0.62f, 0.52f, 0.40f, 0.55f));
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

/// Whether the simulation moved, turned or dropped the object beyond the tolerances (the
/// opposite of the core's per-object stability).
bool unsettled(const PhysicsOutcome& o, const PhysicsSettings& settings) {
  return o.fallen || o.moved >= settings.positionTolerance ||
         o.turned >= settings.rotationTolerance;
}

std::string physicsLabel(std::string_view name, const PhysicsOutcome& o,
                         const PhysicsSettings& settings) {
  std::ostringstream text;
  text << name << ':' << std::fixed;
  if (o.fallen) {
    text << " fell,";
  }
  text << " moved " << std::setprecision(3) << o.moved << " m";
  if (o.turned >= settings.rotationTolerance) {
    text << ", turned " << std::setprecision(2) << o.turned << " rad";
  }
  return text.str();
}

/// x-y extent of what is drawn, so that the ground plane lies under all of it: @p p with
/// @p half on either side.
void growExtent(const Eigen::Vector3d& p, const Eigen::Vector2d& half, Eigen::Vector2d& lo,
                Eigen::Vector2d& hi) {
  lo = lo.cwiseMin(p.head<2>() - half);
  hi = hi.cwiseMax(p.head<2>() + half);
}

}  // namespace

visualization_msgs::MarkerArray makeSceneMarkers(const PreparedRequest& request,
                                                 const SceneResult& scene,
                                                 const std::string& frameId,
                                                 const ros::Time& stamp) {
  MarkerBuilder builder(frameId, stamp);
  const PhysicsSettings& physics = request.physics;
  const bool settled = scene.simulated && scene.physicsMode == PhysicsMode::Settle;
  const std_msgs::ColorRGBA alarm = colour(1.0f, 0.35f, 0.1f, 1.0f);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  // Labels float a little above the top of the geometry (its top offset after the pose).
  const double gap = 0.02;
  for (const FixtureSpec& f : request.fixtures) {
    builder.object("fixtures", *f.object, f.position, f.orientation,
                   colour(0.55f, 0.55f, 0.55f, 0.6f));
    builder.label(f.name, f.position, f.object->topOffset.z() + gap);
  }
  for (std::size_t i = 0; i < scene.placements.size(); ++i) {
    const ObjectPlacement& p = scene.placements[i];
    if (p.hidden) {
      continue;
    }
    const std_msgs::ColorRGBA c = objectColour(p.name);
    builder.object("objects", *p.object, p.position, p.orientation, c);
    const PhysicsOutcome* o =
        scene.simulated && i < scene.physics.size() ? &scene.physics[i] : nullptr;
    growExtent(o ? o->sampledPosition : p.position,
               Eigen::Vector2d::Constant(p.object->horizontalRadius), lo, hi);
    if (o == nullptr || !unsettled(*o, physics)) {
      // Under resting: stable the label gives the resting pose (its index in --describe).
      builder.label(p.restPose == ObjectPlacement::kUpright
                        ? std::string(p.name)
                        : std::string(p.name) + " (pose " + std::to_string(p.restPose) + ")",
                    p.position, p.object->topOffset.z() + gap);
      continue;
    }
    // Unsettled: a red outline where the answer has it; under settle also a faint copy at the
    // sampled pose and an arrow to where it went. The label stays where it was sampled when it
    // fell (a fallen object may lie far below the table, out of view).
    const Bounds bounds = shapesBounds(p.object->shapes, p.orientation);
    builder.outline(p.position, bounds, alarm);
    Eigen::Vector3d labelAt = p.position;
    double top = bounds.topZ;
    if (settled) {
      std_msgs::ColorRGBA faint = c;
      faint.a = 0.3f;
      builder.object("sampled", *p.object, o->sampledPosition, o->sampledOrientation, faint);
      builder.arrow(o->sampledPosition, p.position, alarm);
      if (o->fallen) {
        labelAt = o->sampledPosition;
        top = p.object->topOffset.z();
      }
    }
    // A little higher than a name: clear of the wire box.
    builder.label(physicsLabel(p.name, *o, physics), labelAt, top + 1.5 * gap, alarm);
  }
  for (const SamplerRegion& region : samplerRegions(request, scene)) {
    builder.region(region);
    if (region.triangles.empty()) {
      growExtent(region.centre, 0.5 * region.size, lo, hi);
    }
    for (const Eigen::Vector3d& v : region.triangles) {
      growExtent(v, Eigen::Vector2d::Zero(), lo, hi);
    }
  }
  for (const RelationLink& link : relationLinks(request, scene)) {
    builder.relation(link);
  }
  if (physics.groundZ && lo.x() <= hi.x()) {
    const double margin = 0.25;  // [m] around the objects and regions
    builder.ground(*physics.groundZ, lo - Eigen::Vector2d::Constant(margin),
                   hi + Eigen::Vector2d::Constant(margin));
  }
  return builder.take();
}

geometry_msgs::PoseArray makeScenePoses(const SceneResult& scene, const std::string& frameId,
                                        const ros::Time& stamp) {
  geometry_msgs::PoseArray poses;
  poses.header.frame_id = frameId;
  poses.header.stamp = stamp;
  for (const ObjectPlacement& p : scene.placements) {
    if (!p.hidden) {
      poses.poses.push_back(toPoseMsg(p.position, p.orientation));
    }
  }
  return poses;
}

}  // namespace ros_interface
}  // namespace placement_samplers
