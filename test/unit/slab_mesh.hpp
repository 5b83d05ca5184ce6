#pragma once

// Generated meshes for the support surface tests and benchmark: a closed box whose top is
// finely subdivided (many coplanar up-facing triangles), and a rough sheet (many up-facing
// triangles, few of them coplanar).

#include <Eigen/Core>
#include <vector>

#include "placement_samplers/geometry/shape.hpp"

namespace placement_samplers {
namespace test {

/// The box [-sx/2, sx/2] x [-sy/2, sy/2] x [z0, z1] [m]: its top an n x n grid of squares of
/// two triangles each, its sides strips through the top's border vertices, its bottom a fan
/// about its centre; 2 n^2 + 12 n triangles, counter-clockwise seen from outside.
inline Mesh makeSlabMesh(double sx, double sy, double z0, double z1, int n) {
  Mesh mesh;
  mesh.source = "generated slab";
  const auto top = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      mesh.vertices.emplace_back(-0.5 * sx + sx * i / n, -0.5 * sy + sy * j / n, z1);
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      mesh.triangles.emplace_back(top(i, j), top(i + 1, j), top(i + 1, j + 1));
      mesh.triangles.emplace_back(top(i, j), top(i + 1, j + 1), top(i, j + 1));
    }
  }
  // The top's border, counter-clockwise seen from above.
  std::vector<int> border;
  for (int i = 0; i < n; ++i) border.push_back(top(i, 0));
  for (int j = 0; j < n; ++j) border.push_back(top(n, j));
  for (int i = n; i > 0; --i) border.push_back(top(i, n));
  for (int j = n; j > 0; --j) border.push_back(top(0, j));
  const int firstBottom = static_cast<int>(mesh.vertices.size());
  for (int v : border) {
    mesh.vertices.emplace_back(mesh.vertices[v].x(), mesh.vertices[v].y(), z0);
  }
  const int centre = static_cast<int>(mesh.vertices.size());
  mesh.vertices.emplace_back(0.0, 0.0, z0);
  const int count = static_cast<int>(border.size());
  for (int k = 0; k < count; ++k) {
    const int next = (k + 1) % count;
    const int b0 = firstBottom + k;
    const int b1 = firstBottom + next;
    mesh.triangles.emplace_back(b0, b1, border[next]);
    mesh.triangles.emplace_back(b0, border[next], border[k]);
    mesh.triangles.emplace_back(centre, b1, b0);
  }
  return mesh;
}

/// An open sheet over [0, 0.01 n]^2 [m]: an n x n grid of squares of two triangles each (2 n^2
/// triangles), its vertices at pseudo-random heights in [0, 0.35] mm, so that the triangles
/// tilt by up to about 0.05 rad and few neighbours are coplanar.
inline Mesh makeRoughMesh(int n) {
  Mesh mesh;
  mesh.source = "generated rough sheet";
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const unsigned hash = (static_cast<unsigned>(i) * 73856093u) ^ (j * 19349663u);
      mesh.vertices.emplace_back(0.01 * i, 0.01 * j, 0.00005 * ((hash >> 4) % 8));
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int v = j * (n + 1) + i;
      mesh.triangles.emplace_back(v, v + 1, v + n + 2);
      mesh.triangles.emplace_back(v, v + n + 2, v + n + 1);
    }
  }
  return mesh;
}

}  // namespace test
}  // namespace placement_samplers
