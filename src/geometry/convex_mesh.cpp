// convexMeshHull(): a closed mesh that is convex already is its own hull. Collision meshes often
// are (convex decompositions, hulls saved as meshes), and checking costs linear time where
// quickhull on 50,000 vertices that all lie on the hull costs a lot more.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "geometry/convex_hull.hpp"

namespace placement_samplers::detail {
namespace {

/// The directed edges of a triangle mesh: edge e = 3 t + k of triangle t goes from its corner k
/// to its corner k + 1; outgoing[first[v] .. first[v + 1]) are the edges leaving vertex v.
struct MeshEdges {
  std::vector<int> tails, heads;  ///< per edge
  std::vector<int> first;
  std::vector<int> outgoing;
  std::vector<int> twin;

  int tail(int e) const { return tails[static_cast<std::size_t>(e)]; }
  int head(int e) const { return heads[static_cast<std::size_t>(e)]; }
};

/// Fills the edges grouped by vertex; false when a vertex has no triangle.
bool groupEdges(MeshEdges& m, const std::vector<Eigen::Vector3i>& triangles, std::size_t vertices) {
  const int edges = static_cast<int>(3 * triangles.size());
  m.tails.resize(static_cast<std::size_t>(edges));
  m.heads.resize(static_cast<std::size_t>(edges));
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      m.tails[3 * t + static_cast<std::size_t>(k)] = triangles[t][k];
      m.heads[3 * t + static_cast<std::size_t>(k)] = triangles[t][(k + 1) % 3];
    }
  }
  m.first.assign(vertices + 1, 0);
  for (int e = 0; e < edges; ++e) {
    ++m.first[static_cast<std::size_t>(m.tail(e)) + 1];
  }
  for (std::size_t v = 0; v < vertices; ++v) {
    if (m.first[v + 1] == 0) {
      return false;  // unused: it could lie outside the surface
    }
    m.first[v + 1] += m.first[v];
  }
  m.outgoing.resize(static_cast<std::size_t>(edges));
  std::vector<int> cursor(m.first.begin(), m.first.end() - 1);
  for (int e = 0; e < edges; ++e) {
    m.outgoing[static_cast<std::size_t>(cursor[static_cast<std::size_t>(m.tail(e))]++)] = e;
  }
  return true;
}

/// Fills the twin of each edge; false when an edge is not matched by exactly one edge the other
/// way.
bool matchTwins(MeshEdges& m) {
  const int edges = static_cast<int>(m.tails.size());
  m.twin.assign(static_cast<std::size_t>(edges), -1);
  for (int e = 0; e < edges; ++e) {
    const int a = m.tail(e), b = m.head(e);
    int matches = 0, same = 0;
    for (int i = m.first[static_cast<std::size_t>(b)]; i < m.first[static_cast<std::size_t>(b) + 1];
         ++i) {
      const int x = m.outgoing[static_cast<std::size_t>(i)];
      if (m.head(x) == a) {
        ++matches;
        m.twin[static_cast<std::size_t>(e)] = x;
      }
    }
    for (int i = m.first[static_cast<std::size_t>(a)]; i < m.first[static_cast<std::size_t>(a) + 1];
         ++i) {
      same += m.head(m.outgoing[static_cast<std::size_t>(i)]) == b ? 1 : 0;
    }
    if (matches != 1 || same != 1) {
      return false;
    }
  }
  return true;
}

}  // namespace

