// Meshes' up-facing facets without a polygon union per triangle: up-facing triangles joined
// across shared edges when coplanar, each group's boundary edges (those no coplanar neighbour
// shares) chained into loops. Linear in the triangles but for a sort of the boundary edges.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "geometry/surface_parts.hpp"

namespace placement_samplers {
namespace surfaces {
namespace {

/// A group whose loops make no valid polygon (a broken mesh) is rebuilt as the union of its
/// triangles when it has at most this many; larger ones keep only their valid polygons.
constexpr std::size_t kUnionFallbackTriangles = 4096;

double cross2(const Point2& u, const Point2& v) { return u.x() * v.y() - u.y() * v.x(); }

/// One side of an up-facing triangle, filed under its lower vertex index.
struct EdgeRef {
  int hi;        ///< the higher vertex index
  int up;        ///< the triangle (index among the up-facing ones)
  int corner;    ///< the side runs from corner to corner + 1
  bool forward;  ///< it runs from the lower vertex index to the higher one
};

/// A side no coplanar neighbour shares: part of its group's boundary.
struct BoundaryEdge {
  int group, from, to;
  bool operator<(const BoundaryEdge& o) const {
    return group != o.group ? group < o.group : from != o.from ? from < o.from : to < o.to;
  }
};

class MeshGrouper {
 public:
  MeshGrouper(const WorldMesh& mesh, std::vector<int> up) : mesh_(mesh), up_(std::move(up)) {}

  /// The facets of the up-facing triangles.
  void addFacets(std::vector<Facet>& facets) {
    if (!matchEdges() && dropDuplicates()) {
      matchEdges();
    }
    makeFacets(facets);
  }

 private:
  const Eigen::Vector3d& vertex(int up, int corner) const {
    return mesh_.vertices[mesh_.triangles[up_[up]][corner % 3]];
  }
  Eigen::Vector3d normal(int up) const {
    return (vertex(up, 1) - vertex(up, 0)).cross(vertex(up, 2) - vertex(up, 0));
  }
  /// Whether @p q is within kHeightTolerance of the plane of triangle @p up, vertically.
  bool onPlane(int up, const Eigen::Vector3d& q) const {
    const Eigen::Vector3d n = normal(up);
    const Eigen::Vector3d& p = vertex(up, 0);
    const double z = p.z() - (n.x() * (q.x() - p.x()) + n.y() * (q.y() - p.y())) / n.z();
    return std::abs(q.z() - z) <= kHeightTolerance;
  }
  bool coplanar(const EdgeRef& e, const EdgeRef& f) const {
    return onPlane(e.up, vertex(f.up, f.corner + 2)) && onPlane(f.up, vertex(e.up, e.corner + 2));
  }
  int find(int x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }

  /// Pairs opposite sides of coplanar neighbours and joins their triangles.
  /// @return false when a side appears twice in one direction (duplicated triangles, folds)
  bool matchEdges() {
    const std::size_t count = up_.size();
    parent_.resize(count);
    std::iota(parent_.begin(), parent_.end(), 0);
    // Sides filed by their lower vertex (a counting sort: no hashing, sequential memory).
    std::vector<int> start(mesh_.vertices.size() + 1, 0);
    for (std::size_t u = 0; u < count; ++u) {
      for (int k = 0; k < 3; ++k) {
        const std::array<int, 3>& t = mesh_.triangles[up_[u]];
        ++start[std::min(t[k], t[(k + 1) % 3]) + 1];
      }
    }
    std::partial_sum(start.begin(), start.end(), start.begin());
    edges_.assign(3 * count, EdgeRef{});
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t u = 0; u < count; ++u) {
      const std::array<int, 3>& t = mesh_.triangles[up_[u]];
      for (int k = 0; k < 3; ++k) {
        const int a = t[k];
        const int b = t[(k + 1) % 3];
        edges_[fill[std::min(a, b)]++] = EdgeRef{std::max(a, b), static_cast<int>(u), k, a < b};
      }
    }
    matched_.assign(edges_.size(), 0);
    bool simple = true;
    for (std::size_t v = 0; v + 1 < start.size(); ++v) {
      const auto first = edges_.begin() + start[v];
      const auto last = edges_.begin() + start[v + 1];
      if (last - first > 2) {
        std::sort(first, last, [](const EdgeRef& a, const EdgeRef& b) { return a.hi < b.hi; });
      }
      for (auto run = first; run != last;) {
        auto end = run;
        while (end != last && end->hi == run->hi) {
          ++end;
        }
        simple = matchRun(run - edges_.begin(), end - edges_.begin()) && simple;
        run = end;
      }
    }
    return simple;
  }

