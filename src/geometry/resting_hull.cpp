#include "geometry/resting_hull.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>

namespace placement_samplers::detail {
namespace {

/// Rings of a sphere's polyhedron between its poles, and of a capsule's hemisphere from the
/// equator up (the pole apart).
constexpr int kSphereRings = kCircleSegments / 2 - 1;
constexpr int kCapRings = kCircleSegments / 4;

std::size_t pointCount(const Shape& shape) {
  switch (shape.type) {
    case ShapeType::Box:
      return 8;
    case ShapeType::Cylinder:
      return 2 * kCircleSegments;
    case ShapeType::Sphere:
      return kSphereRings * kCircleSegments + 2;
    case ShapeType::Capsule:
      return 2 * (kCapRings * kCircleSegments + 1);
    case ShapeType::Mesh:
      return shape.mesh ? shape.mesh->vertices.size() : 0;
  }
  return 0;
}

/// A ring of kCircleSegments points at height @p z and radius @p r about the local z axis.
void addRing(HullPoints& out, const Eigen::Isometry3d& pose, double r, double z, int curve) {
  for (int k = 0; k < kCircleSegments; ++k) {
    const double t = 2.0 * M_PI * k / kCircleSegments;
    out.points.push_back(pose * Eigen::Vector3d(r * std::cos(t), r * std::sin(t), z));
    out.curve.push_back(curve);
  }
}

int addCurve(HullPoints& out, const Eigen::Isometry3d& pose, double z, double radius, bool sphere) {
  HullPoints::Curve c;
  c.centre = pose * Eigen::Vector3d(0.0, 0.0, z);
  c.axis = pose.linear().col(2);
  c.radius = radius;
  c.sphere = sphere;
  out.curves.push_back(c);
  return static_cast<int>(out.curves.size()) - 1;
}

/// A hemisphere of radius @p r centred at height @p z, towards +z (@p up) or -z.
void addHemisphere(HullPoints& out, const Eigen::Isometry3d& pose, double r, double z, bool up) {
  const int curve = addCurve(out, pose, z, r, true);
  const double sign = up ? 1.0 : -1.0;
  for (int j = 0; j < kCapRings; ++j) {
    const double polar = 2.0 * M_PI * j / kCircleSegments;  // from the equator
    addRing(out, pose, r * std::cos(polar), z + sign * r * std::sin(polar), curve);
  }
  out.points.push_back(pose * Eigen::Vector3d(0.0, 0.0, z + sign * r));
  out.curve.push_back(curve);
}

/// The point where the true surface that @p curve samples touches a plane of outward normal
/// @p n that touches its polygon at @p p.
Eigen::Vector3d contactPoint(const HullPoints::Curve& curve, const Eigen::Vector3d& p,
                             const Eigen::Vector3d& n) {
  if (curve.sphere) {
    return curve.centre + curve.radius * n;
  }
  const Eigen::Vector3d across = n - n.dot(curve.axis) * curve.axis;
  const double length = across.norm();
  if (length < 1e-9) {
    return p;  // a cap: the disc lies on the plane, its polygon's corners stand for it
  }
  return curve.centre + curve.radius * across / length;
}

double cross2(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

/// How far inside the convex hull of @p points (2-d) the origin lies: the smallest distance to
/// its edges, negative outside; -infinity when the hull is a point or a segment. @p points is
/// reordered; @p chain is scratch space.
double depthInHull(std::vector<Eigen::Vector2d>& points, std::vector<Eigen::Vector2d>& chain) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  chain.clear();
  // Andrew's monotone chain, counter-clockwise, collinear points left out.
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t base = chain.size();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector2d& p = pass == 0 ? points[i] : points[points.size() - 1 - i];
      while (chain.size() >= base + 2 && cross2(chain[chain.size() - 2], chain.back(), p) <= 0.0) {
        chain.pop_back();
      }
      chain.push_back(p);
    }
    chain.pop_back();
  }
  if (chain.size() < 3) {
    return -std::numeric_limits<double>::infinity();
  }
  double depth = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < chain.size(); ++i) {
    const Eigen::Vector2d& a = chain[i];
    const Eigen::Vector2d& b = chain[(i + 1) % chain.size()];
    const double length = (b - a).norm();
    if (length > 0.0) {
      depth = std::min(depth, cross2(a, b, Eigen::Vector2d::Zero()) / length);
    }
  }
  return depth;
}

