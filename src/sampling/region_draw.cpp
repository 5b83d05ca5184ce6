#include <algorithm>
#include <cmath>

#include "placement_samplers/sampling/region.hpp"
#include "sampling/polygon.hpp"
#include "sampling/sin_cos.hpp"

namespace placement_samplers {
namespace {

/// Cells per side of the grid that looks for room in an inset non-convex polygon.
constexpr int kRoomGrid = 128;

/// True when some point of the polygon is at least @p margin from its boundary: cell centres
/// of a grid over its bounding box, and each triangle's centroid. Room thinner than a cell
/// can be missed: such a region would reject nearly every draw anyway.
bool hasRoom(const std::vector<Eigen::Vector2d>& ccw, const std::vector<Eigen::Vector2d>& triangles,
             double margin) {
  const auto fits = [&](const Eigen::Vector2d& p) {
    return detail::polygonContains(ccw, p) && detail::boundaryDistance(ccw, p) >= margin;
  };
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
    if (fits((triangles[t] + triangles[t + 1] + triangles[t + 2]) / 3.0)) {
      return true;
    }
  }
  Eigen::Vector2d lo = ccw[0];
  Eigen::Vector2d hi = ccw[0];
  for (const Eigen::Vector2d& v : ccw) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Eigen::Vector2d step = (hi - lo) / kRoomGrid;
  for (int i = 0; i < kRoomGrid; ++i) {
    for (int j = 0; j < kRoomGrid; ++j) {
      if (fits(lo + Eigen::Vector2d((i + 0.5) * step.x(), (j + 0.5) * step.y()))) {
        return true;
      }
    }
  }
  return false;
}

double trianglesArea(const std::vector<Eigen::Vector2d>& t, std::vector<double>& cumulative) {
  double sum = 0.0;
  for (std::size_t k = 0; k + 2 < t.size(); k += 3) {
    sum += 0.5 * detail::cross2(t[k + 1] - t[k], t[k + 2] - t[k]);
    cumulative.push_back(sum);
  }
  return sum;
}

}  // namespace

std::optional<RegionDraw> RegionDraw::make(const RegionShape& shape, double margin) {
  RegionDraw d;
  d.kind_ = shape.kind;
  d.margin_ = margin;
  d.centre_ = shape.centre;
  switch (shape.kind) {
    case RegionShape::Kind::Rectangle:
      d.a_ = Eigen::Vector2d(shape.xRange[0] + margin, shape.xRange[1] - margin);
      d.b_ = Eigen::Vector2d(shape.yRange[0] + margin, shape.yRange[1] - margin);
      if (d.a_[0] > d.a_[1] || d.b_[0] > d.b_[1]) {
        return std::nullopt;
      }
      d.area_ = (d.a_[1] - d.a_[0]) * (d.b_[1] - d.b_[0]);
      return d;
    case RegionShape::Kind::RotatedRectangle: {
      d.a_ = 0.5 * shape.size - Eigen::Vector2d::Constant(margin);
      if (d.a_.x() < 0.0 || d.a_.y() < 0.0) {
        return std::nullopt;
      }
      double sine = 0.0;
      double cosine = 0.0;
      sinCos(shape.yaw, sine, cosine);
      d.b_ = Eigen::Vector2d(cosine, sine);
      d.area_ = 4.0 * d.a_.x() * d.a_.y();
      return d;
    }
    case RegionShape::Kind::Disk:
    case RegionShape::Kind::Annulus: {
      const double inner = shape.kind == RegionShape::Kind::Disk ? 0.0 : shape.innerRadius + margin;
      const double outer = shape.radius - margin;
      if (outer < 0.0 || inner > outer) {
        return std::nullopt;
      }
      d.inner2_ = inner * inner;
      d.outer2_ = outer * outer;
      d.area_ = M_PI * (d.outer2_ - d.inner2_);
      return d;
    }
    case RegionShape::Kind::Polygon:
      break;
  }
  const std::vector<Eigen::Vector2d> ccw = detail::counterClockwise(shape.vertices);
  if (isConvexPolygon(ccw)) {
    const std::vector<Eigen::Vector2d> inset =
        margin > 0.0 ? detail::insetConvex(ccw, margin) : ccw;
    if (inset.empty()) {
      return std::nullopt;
    }
    d.triangles_ = detail::triangulate(inset);
  } else {
    d.triangles_ = detail::triangulate(ccw);
    if (margin > 0.0) {
      if (!hasRoom(ccw, d.triangles_, margin)) {
        return std::nullopt;
      }
      d.rejects_ = true;
      d.outline_ = ccw;
    }
  }
  d.area_ = trianglesArea(d.triangles_, d.cumulative_);
  if (!(d.area_ > 0.0)) {
    return std::nullopt;
  }
  return d;
}

Eigen::Vector2d RegionDraw::draw(Engine& engine) const {
  switch (kind_) {
    case RegionShape::Kind::Rectangle: {
      // robosuite's order: x, then y.
      const double x = uniform(engine, a_[0], a_[1]);
      return Eigen::Vector2d(x, uniform(engine, b_[0], b_[1]));
    }
    case RegionShape::Kind::RotatedRectangle: {
      const double u = uniform(engine, -a_.x(), a_.x());
      const double v = uniform(engine, -a_.y(), a_.y());
      return centre_ + Eigen::Vector2d(b_.x() * u - b_.y() * v, b_.y() * u + b_.x() * v);
    }
    case RegionShape::Kind::Disk:
    case RegionShape::Kind::Annulus: {
      // The squared radius is uniform over [inner^2, outer^2]: uniform over the area.
      const double rho = std::sqrt(inner2_ + (outer2_ - inner2_) * uniform01(engine));
      double sine = 0.0;
      double cosine = 0.0;
      sinCos(uniform(engine, 0.0, 2.0 * M_PI), sine, cosine);
      return centre_ + rho * Eigen::Vector2d(cosine, sine);
    }
    case RegionShape::Kind::Polygon:
      break;
  }
  // A triangle with probability proportional to its area, then a uniform point in it (the
  // parallelogram's far half folded back).
  const double t = uniform01(engine) * area_;
  const std::size_t k = std::min<std::size_t>(
      static_cast<std::size_t>(std::upper_bound(cumulative_.begin(), cumulative_.end(), t) -
                               cumulative_.begin()),
      cumulative_.size() - 1);
  double u = uniform01(engine);
  double v = uniform01(engine);
  if (u + v > 1.0) {
    u = 1.0 - u;
    v = 1.0 - v;
  }
  const Eigen::Vector2d& a = triangles_[3 * k];
  return a + u * (triangles_[3 * k + 1] - a) + v * (triangles_[3 * k + 2] - a);
}

bool RegionDraw::accepts(const Eigen::Vector2d& p) const {
  return !rejects_ || detail::boundaryDistance(outline_, p) >= margin_;
}

}  // namespace placement_samplers
