// Uniform draws over support surfaces (README, "Support surfaces").
#include <algorithm>
#include <cmath>
#include <limits>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/sampling/region.hpp"
#include "placement_samplers/sampling/surface_region.hpp"
#include "sampling/polygon.hpp"

namespace placement_samplers {
namespace {

/// Cells per side of the grid that looks for room on a surface drawn whole.
constexpr int kRoomGrid = 128;

/// The signed distance of @p p to a surface's edges: positive on it (in the outline and in no
/// hole), negative off it [m].
double depthIn(const std::vector<Eigen::Vector2d>& outer,
               const std::vector<std::vector<Eigen::Vector2d>>& holes, const Eigen::Vector2d& p) {
  bool inside = detail::polygonContains(outer, p);
  double d = detail::boundaryDistance(outer, p);
  for (const std::vector<Eigen::Vector2d>& hole : holes) {
    if (inside && detail::polygonContains(hole, p)) {
      inside = false;
    }
    d = std::min(d, detail::boundaryDistance(hole, p));
  }
  return inside ? d : -d;
}

/// True when some point of the surface is at least @p inset from its edges: each triangle's
/// centroid and the cell centres of a grid over its bounds. Room thinner than a cell can be
/// missed: such a surface would reject nearly every draw anyway.
bool hasRoom(const SupportSurface& s, const std::vector<Eigen::Vector2d>& triangles, double inset) {
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
    if (depthIn(s.outer, s.holes, (triangles[t] + triangles[t + 1] + triangles[t + 2]) / 3.0) >=
        inset) {
      return true;
    }
  }
  Eigen::Vector2d lo = s.outer[0];
  Eigen::Vector2d hi = s.outer[0];
  for (const Eigen::Vector2d& v : s.outer) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Eigen::Vector2d step = (hi - lo) / kRoomGrid;
  for (int i = 0; i < kRoomGrid; ++i) {
    for (int j = 0; j < kRoomGrid; ++j) {
      const Eigen::Vector2d p = lo + Eigen::Vector2d((i + 0.5) * step.x(), (j + 0.5) * step.y());
      if (depthIn(s.outer, s.holes, p) >= inset) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace

std::optional<SurfaceDraw> SurfaceDraw::make(const std::vector<SupportSurface>& surfaces,
                                             double inset, double height, NoFit* why) {
  SurfaceDraw d;
  d.inset_ = inset;
  NoFit fit;
  fit.tooTall = true;
  for (const SupportSurface& s : surfaces) {
    fit.largestClearance = std::max(fit.largestClearance, s.clearance);
    // An empty piece keeps the surfaces' indices.
    Piece piece;
    piece.z = s.z;
    const std::uint32_t index = static_cast<std::uint32_t>(d.pieces_.size());
    if (height <= s.clearance && s.outer.size() >= 3) {
      fit.tooTall = false;
      std::vector<Eigen::Vector2d> triangles;
      try {
        const std::vector<Eigen::Vector2d> ccw = detail::counterClockwise(s.outer);
        piece.outer = ccw;
        piece.holes = s.holes;
        if (s.holes.empty() && isConvexPolygon(ccw)) {
          const std::vector<Eigen::Vector2d> inner =
              inset > 0.0 ? detail::insetConvex(ccw, inset) : ccw;
          if (!inner.empty()) {
            triangles = detail::triangulate(inner);
          }
        } else {
          // Exact triangles of the surface with its holes; the inset by rejection.
          triangles = detail::trapezoidTriangles(ccw, s.holes);
          if (inset > 0.0) {
            if (!hasRoom(s, triangles, inset)) {
              triangles.clear();
            }
            piece.rejects = true;
          }
        }
      } catch (const ConfigError&) {
        triangles.clear();  // a surface rounding made degenerate: left out
      }
      for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
        const double a =
            0.5 * detail::cross2(triangles[t + 1] - triangles[t], triangles[t + 2] - triangles[t]);
        if (!(a > 0.0)) {
          continue;
        }
        d.area_ += a;
        d.cumulative_.push_back(d.area_);
        d.owner_.push_back(index);
        d.triangles_.insert(d.triangles_.end(), triangles.begin() + static_cast<std::ptrdiff_t>(t),
                            triangles.begin() + static_cast<std::ptrdiff_t>(t + 3));
      }
    }
    d.pieces_.push_back(std::move(piece));
  }
  if (!(d.area_ > 0.0)) {
    if (why != nullptr) {
      *why = fit;
    }
    return std::nullopt;
  }
  return d;
}

Eigen::Vector2d SurfaceDraw::draw(Engine& engine, std::size_t& surface) const {
  // A triangle with probability proportional to its area, then a uniform point in it (the
  // parallelogram's far half folded back): the polygon region's draws.
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
  surface = owner_[k];
  const Eigen::Vector2d& a = triangles_[3 * k];
  return a + u * (triangles_[3 * k + 1] - a) + v * (triangles_[3 * k + 2] - a);
}

bool SurfaceDraw::accepts(const Eigen::Vector2d& p, std::size_t surface) const {
  const Piece& piece = pieces_[surface];
  return !piece.rejects || depthIn(piece.outer, piece.holes, p) >= inset_;
}

bool SurfaceDraw::drawnBounds(std::size_t surface, Eigen::Vector2d& lo, Eigen::Vector2d& hi) const {
  lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  hi = -lo;
  for (std::size_t k = 0; k < owner_.size(); ++k) {
    if (owner_[k] == surface) {
      for (std::size_t c = 3 * k; c < 3 * k + 3; ++c) {
        lo = lo.cwiseMin(triangles_[c]);
        hi = hi.cwiseMax(triangles_[c]);
      }
    }
  }
  return (hi.array() >= lo.array()).all();
}

double SurfaceDraw::insetDepth(const Eigen::Vector2d& p, std::size_t surface) const {
  // A convex surface's inset is exactly where the depth reaches the inset; any other keeps
  // the draws that accepts() finds that deep.
  const Piece& piece = pieces_[surface];
  if (piece.outer.empty()) {
    return -std::numeric_limits<double>::infinity();
  }
  return depthIn(piece.outer, piece.holes, p) - inset_;
}

double surfaceShortfall(const SupportSurface& surface, double inset, const Eigen::Vector2d& p) {
  return std::max(0.0, inset - depthIn(surface.outer, surface.holes, p));
}

}  // namespace placement_samplers