  /// Matches the sides of one vertex pair [first, last): each forward one with a coplanar
  /// backward one. @return false when two run the same way
  bool matchRun(std::ptrdiff_t first, std::ptrdiff_t last) {
    int forward = 0;
    for (std::ptrdiff_t i = first; i < last; ++i) {
      forward += edges_[i].forward ? 1 : 0;
    }
    const bool simple = forward <= 1 && last - first - forward <= 1;
    for (std::ptrdiff_t i = first; i < last; ++i) {
      if (!edges_[i].forward || matched_[i]) {
        continue;
      }
      for (std::ptrdiff_t j = first; j < last; ++j) {
        if (!edges_[j].forward && !matched_[j] && coplanar(edges_[i], edges_[j])) {
          matched_[i] = matched_[j] = 1;
          const int a = find(edges_[i].up);
          const int b = find(edges_[j].up);
          parent_[std::max(a, b)] = std::min(a, b);
          break;
        }
      }
    }
    return simple;
  }

  /// Leaves out triangles that repeat another (same vertices, same turn).
  /// @return whether any was left out
  bool dropDuplicates() {
    std::vector<std::pair<std::array<int, 3>, int>> keyed;
    keyed.reserve(up_.size());
    for (int index : up_) {
      std::array<int, 3> t = mesh_.triangles[index];
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      keyed.emplace_back(t, index);
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<int> kept;
    for (std::size_t i = 0; i < keyed.size(); ++i) {
      if (i == 0 || keyed[i].first != keyed[i - 1].first) {
        kept.push_back(keyed[i].second);
      }
    }
    const bool dropped = kept.size() < up_.size();
    up_.swap(kept);
    return dropped;
  }

  /// The loops of one group's boundary edges [first, last) (sorted by their start vertex).
  std::vector<Ring> loops(const std::vector<BoundaryEdge>& edges, std::size_t first,
                          std::size_t last) const {
    std::vector<Ring> rings;
    std::vector<char> used(last - first, 0);
    const auto xy = [&](int v) -> Point2 { return mesh_.vertices[v].head<2>(); };
    for (std::size_t i = first; i < last; ++i) {
      if (used[i - first]) {
        continue;
      }
      Ring ring;
      std::size_t current = i;
      bool closed = false;
      for (std::size_t steps = 0; steps < last - first; ++steps) {
        used[current - first] = 1;
        ring.push_back(xy(edges[current].from));
        const int v = edges[current].to;
        if (v == edges[i].from) {
          closed = true;
          break;
        }
        // Where the boundary touches itself at v, the sharpest left turn keeps the region on
        // the left of one loop: the largest counter-clockwise angle from the way back.
        const Point2 back = xy(edges[current].from) - xy(v);
        std::size_t next = last;
        double best = -1.0;
        const auto range = std::equal_range(
            edges.begin() + first, edges.begin() + last, BoundaryEdge{edges[i].group, v, 0},
            [](const BoundaryEdge& a, const BoundaryEdge& b) { return a.from < b.from; });
        for (auto it = range.first; it != range.second; ++it) {
          const std::size_t j = it - edges.begin();
          if (used[j - first]) {
            continue;
          }
          const Point2 out = xy(it->to) - xy(v);
          double angle = std::atan2(cross2(back, out), back.dot(out));
          angle = angle < 0.0 ? angle + 2.0 * M_PI : angle;
          if (angle > best) {
            best = angle;
            next = j;
          }
        }
        if (next == last) {
          break;  // cannot happen for a group's boundary; never loop on it
        }
        current = next;
      }
      if (closed) {
        rings.push_back(std::move(ring));
      }
    }
    return rings;
  }

  void makeFacets(std::vector<Facet>& facets) {
    const std::size_t count = up_.size();
    std::vector<int> group(count, -1);
    std::vector<int> groupOfRoot(count, -1);
    int groups = 0;
    for (std::size_t u = 0; u < count; ++u) {
      const int root = find(static_cast<int>(u));
      if (groupOfRoot[root] < 0) {
        groupOfRoot[root] = groups++;
      }
      group[u] = groupOfRoot[root];
    }
    std::vector<BoundaryEdge> boundary;
    for (std::size_t i = 0; i < edges_.size(); ++i) {
      if (!matched_[i]) {
        const EdgeRef& e = edges_[i];
        const std::array<int, 3>& t = mesh_.triangles[up_[e.up]];
        boundary.push_back(BoundaryEdge{group[e.up], t[e.corner], t[(e.corner + 1) % 3]});
      }
    }
    std::sort(boundary.begin(), boundary.end());
    // The triangles of each group, in order (a counting sort).
    std::vector<int> start(groups + 1, 0);
    for (int g : group) {
      ++start[g + 1];
    }
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<int> members(count);
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t u = 0; u < count; ++u) {
      members[fill[group[u]]++] = static_cast<int>(u);
    }
    std::size_t edge = 0;
    for (int g = 0; g < groups; ++g) {
      const std::size_t first = edge;
      while (edge < boundary.size() && boundary[edge].group == g) {
        ++edge;
      }
      addGroup(members.begin() + start[g], members.begin() + start[g + 1],
               loops(boundary, first, edge), facets);
    }
  }

