#include "placement_samplers/geometry/resting_poses.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>

#include "geometry/convex_hull.hpp"
#include "geometry/resting_hull.hpp"

namespace placement_samplers {
namespace {

/// The rotation that puts outward normal @p n along -z, turned about z so that the object's x
/// axis (its y axis when x ends up vertical) moves as little as possible.
Eigen::Quaterniond restOrientation(const Eigen::Vector3d& n) {
  Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(n, -Eigen::Vector3d::UnitZ());
  for (const Eigen::Vector3d& axis :
       {Eigen::Vector3d(Eigen::Vector3d::UnitX()), Eigen::Vector3d(Eigen::Vector3d::UnitY())}) {
    const Eigen::Vector3d turned = q * axis;
    if (turned.head<2>().norm() > 1e-9) {
      const double yaw = std::atan2(axis.y(), axis.x()) - std::atan2(turned.y(), turned.x());
      q = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * q;
      break;
    }
  }
  q.normalize();
  if (q.w() < 0.0) {
    q.coeffs() = -q.coeffs();  // one sign for the same rotation
  }
  return q;
}

RestingPose makePose(const std::vector<Shape>& shapes, const Eigen::Vector3d& normal,
                     double probability, bool rolling) {
  RestingPose pose;
  pose.normal = normal.normalized();
  pose.orientation = restOrientation(pose.normal);
  pose.probability = probability;
  pose.bounds = shapesBounds(shapes, pose.orientation);
  pose.rolling = rolling;
  return pose;
}

/// Scales the probabilities to sum to 1; drops all poses when they sum to nothing.
void normalise(std::vector<RestingPose>& poses) {
  double total = 0.0;
  for (const RestingPose& p : poses) {
    total += p.probability;
  }
  if (!(total > 0.0)) {
    poses.clear();
    return;
  }
  for (RestingPose& p : poses) {
    p.probability /= total;
  }
}

/// A box's six faces; a face narrower than twice the margin is not stable and passes its share
/// on equally to its stable neighbours (a thin rod's ends to its sides).
std::vector<RestingPose> boxPoses(const std::vector<Shape>& shapes, const RestingOptions& options) {
  const Shape& box = shapes[0];
  const Eigen::Vector3d half = 0.5 * box.size;
  const Eigen::Matrix3d r = box.pose.linear();
  double share[3], depth[3];
  for (int k = 0; k < 3; ++k) {
    const double a = half[(k + 1) % 3], b = half[(k + 2) % 3], d = half[k];
    // A rectangle of half sides a, b seen from distance d on its axis, over 4 pi.
    share[k] = std::atan(a * b / (d * std::sqrt(a * a + b * b + d * d))) / M_PI;
    depth[k] = std::min(a, b);
  }
  auto stable = [&](int k) { return depth[k] >= options.margin && depth[k] > 0.0; };
  double total[3] = {0.0, 0.0, 0.0};  // per axis, for each of its two faces
  for (int k = 0; k < 3; ++k) {
    if (stable(k)) {
      total[k] += share[k];
      continue;
    }
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const int receivers = (stable(i) ? 1 : 0) + (stable(j) ? 1 : 0);
    for (int m : {i, j}) {
      if (stable(m)) {
        total[m] += share[k] / receivers;  // one face of k to four faces: 2 per axis, halved
      }
    }
  }
  std::vector<RestingPose> poses;
  for (int k = 0; k < 3; ++k) {
    if (stable(k)) {
      for (double sign : {-1.0, 1.0}) {
        poses.push_back(makePose(shapes, sign * r.col(k), total[k], false));
      }
    }
  }
  normalise(poses);
  return poses;
}

/// The direction across @p axis that turns the object least when put down: -z, else -y.
Eigen::Vector3d sideNormal(const Eigen::Vector3d& axis) {
  for (const Eigen::Vector3d& down :
       {Eigen::Vector3d(-Eigen::Vector3d::UnitZ()), Eigen::Vector3d(-Eigen::Vector3d::UnitY())}) {
    const Eigen::Vector3d across = down - down.dot(axis) * axis;
    if (across.norm() > 1e-6) {
      return across.normalized();
    }
  }
  return -Eigen::Vector3d::UnitX();  // not reached: -z and -y are never both along the axis
}

/// A cylinder: two caps, and its side (rolling) when allowed; a capsule: its side only.
std::vector<RestingPose> roundPoses(const std::vector<Shape>& shapes,
                                    const RestingOptions& options) {
  const Shape& shape = shapes[0];
  const Eigen::Vector3d axis = shape.pose.linear().col(2);
  std::vector<RestingPose> poses;
  double side = 1.0;
  if (shape.type == ShapeType::Cylinder) {
    // A disc of radius r seen from distance h on its axis: 2 pi (1 - h / sqrt(h^2 + r^2)).
    const double h = 0.5 * shape.length, r = shape.radius;
    const double cap = 0.5 * (1.0 - h / std::sqrt(h * h + r * r));
    if (r >= options.margin) {
      for (double sign : {-1.0, 1.0}) {
        poses.push_back(makePose(shapes, sign * axis, cap, false));
      }
      side = 1.0 - 2.0 * cap;
    }
  }
  if (options.allowRolling) {
    poses.push_back(makePose(shapes, sideNormal(axis), side, true));
  }
  normalise(poses);
  return poses;
}

std::vector<RestingPose> hullPoses(const std::vector<Shape>& shapes,
                                   const RestingOptions& options) {
  const detail::RestingHull r = detail::restingHull(shapes, options);
  std::vector<RestingPose> poses;
  for (const detail::RestingHull::Sink& sink : r.sinks) {
    if (!sink.rolling || options.allowRolling) {
      poses.push_back(makePose(shapes, r.hull.normals[static_cast<std::size_t>(sink.face)],
                               sink.share, sink.rolling));
    }
  }
  normalise(poses);
  return poses;
}

/// Most probable first; ties (to 1e-12) by the normal's x, y, z (to 1e-9), so that the same
/// object through the hull or in closed form lists its poses in one order.
void sortPoses(std::vector<RestingPose>& poses) {
  auto key = [](const RestingPose& p) {
    return std::make_tuple(-std::llround(p.probability * 1e12), std::llround(p.normal.x() * 1e9),
                           std::llround(p.normal.y() * 1e9), std::llround(p.normal.z() * 1e9));
  };
  std::stable_sort(poses.begin(), poses.end(),
                   [&](const RestingPose& a, const RestingPose& b) { return key(a) < key(b); });
}

/// What MuJoCo 2.2.2, as the physics builds its model, makes of a mesh geom's mass: the physics
/// gives it the vertices only, MuJoCo takes their convex hull, puts the centre of mass at the
/// hull's centroid, but weighs it by the volume of the box with the same inertia (a tetrahedron
/// by 1.39 times its volume, a box by its own). @p centroid gets the hull's centroid; a flat
/// mesh (no hull) weighs nothing.
double meshWeight(const Shape& shape, Eigen::Vector3d& centroid) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(shape.mesh->vertices.size());
  for (const Eigen::Vector3d& v : shape.mesh->vertices) {
    points.push_back(shape.pose * v);
  }
  double volume = 0.0;
  Eigen::Matrix3d spread;
  try {
    std::optional<detail::ConvexHull> hull = detail::convexMeshHull(points, shape.mesh->triangles);
    detail::hullVolume(hull ? *hull : detail::convexHull(points), points, volume, centroid,
                       &spread);
  } catch (const std::invalid_argument&) {
    return 0.0;
  }
  if (!(volume > 0.0)) {
    return 0.0;
  }
  // Principal moments of inertia per unit density, then the box that has them:
  // I_xx = V (b^2 + c^2) / 3 for half sides a, b, c.
  const Eigen::Matrix3d inertia = spread.trace() * Eigen::Matrix3d::Identity() - spread;
  const Eigen::Vector3d moments =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues();
  double box = 8.0;
  for (int k = 0; k < 3; ++k) {
    const double twice = moments.sum() - 2.0 * moments[k];  // I_j + I_k - I_i
    box *= std::sqrt(std::max(0.0, 1.5 * twice / volume));
  }
  return box;
}

}  // namespace

