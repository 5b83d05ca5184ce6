// Meshes in the frame of the surfaces: vertices welded (STL files repeat every vertex), each
// triangle an obstacle where its projection has area, the up-facing ones handed to
// addMeshFacets.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "geometry/surface_parts.hpp"

namespace placement_samplers {
namespace surfaces {
namespace {

/// Vertices in the same cell of this size are one [m]: STL files repeat every vertex.
constexpr double kWeldStep = 1e-9;

std::uint64_t cellBits(double coordinate) {
  double cell = std::nearbyint(coordinate / kWeldStep) + 0.0;  // + 0.0: -0 and 0 are one cell
  std::uint64_t bits;
  std::memcpy(&bits, &cell, sizeof bits);
  return bits;
}

std::uint64_t mix(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

WorldMesh weld(const Mesh& mesh, const Eigen::Isometry3d& pose) {
  const std::size_t n = mesh.vertices.size();
  WorldMesh world;
  world.vertices.reserve(n);
  std::vector<int> id(n, -1);
  std::vector<std::array<std::uint64_t, 3>> keys;
  keys.reserve(n);
  std::size_t capacity = 16;
  while (capacity < 2 * n) {
    capacity <<= 1;
  }
  std::vector<int> table(capacity, -1);  // open addressing, linear probing
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p = pose * mesh.vertices[i];
    if (!p.allFinite() || p.cwiseAbs().maxCoeff() > kFarAway) {
      continue;  // its triangles are left out
    }
    const std::array<std::uint64_t, 3> key = {cellBits(p.x()), cellBits(p.y()), cellBits(p.z())};
    std::size_t slot = mix(key[0] ^ mix(key[1] ^ mix(key[2]))) & (capacity - 1);
    while (table[slot] >= 0 && keys[table[slot]] != key) {
      slot = (slot + 1) & (capacity - 1);
    }
    if (table[slot] < 0) {
      table[slot] = static_cast<int>(world.vertices.size());
      world.vertices.push_back(p);
      keys.push_back(key);
    }
    id[i] = table[slot];
  }
  world.triangles.reserve(mesh.triangles.size());
  const auto welded = [&](int index) {
    return index >= 0 && static_cast<std::size_t>(index) < n ? id[index] : -1;
  };
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const std::array<int, 3> w = {welded(t[0]), welded(t[1]), welded(t[2])};
    if (w[0] >= 0 && w[1] >= 0 && w[2] >= 0 && w[0] != w[1] && w[1] != w[2] && w[0] != w[2]) {
      world.triangles.push_back(w);
    }
  }
  world.zMin = std::numeric_limits<double>::infinity();
  world.zMax = -world.zMin;
  for (const Eigen::Vector3d& p : world.vertices) {
    world.zMin = std::min(world.zMin, p.z());
    world.zMax = std::max(world.zMax, p.z());
  }
  return world;
}

}  // namespace

void addMesh(const Mesh& mesh, const Eigen::Isometry3d& pose, double cosTolerance,
             SurfaceParts& parts) {
  WorldMesh world = weld(mesh, pose);
  if (world.triangles.empty()) {
    return;
  }
  const int meshIndex = static_cast<int>(parts.meshes.size());
  std::vector<int> up;
  parts.triangles.reserve(parts.triangles.size() + world.triangles.size());
  for (std::size_t i = 0; i < world.triangles.size(); ++i) {
    const std::array<int, 3>& t = world.triangles[i];
    const Eigen::Vector3d& p0 = world.vertices[t[0]];
    const Eigen::Vector3d& p1 = world.vertices[t[1]];
    const Eigen::Vector3d& p2 = world.vertices[t[2]];
    const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
    const double length = n.norm();
    // Half the length is the area: a triangle without area has no normal.
    if (0.5 * length > kDegenerateArea && n.z() > 0.0 && n.z() >= cosTolerance * length) {
      up.push_back(static_cast<int>(i));
    }
    if (0.5 * std::abs(n.z()) > kDegenerateArea) {
      TriangleObstacle obstacle;
      obstacle.zMin = std::min({p0.z(), p1.z(), p2.z()});
      obstacle.zMax = std::max({p0.z(), p1.z(), p2.z()});
      obstacle.box = Box2{std::min({p0.x(), p1.x(), p2.x()}), std::min({p0.y(), p1.y(), p2.y()}),
                          std::max({p0.x(), p1.x(), p2.x()}), std::max({p0.y(), p1.y(), p2.y()})};
      obstacle.mesh = meshIndex;
      obstacle.triangle = static_cast<int>(i);
      parts.triangles.push_back(obstacle);
    }
  }
  addMeshFacets(world, std::move(up), parts.facets);
  parts.meshes.push_back(std::move(world));
}

Ring triangleFootprint(const WorldMesh& mesh, int index) {
  const std::array<int, 3>& t = mesh.triangles[index];
  Ring ring = {mesh.vertices[t[0]].head<2>(), mesh.vertices[t[1]].head<2>(),
               mesh.vertices[t[2]].head<2>()};
  if (signedArea(ring) < 0.0) {
    std::swap(ring[1], ring[2]);
  }
  return ring;
}

}  // namespace surfaces
}  // namespace placement_samplers
