// Up-facing faces of boxes and caps of cylinders, and every primitive's height extent and
// footprint (convex, round shapes circumscribed so that a cut is never too small).

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/surface_parts.hpp"

namespace placement_samplers {
namespace surfaces {
namespace {

bool usable(const Eigen::Vector3d& p) {
  return p.allFinite() && p.cwiseAbs().maxCoeff() <= kFarAway;
}

/// A regular polygon of @p count vertices and circumradius @p radius about the z axis of
/// @p pose at local height @p z, in the frame of the surfaces.
std::vector<Eigen::Vector3d> circle(const Eigen::Isometry3d& pose, double radius, double z,
                                    int count) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(count);
  for (int k = 0; k < count; ++k) {
    const double t = 2.0 * M_PI * k / count;
    points.push_back(pose * Eigen::Vector3d(radius * std::cos(t), radius * std::sin(t), z));
  }
  return points;
}

/// Circumradius of the kCutVertices-gon whose inscribed circle has radius @p radius.
double circumscribed(double radius) { return radius / std::cos(M_PI / kCutVertices); }

/// Adds the obstacle of a primitive spanning @p points in 2-D and [zMin, zMax] in height.
/// @return its index, or -1 when it is left out (non-finite or far away)
int addObstacle(const std::vector<Eigen::Vector3d>& points, double zMin, double zMax,
                SurfaceParts& parts) {
  std::vector<Point2> xy;
  xy.reserve(points.size());
  for (const Eigen::Vector3d& p : points) {
    if (!usable(p)) {
      return -1;
    }
    xy.push_back(p.head<2>());
  }
  if (!std::isfinite(zMin) || !std::isfinite(zMax)) {
    return -1;
  }
  Obstacle obstacle;
  obstacle.zMin = zMin;
  obstacle.zMax = zMax;
  obstacle.footprint = convexHull(std::move(xy));
  obstacle.box = ringBox(obstacle.footprint);
  parts.primitives.push_back(std::move(obstacle));
  return static_cast<int>(parts.primitives.size()) - 1;
}

/// Adds the planar facet with corners @p corners (in order around it) and outward unit normal
/// @p normal; @p zMax its highest point.
void addFacet(const std::vector<Eigen::Vector3d>& corners, const Eigen::Vector3d& normal,
              double zMax, int element, SurfaceParts& parts) {
  Facet facet;
  facet.element = element;
  Ring outer;
  double zMin = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : corners) {
    outer.push_back(p.head<2>());
    zMin = std::min(zMin, p.z());
  }
  if (signedArea(outer) < 0.0) {
    std::reverse(outer.begin(), outer.end());
  }
  if (!simplifyRing(outer)) {
    return;
  }
  facet.zMax = zMax;
  facet.horizontal = zMax - zMin <= kHeightTolerance;
  if (facet.horizontal) {
    facet.plane.c = zMax;
  } else {
    const Eigen::Vector3d& p = corners.front();
    facet.plane.a = -normal.x() / normal.z();
    facet.plane.b = -normal.y() / normal.z();
    facet.plane.c = p.z() - facet.plane.a * p.x() - facet.plane.b * p.y();
  }
  facet.box = ringBox(outer);
  facet.polygons.push_back(Polygon2{std::move(outer), {}});
  parts.facets.push_back(std::move(facet));
}

void addBox(const Eigen::Vector3d& size, const Eigen::Isometry3d& pose, double cosTolerance,
            SurfaceParts& parts) {
  const Eigen::Vector3d half = 0.5 * size;
  std::vector<Eigen::Vector3d> corners(8);
  double zMin = std::numeric_limits<double>::infinity();
  double zMax = -zMin;
  for (int i = 0; i < 8; ++i) {
    corners[i] =
        pose * Eigen::Vector3d((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                               (i & 4) ? half.z() : -half.z());
    zMin = std::min(zMin, corners[i].z());
    zMax = std::max(zMax, corners[i].z());
  }
  const int element = addObstacle(corners, zMin, zMax, parts);
  if (element < 0) {
    return;
  }
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const Eigen::Vector3d normal = (side ? 1.0 : -1.0) * pose.linear().col(axis);
      if (!(normal.z() >= cosTolerance) || normal.z() <= 0.0) {
        continue;
      }
      // The four corners with this axis' bit set as the side, around the face.
      const int u = 1 << ((axis + 1) % 3);
      const int v = 1 << ((axis + 2) % 3);
      const int base = side ? (1 << axis) : 0;
      std::vector<Eigen::Vector3d> face = {corners[base], corners[base | u], corners[base | u | v],
                                           corners[base | v]};
      double faceTop = -std::numeric_limits<double>::infinity();
      for (const Eigen::Vector3d& p : face) {
        faceTop = std::max(faceTop, p.z());
      }
      addFacet(face, normal, faceTop, element, parts);
    }
  }
}