  void addGroup(std::vector<int>::const_iterator first, std::vector<int>::const_iterator last,
                std::vector<Ring> rings, std::vector<Facet>& facets) const {
    Facet facet;
    double zMin = std::numeric_limits<double>::infinity();
    facet.zMax = -zMin;
    Eigen::Vector3d normalSum = Eigen::Vector3d::Zero();
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    for (auto it = first; it != last; ++it) {
      const Eigen::Vector3d n = normal(*it);
      normalSum += n;
      weighted += n.z() * (vertex(*it, 0) + vertex(*it, 1) + vertex(*it, 2)) / 3.0;
      for (int k = 0; k < 3; ++k) {
        zMin = std::min(zMin, vertex(*it, k).z());
        facet.zMax = std::max(facet.zMax, vertex(*it, k).z());
      }
    }
    bool valid = true;
    facet.polygons = polygonsFromLoops(std::move(rings), valid);
    if (!valid && static_cast<std::size_t>(last - first) <= kUnionFallbackTriangles) {
      Polygons triangles;
      for (auto it = first; it != last; ++it) {
        Ring ring = {vertex(*it, 0).head<2>(), vertex(*it, 1).head<2>(), vertex(*it, 2).head<2>()};
        if (simplifyRing(ring)) {
          triangles.push_back(Polygon2{std::move(ring), {}});
        }
      }
      facet.polygons = unitePolygons(std::move(triangles));
    }
    if (facet.polygons.empty()) {
      return;
    }
    facet.horizontal = facet.zMax - zMin <= kHeightTolerance;
    if (facet.horizontal) {
      facet.plane.c = facet.zMax;
    } else {
      // Through the area-weighted centroid, along the area-weighted normal.
      const Eigen::Vector3d centroid = weighted / normalSum.z();
      facet.plane.a = -normalSum.x() / normalSum.z();
      facet.plane.b = -normalSum.y() / normalSum.z();
      facet.plane.c = centroid.z() - facet.plane.a * centroid.x() - facet.plane.b * centroid.y();
    }
    facet.box = ringBox(facet.polygons.front().outer);
    for (const Polygon2& polygon : facet.polygons) {
      const Box2 b = ringBox(polygon.outer);
      facet.box = Box2{std::min(facet.box.minX, b.minX), std::min(facet.box.minY, b.minY),
                       std::max(facet.box.maxX, b.maxX), std::max(facet.box.maxY, b.maxY)};
    }
    facets.push_back(std::move(facet));
  }

  const WorldMesh& mesh_;
  std::vector<int> up_;  ///< indices of the up-facing triangles in mesh_.triangles
  std::vector<int> parent_;
  std::vector<EdgeRef> edges_;
  std::vector<char> matched_;
};

}  // namespace

void addMeshFacets(const WorldMesh& mesh, std::vector<int> up, std::vector<Facet>& facets) {
  MeshGrouper(mesh, std::move(up)).addFacets(facets);
}

}  // namespace surfaces
}  // namespace placement_samplers