Eigen::Vector3d centreOfMass(const std::vector<Shape>& shapes) {
  if (shapes.empty()) {
    throw std::invalid_argument("centre of mass: the object has no shapes");
  }
  double total = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (const Shape& shape : shapes) {
    double volume = 0.0;
    Eigen::Vector3d centroid = shape.pose.translation();
    const double r = shape.radius;
    switch (shape.type) {
      case ShapeType::Box:
        volume = shape.size.prod();
        break;
      case ShapeType::Cylinder:
        volume = M_PI * r * r * shape.length;
        break;
      case ShapeType::Sphere:
        volume = 4.0 / 3.0 * M_PI * r * r * r;
        break;
      case ShapeType::Capsule:
        volume = M_PI * r * r * shape.length + 4.0 / 3.0 * M_PI * r * r * r;
        break;
      case ShapeType::Mesh:
        volume = meshWeight(shape, centroid);
        break;
    }
    total += volume;
    moment += volume * centroid;
  }
  if (!(total > 0.0)) {
    throw std::invalid_argument("centre of mass: the shapes enclose no volume");
  }
  return moment / total;
}

std::vector<RestingPose> restingPoses(const std::vector<Shape>& shapes,
                                      const RestingOptions& options) {
  if (shapes.empty()) {
    throw std::invalid_argument("resting poses: the object has no shapes");
  }
  if (!std::isfinite(options.margin) || options.margin < 0.0) {
    std::ostringstream message;
    message << "resting poses: the margin must be finite and at least 0 m, got " << options.margin;
    throw std::invalid_argument(message.str());
  }
  std::vector<RestingPose> poses;
  if (shapes.size() > 1 || shapes[0].type == ShapeType::Mesh) {
    poses = hullPoses(shapes, options);
  } else if (shapes[0].type == ShapeType::Box) {
    poses = boxPoses(shapes, options);
  } else if (shapes[0].type != ShapeType::Sphere) {
    poses = roundPoses(shapes, options);
  }
  sortPoses(poses);
  return poses;
}

}  // namespace placement_samplers