void addCylinder(double radius, double length, const Eigen::Isometry3d& pose, double cosTolerance,
                 SurfaceParts& parts) {
  const Eigen::Vector3d axis = pose.linear().col(2);
  const double half = 0.5 * length;
  const double rim = std::abs(radius) * std::sqrt(std::max(0.0, 1.0 - axis.z() * axis.z()));
  const double zSpan = std::abs(half * axis.z()) + rim;
  std::vector<Eigen::Vector3d> hull = circle(pose, circumscribed(radius), -half, kCutVertices);
  const std::vector<Eigen::Vector3d> top = circle(pose, circumscribed(radius), half, kCutVertices);
  hull.insert(hull.end(), top.begin(), top.end());
  const double zCentre = pose.translation().z();
  const int element = addObstacle(hull, zCentre - zSpan, zCentre + zSpan, parts);
  if (element < 0) {
    return;
  }
  for (double side : {-1.0, 1.0}) {
    const Eigen::Vector3d normal = side * axis;
    if (!(normal.z() >= cosTolerance) || normal.z() <= 0.0) {
      continue;
    }
    // The rim's highest point, above every vertex of the inscribed polygon.
    const double capTop = (pose * Eigen::Vector3d(0.0, 0.0, side * half)).z() + rim;
    addFacet(circle(pose, radius, side * half, kCapVertices), normal, capTop, element, parts);
  }
}

}  // namespace

void addPrimitive(const Shape& shape, const Eigen::Isometry3d& pose, double cosTolerance,
                  SurfaceParts& parts) {
  const double r = std::abs(shape.radius);
  switch (shape.type) {
    case ShapeType::Box:
      addBox(shape.size, pose, cosTolerance, parts);
      break;
    case ShapeType::Cylinder:
      addCylinder(shape.radius, shape.length, pose, cosTolerance, parts);
      break;
    case ShapeType::Sphere: {
      // About the centre in the frame's x-y plane (a turned polygon's projection would be thin).
      Eigen::Isometry3d at = Eigen::Isometry3d::Identity();
      at.translation() = pose.translation();
      const double z = at.translation().z();
      addObstacle(circle(at, circumscribed(r), 0.0, kCutVertices), z - r, z + r, parts);
      break;
    }
    case ShapeType::Capsule: {
      // Two circumscribed polygons about the projected ends (not turned with the axis).
      std::vector<Eigen::Vector3d> points;
      double zMin = std::numeric_limits<double>::infinity();
      double zMax = -zMin;
      for (double side : {-1.0, 1.0}) {
        const Eigen::Vector3d end = pose * Eigen::Vector3d(0.0, 0.0, side * 0.5 * shape.length);
        zMin = std::min(zMin, end.z() - r);
        zMax = std::max(zMax, end.z() + r);
        Eigen::Isometry3d at = Eigen::Isometry3d::Identity();
        at.translation() = end;
        const std::vector<Eigen::Vector3d> ring = circle(at, circumscribed(r), 0.0, kCutVertices);
        points.insert(points.end(), ring.begin(), ring.end());
      }
      addObstacle(points, zMin, zMax, parts);
      break;
    }
    case ShapeType::Mesh:
      break;  // addMesh
  }
}

}  // namespace surfaces
}  // namespace placement_samplers
