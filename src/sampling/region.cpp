#include "placement_samplers/sampling/region.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "placement_samplers/limits.hpp"
#include "sampling/polygon.hpp"
#include "sampling/sin_cos.hpp"

namespace placement_samplers {
namespace {

using detail::cross2;

std::string text(const Eigen::Vector2d& v) {
  std::ostringstream out;
  out << "[" << v.x() << ", " << v.y() << "]";
  return out.str();
}

bool bounded(double v) { return std::isfinite(v) && std::abs(v) <= limits::kCoordinate; }
bool bounded(const Eigen::Vector2d& v) { return bounded(v.x()) && bounded(v.y()); }

std::string boundText() {
  std::ostringstream out;
  out << "within [-" << limits::kCoordinate << ", " << limits::kCoordinate << "] m";
  return out.str();
}

std::optional<ShapeProblem> rangeProblem(const char* key, const Eigen::Vector2d& r) {
  if (!bounded(r)) {
    return ShapeProblem{key, "expected [min, max] " + boundText() + ", got " + text(r)};
  }
  if (r[0] > r[1]) {
    return ShapeProblem{key, "expected [min, max] with min <= max, got " + text(r)};
  }
  return std::nullopt;
}

std::optional<ShapeProblem> lengthProblem(const char* key, double v, bool positive) {
  if (!bounded(v) || v < 0.0 || (positive && v == 0.0)) {
    std::ostringstream out;
    out << "expected a length " << (positive ? "> 0" : ">= 0") << " [m] " << boundText() << ", got "
        << v;
    return ShapeProblem{key, out.str()};
  }
  return std::nullopt;
}

std::optional<ShapeProblem> polygonProblem(const std::vector<Eigen::Vector2d>& v) {
  const std::size_t n = v.size();
  if (n < 3 || n > kMaxPolygonVertices) {
    std::ostringstream out;
    out << "expected 3 to " << kMaxPolygonVertices << " vertices [x, y], got " << n;
    return ShapeProblem{"vertices", out.str()};
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!bounded(v[i])) {
      return ShapeProblem{"vertices", "vertex " + std::to_string(i) + " must lie " + boundText() +
                                          ", got " + text(v[i])};
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (v[i] == v[(i + 1) % n]) {
      return ShapeProblem{"vertices", "vertices " + std::to_string(i) + " and " +
                                          std::to_string((i + 1) % n) + " are the same point " +
                                          text(v[i])};
    }
  }
  const auto edge = [&](std::size_t i) {
    return "the edge from vertex " + std::to_string(i) + " " + text(v[i]) + " to vertex " +
           std::to_string((i + 1) % n) + " " + text(v[(i + 1) % n]);
  };
  for (std::size_t i = 0; i < n; ++i) {
    // Neighbouring edges share a vertex; they may not fold back onto each other.
    const Eigen::Vector2d& a = v[i];
    const Eigen::Vector2d& b = v[(i + 1) % n];
    const Eigen::Vector2d& c = v[(i + 2) % n];
    if (cross2(b - a, c - b) == 0.0 && (b - a).dot(c - b) < 0.0) {
      return ShapeProblem{"vertices", "the polygon intersects itself: " + edge(i) + " overlaps " +
                                          edge((i + 1) % n)};
    }
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) {
        continue;  // neighbours through vertex 0
      }
      if (detail::segmentsIntersect(a, b, v[j], v[(j + 1) % n])) {
        return ShapeProblem{"vertices",
                            "the polygon intersects itself: " + edge(i) + " crosses " + edge(j)};
      }
    }
  }
  if (detail::signedArea2(v) == 0.0) {
    return ShapeProblem{"vertices", "the polygon has no area (its vertices are collinear)"};
  }
  return std::nullopt;
}

/// @p p in the rotated rectangle's own frame.
Eigen::Vector2d local(const RegionShape& s, const Eigen::Vector2d& p) {
  double sine = 0.0;
  double cosine = 0.0;
  sinCos(s.yaw, sine, cosine);
  const Eigen::Vector2d d = p - s.centre;
  return Eigen::Vector2d(cosine * d.x() + sine * d.y(), -sine * d.x() + cosine * d.y());
}

double boxDistance(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Eigen::Vector2d& p) {
  const double dx = std::max({lo.x() - p.x(), 0.0, p.x() - hi.x()});
  const double dy = std::max({lo.y() - p.y(), 0.0, p.y() - hi.y()});
  return std::hypot(dx, dy);
}

