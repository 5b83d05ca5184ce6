#include "sampling/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <list>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/sampling/region.hpp"

namespace placement_samplers::detail {
namespace {

double orient(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return cross2(b - a, c - a);
}

/// @p p, collinear with [a, b], lies within its bounding box.
bool onSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

int sign(double v) { return (v > 0.0) - (v < 0.0); }

/// @p p in the closed triangle (a, b, c), counter-clockwise.
bool inTriangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                const Eigen::Vector2d& c) {
  return orient(a, b, p) >= 0.0 && orient(b, c, p) >= 0.0 && orient(c, a, p) >= 0.0;
}

}  // namespace

double signedArea2(const std::vector<Eigen::Vector2d>& v) {
  double sum = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    sum += cross2(v[i], v[(i + 1) % v.size()]);
  }
  return sum;
}

bool segmentsIntersect(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                       const Eigen::Vector2d& d) {
  const int o1 = sign(orient(a, b, c));
  const int o2 = sign(orient(a, b, d));
  const int o3 = sign(orient(c, d, a));
  const int o4 = sign(orient(c, d, b));
  if (o1 * o2 < 0 && o3 * o4 < 0) {
    return true;
  }
  return (o1 == 0 && onSegment(a, b, c)) || (o2 == 0 && onSegment(a, b, d)) ||
         (o3 == 0 && onSegment(c, d, a)) || (o4 == 0 && onSegment(c, d, b));
}

double segmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

double boundaryDistance(const std::vector<Eigen::Vector2d>& v, const Eigen::Vector2d& p) {
  double best = INFINITY;
  for (std::size_t i = 0; i < v.size(); ++i) {
    best = std::min(best, segmentDistance(p, v[i], v[(i + 1) % v.size()]));
  }
  return best;
}

bool polygonContains(const std::vector<Eigen::Vector2d>& v, const Eigen::Vector2d& p) {
  bool inside = false;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    const Eigen::Vector2d& a = v[i];
    const Eigen::Vector2d& b = v[j];
    if (orient(a, b, p) == 0.0 && onSegment(a, b, p)) {
      return true;  // on the boundary: the shape is closed
    }
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

std::vector<Eigen::Vector2d> counterClockwise(std::vector<Eigen::Vector2d> v) {
  if (signedArea2(v) < 0.0) {
    std::reverse(v.begin(), v.end());
  }
  return v;
}

std::vector<Eigen::Vector2d> triangulate(const std::vector<Eigen::Vector2d>& ccw) {
  std::vector<Eigen::Vector2d> out;
  if (isConvexPolygon(ccw)) {
    for (std::size_t i = 1; i + 1 < ccw.size(); ++i) {
      out.insert(out.end(), {ccw[0], ccw[i], ccw[i + 1]});
    }
    return out;
  }
  // Ear clipping, O(n^3) at worst: polygons are small and this runs once per build.
  std::list<std::size_t> left;
  for (std::size_t i = 0; i < ccw.size(); ++i) {
    left.push_back(i);
  }
  while (left.size() > 3) {
    bool clipped = false;
    for (auto it = left.begin(); it != left.end(); ++it) {
      const auto prev = it == left.begin() ? std::prev(left.end()) : std::prev(it);
      const auto next = std::next(it) == left.end() ? left.begin() : std::next(it);
      const Eigen::Vector2d& a = ccw[*prev];
      const Eigen::Vector2d& b = ccw[*it];
      const Eigen::Vector2d& c = ccw[*next];
      const double turn = orient(a, b, c);
      if (turn < 0.0) {
        continue;  // a reflex vertex is no ear
      }
      bool ear = true;
      if (turn > 0.0) {
        for (const std::size_t k : left) {
          if (k != *prev && k != *it && k != *next && inTriangle(ccw[k], a, b, c)) {
            ear = false;
            break;
          }
        }
      }
      if (ear) {
        if (turn > 0.0) {
          out.insert(out.end(), {a, b, c});
        }
        left.erase(it);  // a collinear vertex goes without a triangle
        clipped = true;
        break;
      }
    }
    if (!clipped) {
      throw ConfigError("the polygon could not be cut into triangles (nearly degenerate?)");
    }
  }
  auto it = left.begin();
  const Eigen::Vector2d& a = ccw[*it++];
  const Eigen::Vector2d& b = ccw[*it++];
  const Eigen::Vector2d& c = ccw[*it];
  if (orient(a, b, c) > 0.0) {
    out.insert(out.end(), {a, b, c});
  }
  return out;
}

std::vector<Eigen::Vector2d> insetConvex(const std::vector<Eigen::Vector2d>& ccw, double margin) {
  std::vector<Eigen::Vector2d> poly = ccw;
  for (std::size_t e = 0; e < ccw.size() && poly.size() >= 3; ++e) {
    const Eigen::Vector2d& a = ccw[e];
    const Eigen::Vector2d edge = ccw[(e + 1) % ccw.size()] - a;
    const double length = edge.norm();
    if (length == 0.0) {
      continue;
    }
    const Eigen::Vector2d inward(-edge.y() / length, edge.x() / length);
    // Sutherland-Hodgman against the half-plane inward . (p - a) >= margin.
    std::vector<Eigen::Vector2d> clipped;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector2d& p = poly[i];
      const Eigen::Vector2d& q = poly[(i + 1) % poly.size()];
      const double dp = inward.dot(p - a) - margin;
      const double dq = inward.dot(q - a) - margin;
      if (dp >= 0.0) {
        clipped.push_back(p);
      }
      if ((dp >= 0.0) != (dq >= 0.0)) {
        clipped.push_back(p + (q - p) * (dp / (dp - dq)));
      }
    }
    poly.swap(clipped);
  }
  if (poly.size() < 3 || signedArea2(poly) <= 0.0) {
    return {};
  }
  return poly;
}