std::optional<ConvexHull> convexMeshHull(const std::vector<Eigen::Vector3d>& points,
                                         const std::vector<Eigen::Vector3i>& triangles) {
  const std::size_t vertexCount = points.size(), triangleCount = triangles.size();
  if (triangleCount < 4 || vertexCount > kMaxHullPoints || triangleCount > 2 * kMaxHullPoints) {
    return std::nullopt;
  }
  for (const Eigen::Vector3i& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || static_cast<std::size_t>(t[k]) >= vertexCount || t[k] == t[(k + 1) % 3]) {
        return std::nullopt;
      }
    }
  }
  // A closed surface of the sphere's topology: V - E + F = 2 with E = 3 F / 2.
  if (2 * vertexCount != triangleCount + 4) {
    return std::nullopt;
  }
  MeshEdges m;
  if (!groupEdges(m, triangles, vertexCount)) {
    return std::nullopt;
  }
  auto at = [&](int vertex) -> const Eigen::Vector3d& {
    return points[static_cast<std::size_t>(vertex)];
  };
  std::vector<Eigen::Vector3d> normal(triangleCount);
  std::vector<double> area(triangleCount);
  for (std::size_t t = 0; t < triangleCount; ++t) {
    const Eigen::Vector3i& c = triangles[t];
    const Eigen::Vector3d n = (at(c[1]) - at(c[0])).cross(at(c[2]) - at(c[0]));
    area[t] = n.norm();
    if (!(area[t] > 0.0) || !std::isfinite(area[t])) {
      return std::nullopt;
    }
    normal[t] = n / area[t];
  }
  // Convex at every vertex: its neighbours on or below the plane of each of its triangles.
  const double tol = hullTolerance(points);
  for (std::size_t t = 0; t < triangleCount; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int v = triangles[t][k];
      for (int i = m.first[static_cast<std::size_t>(v)];
           i < m.first[static_cast<std::size_t>(v) + 1]; ++i) {
        const int w = m.head(m.outgoing[static_cast<std::size_t>(i)]);
        if (normal[t].dot(at(w) - at(v)) > tol) {
          return std::nullopt;
        }
      }
    }
  }
  if (!matchTwins(m)) {
    return std::nullopt;
  }
  // Faces: triangles grown from a seed while all their corners lie within the tolerance of the
  // seed's plane. (No check that the surface is one piece: with V - E + F = 2 a second piece
  // would make the other one a torus or worse, which is not convex at every vertex.)
  std::vector<int> region(triangleCount, -1);
  std::vector<int> queue;
  std::vector<int> seeds;
  std::vector<Eigen::Vector3d> regionNormal;
  for (std::size_t seed = 0; seed < triangleCount; ++seed) {
    if (region[seed] >= 0) {
      continue;
    }
    const int r = static_cast<int>(seeds.size());
    seeds.push_back(static_cast<int>(seed));
    regionNormal.push_back(Eigen::Vector3d::Zero());
    const Eigen::Vector3d& n = normal[seed];
    const Eigen::Vector3d& origin = at(triangles[seed][0]);
    region[seed] = r;
    queue.assign(1, static_cast<int>(seed));
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const std::size_t u = static_cast<std::size_t>(queue[q]);
      regionNormal.back() += area[u] * normal[u];
      for (int k = 0; k < 3; ++k) {
        const std::size_t w =
            static_cast<std::size_t>(m.twin[3 * u + static_cast<std::size_t>(k)] / 3);
        if (region[w] >= 0) {
          continue;
        }
        bool flat = true;
        for (int j = 0; j < 3; ++j) {
          flat = flat && std::abs(n.dot(at(triangles[w][j]) - origin)) <= tol;
        }
        if (flat) {
          region[w] = r;
          queue.push_back(static_cast<int>(w));
        }
      }
    }
  }
  // Each face's boundary, walked edge to edge in the triangles' direction.
  auto boundary = [&](int e) {
    return region[static_cast<std::size_t>(m.twin[static_cast<std::size_t>(e)] / 3)] !=
           region[static_cast<std::size_t>(e / 3)];
  };
  std::vector<int> boundaryCount(seeds.size(), 0), startEdge(seeds.size(), -1);
  for (int e = 0; e < static_cast<int>(3 * triangleCount); ++e) {
    if (boundary(e)) {
      const std::size_t r = static_cast<std::size_t>(region[static_cast<std::size_t>(e / 3)]);
      ++boundaryCount[r];
      if (startEdge[r] < 0) {
        startEdge[r] = e;
      }
    }
  }
  ConvexHull hull;
  hull.tolerance = tol;
  for (std::size_t r = 0; r < seeds.size(); ++r) {
    if (startEdge[r] < 0) {
      return std::nullopt;  // a face with no edge: the surface is one flat piece
    }
    int e = startEdge[r];
    for (int steps = 0;; ++steps) {
      if (steps == boundaryCount[r]) {
        if (e != startEdge[r]) {
          return std::nullopt;
        }
        break;
      }
      hull.vertices.push_back(m.tail(e));
      hull.neighbours.push_back(
          region[static_cast<std::size_t>(m.twin[static_cast<std::size_t>(e)] / 3)]);
      // The one boundary edge of this face that leaves the vertex this one reaches.
      const int b = m.head(e);
      int next = -1;
      for (int i = m.first[static_cast<std::size_t>(b)];
           i < m.first[static_cast<std::size_t>(b) + 1]; ++i) {
        const int x = m.outgoing[static_cast<std::size_t>(i)];
        if (region[static_cast<std::size_t>(x / 3)] == static_cast<int>(r) && boundary(x)) {
          if (next >= 0) {
            return std::nullopt;  // the face touches itself at b
          }
          next = x;
        }
      }
      if (next < 0) {
        return std::nullopt;
      }
      e = next;
    }
    hull.start.push_back(static_cast<int>(hull.vertices.size()));
    hull.normals.push_back(regionNormal[r].normalized());
  }
  if (hull.faceCount() < 4) {
    return std::nullopt;
  }
  return hull;
}

}  // namespace placement_samplers::detail