/// Sinks found by following each face's toppling chain; a chain that comes back to itself
/// makes a rolling sink at its face with the lowest centre of mass.
void followChains(RestingHull& r) {
  const std::size_t faces = r.next.size();
  constexpr int kUnvisited = -1, kOnPath = -2;
  r.sink.assign(faces, kUnvisited);
  for (std::size_t f = 0; f < faces; ++f) {
    if (r.next[f] < 0) {
      r.sink[f] = static_cast<int>(r.sinks.size());
      r.sinks.push_back({static_cast<int>(f), false, 0.0});
    }
  }
  std::vector<int> path;
  for (std::size_t f = 0; f < faces; ++f) {
    path.clear();
    int g = static_cast<int>(f);
    while (r.sink[static_cast<std::size_t>(g)] == kUnvisited) {
      r.sink[static_cast<std::size_t>(g)] = kOnPath;
      path.push_back(g);
      g = r.next[static_cast<std::size_t>(g)];
    }
    int sink = r.sink[static_cast<std::size_t>(g)];
    if (sink == kOnPath) {  // a cycle, from g to the end of the path
      int lowest = g;
      for (auto it = std::find(path.begin(), path.end(), g); it != path.end(); ++it) {
        if (r.height[static_cast<std::size_t>(*it)] < r.height[static_cast<std::size_t>(lowest)]) {
          lowest = *it;
        }
      }
      sink = static_cast<int>(r.sinks.size());
      r.sinks.push_back({lowest, true, 0.0});
    }
    for (int h : path) {
      r.sink[static_cast<std::size_t>(h)] = sink;
    }
  }
}

int findRoot(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

/// One rolling sink for each set of rolling sinks whose faces touch (the polygons of one
/// cylinder's side end in many small cycles); the shares summed.
void mergeRollingSinks(RestingHull& r) {
  std::vector<int> parent(r.sinks.size());
  std::iota(parent.begin(), parent.end(), 0);
  const ConvexHull& hull = r.hull;
  for (std::size_t f = 0; f < hull.faceCount(); ++f) {
    const int s = r.sink[f];
    if (!r.sinks[static_cast<std::size_t>(s)].rolling) {
      continue;
    }
    for (int k = hull.start[f]; k < hull.start[f + 1]; ++k) {
      const int t = r.sink[static_cast<std::size_t>(hull.neighbours[static_cast<std::size_t>(k)])];
      if (r.sinks[static_cast<std::size_t>(t)].rolling) {
        const int a = findRoot(parent, s), b = findRoot(parent, t);
        parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
      }
    }
  }
  std::vector<int> index(r.sinks.size(), -1);
  std::vector<RestingHull::Sink> merged;
  for (std::size_t s = 0; s < r.sinks.size(); ++s) {
    const std::size_t root = static_cast<std::size_t>(findRoot(parent, static_cast<int>(s)));
    if (index[root] < 0) {
      index[root] = static_cast<int>(merged.size());
      merged.push_back({r.sinks[root].face, r.sinks[root].rolling, 0.0});
    }
    index[s] = index[root];
    RestingHull::Sink& m = merged[static_cast<std::size_t>(index[s])];
    m.share += r.sinks[s].share;
    const int face = r.sinks[s].face;
    if (r.height[static_cast<std::size_t>(face)] < r.height[static_cast<std::size_t>(m.face)]) {
      m.face = face;
    }
  }
  for (int& s : r.sink) {
    s = index[static_cast<std::size_t>(s)];
  }
  r.sinks = std::move(merged);
}

}  // namespace

double triangleSolidAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                          const Eigen::Vector3d& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double numerator = a.dot(b.cross(c));
  const double denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
  return 2.0 * std::atan2(numerator, denominator);
}

HullPoints hullPoints(const std::vector<Shape>& shapes) {
  std::size_t total = 0;
  for (const Shape& shape : shapes) {
    total += pointCount(shape);
  }
  if (total > kMaxHullPoints) {
    throw std::invalid_argument("resting poses: the geometry has " + std::to_string(total) +
                                " points (mesh vertices, and " + std::to_string(kCircleSegments) +
                                "-gons for round shapes), at most " +
                                std::to_string(kMaxHullPoints) + " are taken");
  }
  HullPoints out;
  out.points.reserve(total);
  out.curve.reserve(total);
  for (const Shape& shape : shapes) {
    const Eigen::Isometry3d& pose = shape.pose;
    switch (shape.type) {
      case ShapeType::Box:
        for (int i = 0; i < 8; ++i) {
          const Eigen::Vector3d half = 0.5 * shape.size;
          out.points.push_back(pose * Eigen::Vector3d((i & 1) ? half.x() : -half.x(),
                                                      (i & 2) ? half.y() : -half.y(),
                                                      (i & 4) ? half.z() : -half.z()));
          out.curve.push_back(-1);
        }
        break;
      case ShapeType::Cylinder:
        for (double z : {-0.5 * shape.length, 0.5 * shape.length}) {
          addRing(out, pose, shape.radius, z, addCurve(out, pose, z, shape.radius, false));
        }
        break;
      case ShapeType::Sphere: {
        const int curve = addCurve(out, pose, 0.0, shape.radius, true);
        for (int j = 1; j <= kSphereRings; ++j) {
          const double polar = M_PI * j / (kSphereRings + 1);
          addRing(out, pose, shape.radius * std::sin(polar), shape.radius * std::cos(polar), curve);
        }
        for (double z : {-shape.radius, shape.radius}) {
          out.points.push_back(pose * Eigen::Vector3d(0.0, 0.0, z));
          out.curve.push_back(curve);
        }
        break;
      }
      case ShapeType::Capsule:
        addHemisphere(out, pose, shape.radius, 0.5 * shape.length, true);
        addHemisphere(out, pose, shape.radius, -0.5 * shape.length, false);
        break;
      case ShapeType::Mesh:
        for (const Eigen::Vector3d& v : shape.mesh->vertices) {
          out.points.push_back(pose * v);
          out.curve.push_back(-1);
        }
        break;
    }
  }
  return out;
}

