#include "placement_samplers/ros/conversions.hpp"

#include <cmath>
#include <sstream>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/geometry/unit_quaternion.hpp"

namespace placement_samplers {
namespace ros_interface {

geometry_msgs::Pose toPoseMsg(const Eigen::Vector3d& position,
                              const Eigen::Quaterniond& orientation) {
  geometry_msgs::Pose pose;
  pose.position.x = position.x();
  pose.position.y = position.y();
  pose.position.z = position.z();
  pose.orientation.x = orientation.x();
  pose.orientation.y = orientation.y();
  pose.orientation.z = orientation.z();
  pose.orientation.w = orientation.w();
  return pose;
}

Eigen::Quaterniond fromQuaternionMsg(const geometry_msgs::Quaternion& q, const std::string& field) {
  const Eigen::Quaterniond out(q.w, q.x, q.y, q.z);
  if (!isUnitQuaternion(out)) {
    std::ostringstream text;
    text << field << " must be a unit quaternion, got (x " << q.x << ", y " << q.y << ", z " << q.z
         << ", w " << q.w << ")";
    if (q.x == 0.0 && q.y == 0.0 && q.z == 0.0 && q.w == 0.0) {
      text << "; use w: 1 for no rotation";
    }
    throw RequestError(text.str());
  }
  return out.normalized();
}

Shape fromSolidPrimitive(const shape_msgs::SolidPrimitive& primitive, const std::string& field) {
  const auto& d = primitive.dimensions;
  auto need = [&](std::size_t n, const char* what) {
    if (d.size() != n) {
      throw RequestError(field + ": a " + what + " needs " + std::to_string(n) +
                         " dimensions, got " + std::to_string(d.size()));
    }
  };
  Shape shape;
  switch (primitive.type) {
    case shape_msgs::SolidPrimitive::BOX:
      need(3, "box");
      shape = Shape::box(Eigen::Vector3d(d[shape_msgs::SolidPrimitive::BOX_X],
                                         d[shape_msgs::SolidPrimitive::BOX_Y],
                                         d[shape_msgs::SolidPrimitive::BOX_Z]));
      break;
    case shape_msgs::SolidPrimitive::SPHERE:
      need(1, "sphere");
      shape = Shape::sphere(d[shape_msgs::SolidPrimitive::SPHERE_RADIUS]);
      break;
    case shape_msgs::SolidPrimitive::CYLINDER:
      need(2, "cylinder");
      shape = Shape::cylinder(d[shape_msgs::SolidPrimitive::CYLINDER_RADIUS],
                              d[shape_msgs::SolidPrimitive::CYLINDER_HEIGHT]);
      break;
    default:
      throw RequestError(field + ": type must be BOX (1), SPHERE (2) or CYLINDER (3), got " +
                         std::to_string(static_cast<int>(primitive.type)));
  }
  return shape;  // sizes are checked with the request, in SceneGenerator::prepare()
}

SampleRequest toSampleRequest(const SamplePlacements::Request& req) {
  SampleRequest out;
  out.sampler = req.sampler;
  out.maxAttempts = req.max_attempts;
  for (std::size_t i = 0; i < req.fixtures.size(); ++i) {
    const Fixture& f = req.fixtures[i];
    const std::string field = "fixtures[" + std::to_string(i) + "]";
    RequestFixture fixture;
    fixture.name = f.name;
    fixture.object = f.object;
    fixture.position = Eigen::Vector3d(f.pose.position.x, f.pose.position.y, f.pose.position.z);
    if (!fixture.position.allFinite()) {
      throw RequestError(field + ".pose.position must be finite");
    }
    fixture.orientation = fromQuaternionMsg(f.pose.orientation, field + ".pose.orientation");
    if (f.object.empty()) {
      fixture.shape = fromSolidPrimitive(f.shape, field + ".shape");
    }
    out.fixtures.push_back(std::move(fixture));
  }
  if (req.use_reference_point) {
    if (!req.reference.empty()) {
      throw RequestError("give either reference or use_reference_point, not both");
    }
    const Eigen::Vector3d p(req.reference_point.x, req.reference_point.y, req.reference_point.z);
    if (!p.allFinite()) {
      throw RequestError("reference_point must be finite");
    }
    out.reference = Reference::at(p);
  } else if (!req.reference.empty()) {
    out.reference = Reference::named(req.reference);
  }
  switch (req.on_top) {
    case SamplePlacements::Request::ON_TOP_DEFAULT:
      break;
    case SamplePlacements::Request::ON_TOP_TRUE:
      out.onTop = true;
      break;
    case SamplePlacements::Request::ON_TOP_FALSE:
      out.onTop = false;
      break;
    default:
      throw RequestError(
          "on_top must be ON_TOP_DEFAULT (0), ON_TOP_TRUE (1) or ON_TOP_FALSE (2), got " +
          std::to_string(static_cast<int>(req.on_top)));
  }
  switch (req.collision_check) {
    case SamplePlacements::Request::CHECK_DEFAULT:
      break;
    case SamplePlacements::Request::CHECK_RADIUS:
      out.collisionCheck = CollisionMode::Radius;
      break;
    case SamplePlacements::Request::CHECK_FCL:
      out.collisionCheck = CollisionMode::Fcl;
      break;
    case SamplePlacements::Request::CHECK_RADIUS_AND_FCL:
      out.collisionCheck = CollisionMode::RadiusAndFcl;
      break;
    default:
      throw RequestError(
          "collision_check must be CHECK_DEFAULT (0), CHECK_RADIUS (1), CHECK_FCL (2) or "
          "CHECK_RADIUS_AND_FCL (3), got " +
          std::to_string(static_cast<int>(req.collision_check)));
  }
  switch (req.physics) {
    case SamplePlacements::Request::PHYSICS_DEFAULT:
      break;
    case SamplePlacements::Request::PHYSICS_NONE:
      out.physics = PhysicsMode::None;
      break;
    case SamplePlacements::Request::PHYSICS_CHECK:
      out.physics = PhysicsMode::Check;
      break;
    case SamplePlacements::Request::PHYSICS_SETTLE:
      out.physics = PhysicsMode::Settle;
      break;
    default:
      throw RequestError(
          "physics must be PHYSICS_DEFAULT (0), PHYSICS_NONE (1), PHYSICS_CHECK (2) or "
          "PHYSICS_SETTLE (3), got " +
          std::to_string(static_cast<int>(req.physics)));
  }
  return out;
}

placement_samplers::Scene toSceneMsg(const SceneResult& scene) {
  placement_samplers::Scene msg;
  msg.success = scene.success;
  msg.message = scene.message;
  msg.placements.reserve(scene.placements.size());
  msg.simulated = scene.simulated;
  msg.stable = scene.simulated && scene.stable;
  for (std::size_t i = 0; i < scene.placements.size(); ++i) {
    const ObjectPlacement& p = scene.placements[i];
    placement_samplers::Placement m;
    m.name = p.name;
    m.sampler = p.sampler;
    m.pose = toPoseMsg(p.position, p.orientation);
    m.attempts = p.attempts;
    m.rest_pose = p.restPose;
    // Without a simulation the sampled pose is the pose: a unit quaternion, never zeros.
    m.sampled_pose = m.pose;
    if (scene.simulated && i < scene.physics.size()) {
      const PhysicsOutcome& o = scene.physics[i];
      m.sampled_pose = toPoseMsg(o.sampledPosition, o.sampledOrientation);
      // Hidden objects are parked far away, out of the simulation.
      m.simulated = !p.hidden;
      m.moved = o.moved;
      m.turned = o.turned;
      m.fallen = o.fallen;
    }
    msg.placements.push_back(std::move(m));
  }
  return msg;
}

placement_samplers::Fixture toFixtureMsg(const FixtureSpec& fixture) {
  placement_samplers::Fixture msg;
  msg.name = fixture.name;
  msg.object = fixture.objectName;
  msg.pose = toPoseMsg(fixture.position, fixture.orientation);
  if (fixture.objectName.empty() && fixture.object && fixture.object->shapes.size() == 1) {
    // A request's primitive: the inverse of fromSolidPrimitive.
    const Shape& shape = fixture.object->shapes.front();
    using shape_msgs::SolidPrimitive;
    switch (shape.type) {
      case ShapeType::Box:
        msg.shape.type = SolidPrimitive::BOX;
        msg.shape.dimensions = {shape.size.x(), shape.size.y(), shape.size.z()};
        break;
      case ShapeType::Sphere:
        msg.shape.type = SolidPrimitive::SPHERE;
        msg.shape.dimensions = {shape.radius};
        break;
      case ShapeType::Cylinder:
        msg.shape.type = SolidPrimitive::CYLINDER;
        msg.shape.dimensions.resize(2);
        msg.shape.dimensions[SolidPrimitive::CYLINDER_HEIGHT] = shape.length;
        msg.shape.dimensions[SolidPrimitive::CYLINDER_RADIUS] = shape.radius;
        break;
      default:
        break;  // requests carry boxes, spheres and cylinders only
    }
  }
  return msg;
}

std::vector<geometry_msgs::TransformStamped> toTransforms(const SceneResult& scene,
                                                          const std::vector<FixtureSpec>& fixtures,
                                                          const std::string& frameId,
                                                          const std::string& tfPrefix,
                                                          const ros::Time& stamp) {
  std::vector<geometry_msgs::TransformStamped> out;
  auto add = [&](std::string_view name, const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
    geometry_msgs::TransformStamped t;
    t.header.stamp = stamp;
    t.header.frame_id = frameId;
    t.child_frame_id = tfPrefix;
    t.child_frame_id += name;
    t.transform.translation.x = p.x();
    t.transform.translation.y = p.y();
    t.transform.translation.z = p.z();
    t.transform.rotation.x = q.x();
    t.transform.rotation.y = q.y();
    t.transform.rotation.z = q.z();
    t.transform.rotation.w = q.w();
    out.push_back(t);
  };
  for (const FixtureSpec& f : fixtures) {
    add(f.name, f.position, f.orientation);
  }
  for (const ObjectPlacement& p : scene.placements) {
    add(p.name, p.position, p.orientation);
  }
  return out;
}

}  // namespace ros_interface
}  // namespace placement_samplers