std::vector<Eigen::Vector2d> trapezoidTriangles(
    const std::vector<Eigen::Vector2d>& outer,
    const std::vector<std::vector<Eigen::Vector2d>>& holes) {
  struct Edge {
    Eigen::Vector2d lo;  // the end with the smaller y
    Eigen::Vector2d hi;
    double xAt(double y) const {
      const double t = (y - lo.y()) / (hi.y() - lo.y());
      return lo.x() + std::clamp(t, 0.0, 1.0) * (hi.x() - lo.x());
    }
  };
  std::vector<Edge> edges;
  std::vector<double> ys;
  const auto addRing = [&](const std::vector<Eigen::Vector2d>& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Eigen::Vector2d& a = ring[i];
      const Eigen::Vector2d& b = ring[(i + 1) % ring.size()];
      ys.push_back(a.y());
      if (a.y() != b.y()) {  // horizontal edges bound no slab
        edges.push_back(a.y() < b.y() ? Edge{a, b} : Edge{b, a});
      }
    }
  };
  addRing(outer);
  for (const std::vector<Eigen::Vector2d>& hole : holes) {
    addRing(hole);
  }
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  std::sort(edges.begin(), edges.end(),
            [](const Edge& a, const Edge& b) { return a.lo.y() < b.lo.y(); });
  std::vector<Eigen::Vector2d> out;
  std::vector<const Edge*> active;
  std::vector<std::pair<double, const Edge*>> crossing;
  std::size_t next = 0;
  for (std::size_t k = 0; k + 1 < ys.size(); ++k) {
    const double y0 = ys[k];
    const double y1 = ys[k + 1];
    const double mid = 0.5 * (y0 + y1);
    while (next < edges.size() && edges[next].lo.y() < mid) {
      active.push_back(&edges[next++]);
    }
    active.erase(std::remove_if(active.begin(), active.end(),
                                [&](const Edge* e) { return e->hi.y() <= mid; }),
                 active.end());
    crossing.clear();
    for (const Edge* e : active) {
      crossing.emplace_back(e->xAt(mid), e);
    }
    std::sort(crossing.begin(), crossing.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    // Even-odd: inside between the first and second crossing, the third and fourth, ...
    for (std::size_t i = 0; i + 1 < crossing.size(); i += 2) {
      const Edge& l = *crossing[i].second;
      const Edge& r = *crossing[i + 1].second;
      const Eigen::Vector2d a(l.xAt(y0), y0);
      const Eigen::Vector2d b(r.xAt(y0), y0);
      const Eigen::Vector2d c(r.xAt(y1), y1);
      const Eigen::Vector2d d(l.xAt(y1), y1);
      if (b.x() > a.x()) {
        out.insert(out.end(), {a, b, c});
      }
      if (c.x() > d.x()) {
        out.insert(out.end(), {a, c, d});
      }
    }
  }
  return out;
}

}  // namespace placement_samplers::detail