void appendCircle(std::vector<Eigen::Vector2d>& out, const Eigen::Vector2d& c, double inner,
                  double outer, int segments) {
  for (int k = 0; k < segments; ++k) {
    Eigen::Vector2d u[2];
    for (int e = 0; e < 2; ++e) {
      double sine = 0.0;
      double cosine = 0.0;
      sinCos(2.0 * M_PI * (k + e) / segments, sine, cosine);
      u[e] = Eigen::Vector2d(cosine, sine);
    }
    if (inner <= 0.0) {
      out.insert(out.end(), {c, c + outer * u[0], c + outer * u[1]});
    } else {
      out.insert(out.end(), {c + inner * u[0], c + outer * u[0], c + outer * u[1]});
      out.insert(out.end(), {c + inner * u[0], c + outer * u[1], c + inner * u[1]});
    }
  }
}

}  // namespace

RegionShape RegionShape::rectangle(const Eigen::Vector2d& x, const Eigen::Vector2d& y) {
  RegionShape s;
  s.kind = Kind::Rectangle;
  s.xRange = x;
  s.yRange = y;
  return s;
}

RegionShape RegionShape::rotatedRectangle(const Eigen::Vector2d& centre,
                                          const Eigen::Vector2d& size, double yaw) {
  RegionShape s;
  s.kind = Kind::RotatedRectangle;
  s.centre = centre;
  s.size = size;
  s.yaw = yaw;
  return s;
}

RegionShape RegionShape::disk(const Eigen::Vector2d& centre, double radius) {
  RegionShape s;
  s.kind = Kind::Disk;
  s.centre = centre;
  s.radius = radius;
  return s;
}

RegionShape RegionShape::annulus(const Eigen::Vector2d& centre, double inner, double outer) {
  RegionShape s;
  s.kind = Kind::Annulus;
  s.centre = centre;
  s.innerRadius = inner;
  s.radius = outer;
  return s;
}

RegionShape RegionShape::polygon(std::vector<Eigen::Vector2d> vertices) {
  RegionShape s;
  s.kind = Kind::Polygon;
  s.vertices = std::move(vertices);
  return s;
}

const char* shapeKindName(RegionShape::Kind kind) {
  switch (kind) {
    case RegionShape::Kind::Rectangle:
      return "rectangle";
    case RegionShape::Kind::RotatedRectangle:
      return "rotated_rectangle";
    case RegionShape::Kind::Disk:
      return "disk";
    case RegionShape::Kind::Annulus:
      return "annulus";
    case RegionShape::Kind::Polygon:
      return "polygon";
  }
  return "?";
}

std::optional<ShapeProblem> findShapeProblem(const RegionShape& s) {
  using Kind = RegionShape::Kind;
  if (s.kind == Kind::Rectangle) {
    if (auto p = rangeProblem("x_range", s.xRange)) {
      return p;
    }
    return rangeProblem("y_range", s.yRange);
  }
  if (s.kind == Kind::Polygon) {
    return polygonProblem(s.vertices);
  }
  if (!bounded(s.centre)) {
    return ShapeProblem{"center", "expected [x, y] " + boundText() + ", got " + text(s.centre)};
  }
  if (s.kind == Kind::RotatedRectangle) {
    if (auto p = lengthProblem("size", s.size.x(), false)) {
      p->message = "expected [x, y] lengths >= 0 [m] " + boundText() + ", got " + text(s.size);
      return p;
    }
    if (auto p = lengthProblem("size", s.size.y(), false)) {
      p->message = "expected [x, y] lengths >= 0 [m] " + boundText() + ", got " + text(s.size);
      return p;
    }
    if (!std::isfinite(s.yaw)) {
      return ShapeProblem{"yaw", "expected a finite angle [rad]"};
    }
    return std::nullopt;
  }
  if (s.kind == Kind::Disk) {
    return lengthProblem("radius", s.radius, true);
  }
  if (auto p = lengthProblem("inner_radius", s.innerRadius, false)) {
    return p;
  }
  if (auto p = lengthProblem("outer_radius", s.radius, true)) {
    return p;
  }
  if (s.innerRadius >= s.radius) {
    std::ostringstream out;
    out << "the inner radius " << s.innerRadius << " m must be less than outer_radius " << s.radius
        << " m";
    return ShapeProblem{"inner_radius", out.str()};
  }
  return std::nullopt;
}

bool shapeContains(const RegionShape& s, const Eigen::Vector2d& p) {
  switch (s.kind) {
    case RegionShape::Kind::Rectangle:
      return s.xRange[0] <= p.x() && p.x() <= s.xRange[1] && s.yRange[0] <= p.y() &&
             p.y() <= s.yRange[1];
    case RegionShape::Kind::RotatedRectangle: {
      const Eigen::Vector2d q = local(s, p);
      return std::abs(q.x()) <= 0.5 * s.size.x() && std::abs(q.y()) <= 0.5 * s.size.y();
    }
    case RegionShape::Kind::Disk:
      return (p - s.centre).squaredNorm() <= s.radius * s.radius;
    case RegionShape::Kind::Annulus: {
      const double d2 = (p - s.centre).squaredNorm();
      return s.innerRadius * s.innerRadius <= d2 && d2 <= s.radius * s.radius;
    }
    case RegionShape::Kind::Polygon:
      return detail::polygonContains(s.vertices, p);
  }
  return false;
}

