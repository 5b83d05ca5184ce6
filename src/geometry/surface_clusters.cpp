// Coplanar facets grouped: level ones by height, tilted ones where they touch.

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "geometry/box_grid.hpp"
#include "geometry/surface_parts.hpp"

namespace placement_samplers {
namespace surfaces {
namespace {

Box2 merged(const Box2& a, const Box2& b) {
  return Box2{std::min(a.minX, b.minX), std::min(a.minY, b.minY), std::max(a.maxX, b.maxX),
              std::max(a.maxY, b.maxY)};
}

/// Whether two planes are within kHeightTolerance of each other over @p box.
bool coplanar(const Plane& p, const Plane& q, const Box2& box) {
  for (double x : {box.minX, box.maxX}) {
    for (double y : {box.minY, box.maxY}) {
      if (!(std::abs(p.at(x, y) - q.at(x, y)) <= kHeightTolerance)) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace

std::vector<std::vector<int>> touchingGroups(const std::vector<Box2>& boxes,
                                             const std::function<bool(int, int)>& joinable) {
  // Candidates from a grid of the boxes: linear for many small ones (a rough mesh).
  BoxGrid grid(boxes);
  std::vector<int> parent(boxes.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int k) {
    while (parent[k] != k) {
      k = parent[k] = parent[parent[k]];
    }
    return k;
  };
  const double t = kLinearTolerance;
  std::vector<int> near;
  for (int k = 0; k < static_cast<int>(boxes.size()); ++k) {
    const Box2& b = boxes[k];
    grid.query(Box2{b.minX - t, b.minY - t, b.maxX + t, b.maxY + t}, near);
    for (int a : near) {
      const Box2& o = boxes[a];
      if (a < k && o.minX <= b.maxX + t && b.minX <= o.maxX + t && o.minY <= b.maxY + t &&
          b.minY <= o.maxY + t && root(a) != root(k) && joinable(a, k)) {
        const int ra = root(a);
        const int rk = root(k);
        parent[std::max(ra, rk)] = std::min(ra, rk);
      }
    }
  }
  std::vector<std::vector<int>> groups;
  std::vector<int> groupOf(boxes.size(), -1);
  for (int k = 0; k < static_cast<int>(boxes.size()); ++k) {
    const int r = root(k);
    if (groupOf[r] < 0) {
      groupOf[r] = static_cast<int>(groups.size());
      groups.emplace_back();
    }
    groups[groupOf[r]].push_back(k);
  }
  return groups;
}

std::vector<Cluster> clusterFacets(const std::vector<Facet>& facets) {
  std::vector<int> flat;
  std::vector<int> tilted;
  for (std::size_t i = 0; i < facets.size(); ++i) {
    (facets[i].horizontal ? flat : tilted).push_back(static_cast<int>(i));
  }
  std::stable_sort(flat.begin(), flat.end(),
                   [&](int a, int b) { return facets[a].zMax < facets[b].zMax; });
  std::vector<Cluster> clusters;
  const auto start = [&](int i) {
    Cluster c;
    c.facets.push_back(i);
    c.zFirst = c.z = facets[i].zMax;
    clusters.push_back(std::move(c));
  };
  const auto join = [&](Cluster& c, int i) {
    c.facets.push_back(i);
    c.z = std::max(c.z, facets[i].zMax);
  };
  for (int i : flat) {
    if (!clusters.empty() && facets[i].zMax - clusters.back().zFirst <= kHeightTolerance) {
      join(clusters.back(), i);
    } else {
      start(i);
    }
  }
  // Tilted facets: joined where their boxes touch and their planes agree over both.
  std::vector<Box2> boxes;
  boxes.reserve(tilted.size());
  for (int i : tilted) {
    boxes.push_back(facets[i].box);
  }
  const auto groups = touchingGroups(boxes, [&](int a, int b) {
    return coplanar(facets[tilted[a]].plane, facets[tilted[b]].plane, merged(boxes[a], boxes[b]));
  });
  for (const std::vector<int>& group : groups) {
    start(tilted[group.front()]);
    for (std::size_t k = 1; k < group.size(); ++k) {
      join(clusters.back(), tilted[group[k]]);
    }
  }
  return clusters;
}

}  // namespace surfaces
}  // namespace placement_samplers