RestingHull restingHull(const std::vector<Shape>& shapes, const RestingOptions& options) {
  RestingHull r;
  r.input = hullPoints(shapes);
  std::optional<ConvexHull> convexMesh;
  if (shapes.size() == 1 && shapes[0].type == ShapeType::Mesh) {
    convexMesh = convexMeshHull(r.input.points, shapes[0].mesh->triangles);
  }
  r.hull = convexMesh ? std::move(*convexMesh) : convexHull(r.input.points);
  const ConvexHull& hull = r.hull;
  const std::vector<Eigen::Vector3d>& points = r.input.points;
  if (shapes.size() == 1 && shapes[0].type == ShapeType::Mesh) {
    double volume = 0.0;  // the physics' mass model of a mesh: its hull (centreOfMass())
    hullVolume(hull, points, volume, r.centreOfMass);
  } else {
    r.centreOfMass = centreOfMass(shapes);
  }
  const Eigen::Vector3d& com = r.centreOfMass;
  const std::size_t faces = hull.faceCount();
  r.share.resize(faces);
  r.height.resize(faces);
  r.depth.resize(faces);
  r.next.resize(faces);
  std::vector<Eigen::Vector2d> contact, chain;
  double total = 0.0;
  for (std::size_t f = 0; f < faces; ++f) {
    const int* corner = hull.vertices.data() + hull.start[f];
    const int count = hull.cornerCount(f);
    const Eigen::Vector3d& n = hull.normals[f];
    if (!(n.squaredNorm() > 0.5)) {  // a face of no area (not seen): no share, not stable
      r.share[f] = 0.0;
      r.height[f] = std::numeric_limits<double>::infinity();
      r.depth[f] = -std::numeric_limits<double>::infinity();
      r.next[f] = hull.neighbours[static_cast<std::size_t>(hull.start[f])];
      continue;
    }
    auto at = [&](int k) -> const Eigen::Vector3d& {
      return points[static_cast<std::size_t>(corner[k % count])];
    };
    double solidAngle = 0.0, height = 0.0;
    bool exact = true;
    for (int k = 0; k < count; ++k) {
      if (k >= 1 && k + 1 < count) {
        solidAngle += triangleSolidAngle(at(0) - com, at(k) - com, at(k + 1) - com);
      }
      height += n.dot(at(k) - com);
      exact = exact && r.input.curve[static_cast<std::size_t>(corner[k])] < 0;
    }
    r.share[f] = solidAngle;
    total += solidAngle;
    r.height[f] = height / count;
    // The edge the centre of mass lies farthest beyond, seen along the normal.
    double farthest = -std::numeric_limits<double>::infinity();
    int edge = 0;
    for (int k = 0; k < count; ++k) {
      const Eigen::Vector3d outward = (at(k + 1) - at(k)).cross(n);
      const double length = outward.norm();
      const double beyond = length > 0.0 ? outward.dot(com - at(k)) / length : 0.0;
      if (beyond > farthest) {
        farthest = beyond;
        edge = k;
      }
    }
    if (exact) {
      r.depth[f] = -farthest;
    } else {  // the true contact of the round shapes whose polygons this face touches
      const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
      contact.clear();
      for (int k = 0; k < count; ++k) {
        const int c = r.input.curve[static_cast<std::size_t>(corner[k])];
        const Eigen::Vector3d p =
            c < 0 ? at(k) : contactPoint(r.input.curves[static_cast<std::size_t>(c)], at(k), n);
        contact.emplace_back(e1.dot(p - com), e2.dot(p - com));
      }
      r.depth[f] = depthInHull(contact, chain);
    }
    const bool stable = r.depth[f] >= options.margin && r.depth[f] > 0.0;
    r.next[f] = stable ? -1 : hull.neighbours[static_cast<std::size_t>(hull.start[f] + edge)];
  }
  if (!(total > 0.0)) {
    throw std::invalid_argument("resting poses: the centre of mass is not inside the hull");
  }
  for (double& s : r.share) {
    s /= total;
  }
  followChains(r);
  for (std::size_t f = 0; f < faces; ++f) {
    r.sinks[static_cast<std::size_t>(r.sink[f])].share += r.share[f];
  }
  mergeRollingSinks(r);
  return r;
}

}  // namespace placement_samplers::detail
