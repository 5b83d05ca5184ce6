#include "geometry/surface_polygons.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#include <cmath>
#include <exception>
#include <limits>
#include <utility>

namespace placement_samplers {
namespace surfaces {
namespace {

namespace bg = boost::geometry;
using BPoint = bg::model::d2::point_xy<double>;
/// Counter-clockwise outer rings, clockwise holes, closed rings: the orientation kept here.
using BPolygon = bg::model::polygon<BPoint, false, true>;
using BMulti = bg::model::multi_polygon<BPolygon>;

double cross(const Point2& u, const Point2& v) { return u.x() * v.y() - u.y() * v.x(); }

/// Whether @p b adds nothing between @p a and @p c: it repeats one of them, lies on their line,
/// or is the tip of a zero-width spike.
bool removable(const Point2& a, const Point2& b, const Point2& c) {
  const Point2 u = b - a;
  const Point2 v = c - b;
  const double lu = u.norm();
  const double lv = v.norm();
  if (lu <= kLinearTolerance || lv <= kLinearTolerance) {
    return true;
  }
  return std::abs(cross(u, v)) <= kLinearTolerance * std::max(lu, lv);
}

void appendRing(const Ring& ring, bg::model::ring<BPoint, false, true>& out) {
  out.clear();
  out.reserve(ring.size() + 1);
  for (const Point2& p : ring) {
    out.push_back(BPoint(p.x(), p.y()));
  }
  if (!ring.empty()) {
    out.push_back(BPoint(ring.front().x(), ring.front().y()));
  }
}

BPolygon toBoost(const Polygon2& polygon) {
  BPolygon out;
  appendRing(polygon.outer, out.outer());
  out.inners().resize(polygon.holes.size());
  for (std::size_t i = 0; i < polygon.holes.size(); ++i) {
    appendRing(polygon.holes[i], out.inners()[i]);
  }
  return out;
}

Ring fromBoost(const bg::model::ring<BPoint, false, true>& ring) {
  Ring out;
  out.reserve(ring.size());
  for (const BPoint& p : ring) {
    out.emplace_back(p.x(), p.y());
  }
  if (out.size() > 1 && out.front() == out.back()) {
    out.pop_back();
  }
  return out;
}

Polygons fromBoost(const BMulti& multi) {
  Polygons out;
  out.reserve(multi.size());
  for (const BPolygon& p : multi) {
    Polygon2 polygon;
    polygon.outer = fromBoost(p.outer());
    for (const auto& hole : p.inners()) {
      polygon.holes.push_back(fromBoost(hole));
    }
    out.push_back(std::move(polygon));
  }
  simplifyPolygons(out);
  return out;
}

/// The union of @p polygons, merged pairwise in rounds (each round halves their number).
/// @throw what Boost.Geometry throws for input it cannot handle
BMulti uniteBoost(const Polygons& polygons) {
  std::vector<BMulti> parts;
  parts.reserve(polygons.size());
  for (const Polygon2& polygon : polygons) {
    BMulti multi;
    multi.push_back(toBoost(polygon));
    bg::correct(multi);
    parts.push_back(std::move(multi));
  }
  while (parts.size() > 1) {
    std::vector<BMulti> next;
    next.reserve(parts.size() / 2 + 1);
    for (std::size_t i = 0; i < parts.size(); i += 2) {
      if (i + 1 == parts.size()) {
        next.push_back(std::move(parts[i]));
        continue;
      }
      BMulti merged;
      bg::union_(parts[i], parts[i + 1], merged);
      next.push_back(std::move(merged));
    }
    parts.swap(next);
  }
  return parts.empty() ? BMulti() : std::move(parts.front());
}

/// 1 when @p p is inside @p ring, -1 outside, 0 on its boundary (within kLinearTolerance).
int pointInRing(const Point2& p, const Ring& ring) {
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Point2& a = ring[j];
    const Point2& b = ring[i];
    const Point2 ab = b - a;
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    if ((a + t * ab - p).norm() <= kLinearTolerance) {
      return 0;
    }
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * ab.x() / ab.y();
      if (p.x() < x) {
        inside = !inside;
      }
    }
  }
  return inside ? 1 : -1;
}

/// Whether @p hole lies inside @p outer, decided by its first vertex not on the outer ring.
bool ringInside(const Ring& hole, const Ring& outer) {
  for (const Point2& p : hole) {
    const int side = pointInRing(p, outer);
    if (side != 0) {
      return side > 0;
    }
  }
  return false;
}

}  // namespace

double signedArea(const Ring& ring) {
  if (ring.size() < 3) {
    return 0.0;
  }
  // Relative to the first vertex: far from the origin the products stay small.
  const Point2& o = ring.front();
  double twice = 0.0;
  for (std::size_t i = 1; i + 1 < ring.size(); ++i) {
    twice += cross(ring[i] - o, ring[i + 1] - o);
  }
  return 0.5 * twice;
}

double polygonArea(const Polygon2& polygon) {
  double area = signedArea(polygon.outer);
  for (const Ring& hole : polygon.holes) {
    area += signedArea(hole);
  }
  return area;
}