double distanceToShape(const RegionShape& s, const Eigen::Vector2d& p) {
  switch (s.kind) {
    case RegionShape::Kind::Rectangle:
      return boxDistance(Eigen::Vector2d(s.xRange[0], s.yRange[0]),
                         Eigen::Vector2d(s.xRange[1], s.yRange[1]), p);
    case RegionShape::Kind::RotatedRectangle:
      return boxDistance(-0.5 * s.size, 0.5 * s.size, local(s, p));
    case RegionShape::Kind::Disk:
      return std::max((p - s.centre).norm() - s.radius, 0.0);
    case RegionShape::Kind::Annulus: {
      const double d = (p - s.centre).norm();
      return std::max({s.innerRadius - d, d - s.radius, 0.0});
    }
    case RegionShape::Kind::Polygon:
      return detail::polygonContains(s.vertices, p) ? 0.0 : detail::boundaryDistance(s.vertices, p);
  }
  return 0.0;
}

double shapeDepth(const RegionShape& s, const Eigen::Vector2d& p) {
  const auto box = [](const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                      const Eigen::Vector2d& q) {
    const double inside =
        std::min({q.x() - lo.x(), hi.x() - q.x(), q.y() - lo.y(), hi.y() - q.y()});
    return inside >= 0.0 ? inside : -boxDistance(lo, hi, q);
  };
  switch (s.kind) {
    case RegionShape::Kind::Rectangle:
      return box(Eigen::Vector2d(s.xRange[0], s.yRange[0]),
                 Eigen::Vector2d(s.xRange[1], s.yRange[1]), p);
    case RegionShape::Kind::RotatedRectangle:
      return box(-0.5 * s.size, 0.5 * s.size, local(s, p));
    case RegionShape::Kind::Disk:
      return s.radius - (p - s.centre).norm();
    case RegionShape::Kind::Annulus: {
      const double d = (p - s.centre).norm();
      return std::min(d - s.innerRadius, s.radius - d);
    }
    case RegionShape::Kind::Polygon: {
      const double d = detail::boundaryDistance(s.vertices, p);
      return detail::polygonContains(s.vertices, p) ? d : -d;
    }
  }
  return 0.0;
}

void shapeBounds(const RegionShape& s, Eigen::Vector2d& lo, Eigen::Vector2d& hi) {
  if (s.kind == RegionShape::Kind::Disk || s.kind == RegionShape::Kind::Annulus) {
    lo = s.centre - Eigen::Vector2d::Constant(s.radius);
    hi = s.centre + Eigen::Vector2d::Constant(s.radius);
    return;
  }
  const std::vector<Eigen::Vector2d> corners = shapeTriangles(s);
  lo = hi = corners.front();
  for (const Eigen::Vector2d& c : corners) {
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
}

bool isConvexPolygon(const std::vector<Eigen::Vector2d>& v) {
  bool left = false;
  bool right = false;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double turn =
        cross2(v[(i + 1) % v.size()] - v[i], v[(i + 2) % v.size()] - v[(i + 1) % v.size()]);
    left = left || turn > 0.0;
    right = right || turn < 0.0;
  }
  return !(left && right);
}

std::vector<Eigen::Vector2d> shapeTriangles(const RegionShape& s, int segments) {
  std::vector<Eigen::Vector2d> out;
  std::vector<Eigen::Vector2d> corners;
  switch (s.kind) {
    case RegionShape::Kind::Rectangle:
      corners = {{s.xRange[0], s.yRange[0]},
                 {s.xRange[1], s.yRange[0]},
                 {s.xRange[1], s.yRange[1]},
                 {s.xRange[0], s.yRange[1]}};
      break;
    case RegionShape::Kind::RotatedRectangle: {
      double sine = 0.0;
      double cosine = 0.0;
      sinCos(s.yaw, sine, cosine);
      for (const auto& [x, y] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        const double lx = 0.5 * x * s.size.x();
        const double ly = 0.5 * y * s.size.y();
        corners.push_back(s.centre +
                          Eigen::Vector2d(cosine * lx - sine * ly, sine * lx + cosine * ly));
      }
      break;
    }
    case RegionShape::Kind::Disk:
    case RegionShape::Kind::Annulus:
      appendCircle(out, s.centre, s.kind == RegionShape::Kind::Disk ? 0.0 : s.innerRadius, s.radius,
                   segments);
      return out;
    case RegionShape::Kind::Polygon:
      return detail::triangulate(detail::counterClockwise(s.vertices));
  }
  return {corners[0], corners[1], corners[2], corners[0], corners[2], corners[3]};
}

}  // namespace placement_samplers
