// Provisional (not committed): boxes' six faces only.
#include "placement_samplers/geometry/resting_poses.hpp"
#include <cmath>
namespace placement_samplers {
Eigen::Vector3d centreOfMass(const std::vector<Shape>&) { return Eigen::Vector3d::Zero(); }
std::vector<RestingPose> restingPoses(const std::vector<Shape>& shapes, const RestingOptions&) {
  std::vector<RestingPose> out;
  if (shapes.size() != 1 || shapes[0].type != ShapeType::Box) return out;
  const Eigen::Vector3d h = 0.5 * shapes[0].size;
  for (int axis = 0; axis < 3; ++axis) for (int sign : {-1, 1}) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero(); n[axis] = sign;
    RestingPose p; p.normal = n;
    p.orientation = Eigen::Quaterniond::FromTwoVectors(n, -Eigen::Vector3d::UnitZ());
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    p.probability = 4.0 * std::atan(h[a] * h[b] / (h[axis] * h.norm())) / (4.0 * M_PI);
    p.bounds = shapesBounds(shapes, p.orientation);
    out.push_back(p);
  }
  return out;
}
}
