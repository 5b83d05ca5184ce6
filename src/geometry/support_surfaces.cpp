#include "placement_samplers/geometry/support_surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include "geometry/surface_parts.hpp"

namespace placement_samplers {
namespace {

using namespace surfaces;

const Eigen::Vector2d& lowestXVertex(const std::vector<Eigen::Vector2d>& ring) {
  return *std::min_element(ring.begin(), ring.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
}

}  // namespace

SurfaceSearch findSupportSurfaces(const std::vector<Shape>& shapes, const Eigen::Isometry3d& pose,
                                  const SurfaceOptions& options) {
  // A tolerance beyond a right angle would take side faces; NaN takes none but exact +z.
  const double tolerance =
      options.normalTolerance >= 0.0 ? std::min(options.normalTolerance, 0.5 * M_PI) : 0.0;
  const double cosTolerance = std::cos(tolerance);
  SurfaceParts parts;
  for (const Shape& shape : shapes) {
    const Eigen::Isometry3d placed = pose * shape.pose;
    if (shape.type == ShapeType::Mesh) {
      if (shape.mesh) {
        addMesh(*shape.mesh, placed, cosTolerance, parts);
      }
    } else {
      addPrimitive(shape, placed, cosTolerance, parts);
    }
  }
  SurfaceSearch search = extractSurfaces(parts, clusterFacets(parts.facets), options);
  std::vector<std::pair<Eigen::Vector2d, std::size_t>> keys;
  for (std::size_t i = 0; i < search.surfaces.size(); ++i) {
    keys.emplace_back(lowestXVertex(search.surfaces[i].outer), i);
  }
  std::stable_sort(keys.begin(), keys.end(), [&](const auto& a, const auto& b) {
    const double za = search.surfaces[a.second].z;
    const double zb = search.surfaces[b.second].z;
    if (za != zb) {
      return za < zb;
    }
    if (a.first.x() != b.first.x()) {
      return a.first.x() < b.first.x();
    }
    return a.first.y() < b.first.y();
  });
  std::vector<SupportSurface> sorted;
  sorted.reserve(keys.size());
  for (const auto& key : keys) {
    sorted.push_back(std::move(search.surfaces[key.second]));
  }
  search.surfaces.swap(sorted);
  return search;
}

SupportSurface movedSurface(const SupportSurface& surface, double yaw,
                            const Eigen::Vector3d& translation) {
  const Eigen::Rotation2Dd turn(yaw);
  const Eigen::Vector2d shift = translation.head<2>();
  SupportSurface moved = surface;
  moved.z = surface.z + translation.z();
  for (Eigen::Vector2d& p : moved.outer) {
    p = turn * p + shift;
  }
  for (auto& hole : moved.holes) {
    for (Eigen::Vector2d& p : hole) {
      p = turn * p + shift;
    }
  }
  return moved;
}

}  // namespace placement_samplers
