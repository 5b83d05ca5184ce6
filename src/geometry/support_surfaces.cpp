// Provisional: box tops only, no merging, cuts or clearance (the full extraction replaces it).
#include "placement_samplers/geometry/support_surfaces.hpp"

#include <algorithm>
#include <cmath>

namespace placement_samplers {

SurfaceSearch findSupportSurfaces(const std::vector<Shape>& shapes, const Eigen::Isometry3d& pose,
                                  const SurfaceOptions& options) {
  SurfaceSearch out;
  for (const Shape& shape : shapes) {
    if (shape.type != ShapeType::Box) {
      continue;
    }
    const Eigen::Isometry3d world = pose * shape.pose;
    const Eigen::Matrix3d r = world.linear();
    if (r(2, 2) < std::cos(options.normalTolerance)) {
      continue;
    }
    const Eigen::Vector3d h = 0.5 * shape.size;
    SupportSurface s;
    double z = -1e300;
    for (const auto& c : {Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, -1), Eigen::Vector2d(1, 1),
                          Eigen::Vector2d(-1, 1)}) {
      const Eigen::Vector3d p = world * Eigen::Vector3d(c.x() * h.x(), c.y() * h.y(), h.z());
      s.outer.push_back(p.head<2>());
      z = std::max(z, p.z());
    }
    s.z = z;
    s.area = shape.size.x() * shape.size.y();
    if (s.area < options.minArea) {
      out.largestDroppedArea = std::max(out.largestDroppedArea, s.area);
      continue;
    }
    out.surfaces.push_back(s);
  }
  std::sort(out.surfaces.begin(), out.surfaces.end(),
            [](const SupportSurface& a, const SupportSurface& b) { return a.z < b.z; });
  return out;
}

SupportSurface movedSurface(const SupportSurface& surface, double yaw,
                            const Eigen::Vector3d& translation) {
  const Eigen::Rotation2Dd r(yaw);
  SupportSurface s = surface;
  for (Eigen::Vector2d& v : s.outer) {
    v = r * v + translation.head<2>();
  }
  for (auto& hole : s.holes) {
    for (Eigen::Vector2d& v : hole) {
      v = r * v + translation.head<2>();
    }
  }
  s.z += translation.z();
  return s;
}

}  // namespace placement_samplers