Box2 ringBox(const Ring& ring) {
  Box2 box{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
           -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const Point2& p : ring) {
    box.minX = std::min(box.minX, p.x());
    box.minY = std::min(box.minY, p.y());
    box.maxX = std::max(box.maxX, p.x());
    box.maxY = std::max(box.maxY, p.y());
  }
  return box;
}

bool simplifyRing(Ring& ring) {
  Ring kept;
  kept.reserve(ring.size());
  for (const Point2& p : ring) {
    kept.push_back(p);
    while (kept.size() >= 3 && removable(kept[kept.size() - 3], kept[kept.size() - 2], p)) {
      kept.erase(kept.end() - 2);
    }
  }
  // Across the closing vertex: the last and the first may still be removable.
  bool changed = true;
  while (changed && kept.size() >= 3) {
    changed = false;
    const std::size_t n = kept.size();
    if (removable(kept[n - 2], kept[n - 1], kept[0])) {
      kept.pop_back();
      changed = true;
    } else if (removable(kept[n - 1], kept[0], kept[1])) {
      kept.erase(kept.begin());
      changed = true;
    }
  }
  ring.swap(kept);
  return ring.size() >= 3 && std::abs(signedArea(ring)) > kDegenerateArea;
}

void simplifyPolygons(Polygons& polygons) {
  Polygons kept;
  kept.reserve(polygons.size());
  for (Polygon2& polygon : polygons) {
    if (!simplifyRing(polygon.outer)) {
      continue;
    }
    std::vector<Ring> holes;
    for (Ring& hole : polygon.holes) {
      if (simplifyRing(hole)) {
        holes.push_back(std::move(hole));
      }
    }
    polygon.holes.swap(holes);
    kept.push_back(std::move(polygon));
  }
  polygons.swap(kept);
}

Polygons polygonsFromLoops(std::vector<Ring> loops, bool& valid) {
  valid = true;
  std::vector<Ring> outers;
  std::vector<Ring> holes;
  for (Ring& loop : loops) {
    if (simplifyRing(loop)) {
      (signedArea(loop) > 0.0 ? outers : holes).push_back(std::move(loop));
    }
  }
  Polygons polygons(outers.size());
  std::vector<double> areas(outers.size());
  std::vector<Box2> boxes(outers.size());
  for (std::size_t i = 0; i < outers.size(); ++i) {
    areas[i] = signedArea(outers[i]);
    boxes[i] = ringBox(outers[i]);
    polygons[i].outer = std::move(outers[i]);
  }
  for (Ring& hole : holes) {
    std::size_t best = polygons.size();
    if (polygons.size() == 1) {
      best = 0;  // a mesh group's one outline: is_valid below checks that the holes are inside
    } else {
      const Box2 box = ringBox(hole);
      for (std::size_t i = 0; i < polygons.size(); ++i) {
        const Box2& b = boxes[i];
        const bool boxInside =
            b.minX <= box.minX && b.minY <= box.minY && b.maxX >= box.maxX && b.maxY >= box.maxY;
        if (boxInside && (best == polygons.size() || areas[i] < areas[best]) &&
            ringInside(hole, polygons[i].outer)) {
          best = i;
        }
      }
    }
    if (best < polygons.size()) {
      polygons[best].holes.push_back(std::move(hole));
    }
  }
  Polygons kept;
  kept.reserve(polygons.size());
  for (Polygon2& polygon : polygons) {
    // A triangle without holes cannot be invalid once it has area.
    bool ok = polygon.outer.size() == 3 && polygon.holes.empty();
    if (!ok) {
      try {
        ok = bg::is_valid(toBoost(polygon));
      } catch (const std::exception&) {
        ok = false;
      }
    }
    if (ok) {
      kept.push_back(std::move(polygon));
    } else {
      valid = false;
    }
  }
  return kept;
}

Polygons unitePolygons(Polygons polygons) {
  if (polygons.size() <= 1) {
    return polygons;
  }
  try {
    return fromBoost(uniteBoost(polygons));
  } catch (const std::exception&) {
    return polygons;
  }
}

Polygons subtractPolygons(const Polygons& polygons, Polygons cuts) {
  if (cuts.empty() || polygons.empty()) {
    return polygons;
  }
  try {
    const BMulti from = uniteBoost(polygons);
    const BMulti cut = uniteBoost(cuts);
    BMulti out;
    bg::difference(from, cut, out);
    return fromBoost(out);
  } catch (const std::exception&) {
    return {};
  }
}

double overlapArea(const Polygon2& a, const Polygon2& b) {
  try {
    BPolygon pa = toBoost(a);
    BPolygon pb = toBoost(b);
    bg::correct(pa);
    bg::correct(pb);
    BMulti out;
    bg::intersection(pa, pb, out);
    return bg::area(out);
  } catch (const std::exception&) {
    return std::numeric_limits<double>::infinity();
  }
}

}  // namespace surfaces
}  // namespace placement_samplers
