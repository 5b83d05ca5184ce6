#include "resting.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "placement_samplers/geometry/resting_poses.hpp"

namespace placement_samplers::benchmark {
namespace {

using Clock = std::chrono::steady_clock;

Shape meshShape(std::shared_ptr<Mesh> mesh) {
  Shape shape;
  shape.type = ShapeType::Mesh;
  shape.mesh = std::move(mesh);
  return shape;
}

/// An ellipsoid of semi-axes 0.1, 0.06, 0.04 m: 2 poles and 200 rings of 250 vertices, each ring
/// turned half a segment from the last (no two triangles coplanar): 100,000 triangles.
Shape ellipsoidMesh() {
  constexpr int kSegments = 250, kRings = 200;
  auto mesh = std::make_shared<Mesh>();
  mesh->vertices.emplace_back(0.0, 0.0, 0.04);
  for (int j = 1; j <= kRings; ++j) {
    const double polar = M_PI * j / (kRings + 1);
    for (int k = 0; k < kSegments; ++k) {
      const double t = 2.0 * M_PI * (k + 0.5 * (j % 2)) / kSegments;
      mesh->vertices.emplace_back(0.1 * std::sin(polar) * std::cos(t),
                                  0.06 * std::sin(polar) * std::sin(t), 0.04 * std::cos(polar));
    }
  }
  mesh->vertices.emplace_back(0.0, 0.0, -0.04);
  const int last = static_cast<int>(mesh->vertices.size()) - 1;
  auto at = [](int ring, int k) { return 1 + (ring - 1) * kSegments + (k % kSegments); };
  for (int k = 0; k < kSegments; ++k) {
    mesh->triangles.emplace_back(0, at(1, k), at(1, k + 1));
    mesh->triangles.emplace_back(last, at(kRings, k + 1), at(kRings, k));
  }
  // Each quad between two rings split along the diagonal that keeps the surface convex.
  const std::vector<Eigen::Vector3d>& p = mesh->vertices;
  for (int j = 1; j < kRings; ++j) {
    for (int k = 0; k < kSegments; ++k) {
      const int a = at(j, k), b = at(j + 1, k), c = at(j + 1, k + 1), d = at(j, k + 1);
      const Eigen::Vector3d n = (p[b] - p[a]).cross(p[d] - p[a]);
      if (n.dot(p[c] - p[a]) <= 0.0) {
        mesh->triangles.emplace_back(a, b, d);
        mesh->triangles.emplace_back(d, b, c);
      } else {
        mesh->triangles.emplace_back(a, b, c);
        mesh->triangles.emplace_back(a, c, d);
      }
    }
  }
  return meshShape(mesh);
}

/// A box 0.2 x 0.1 x 0.05 m, each side a grid of 91 x 91 squares of two triangles (99,372 in
/// all; every vertex of a side on its plane, those of its edges on a line).
Shape tessellatedBoxMesh() {
  constexpr int kCells = 91;
  const Eigen::Vector3d half(0.1, 0.05, 0.025);
  auto mesh = std::make_shared<Mesh>();
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {-1.0, 1.0}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const int base = static_cast<int>(mesh->vertices.size());
      for (int i = 0; i <= kCells; ++i) {
        for (int k = 0; k <= kCells; ++k) {
          Eigen::Vector3d p;
          p[axis] = sign * half[axis];
          p[u] = half[u] * (2.0 * i / kCells - 1.0);
          p[v] = half[v] * (2.0 * k / kCells - 1.0);
          mesh->vertices.push_back(p);
        }
      }
      auto at = [&](int i, int k) { return base + i * (kCells + 1) + k; };
      for (int i = 0; i < kCells; ++i) {
        for (int k = 0; k < kCells; ++k) {
          mesh->triangles.emplace_back(at(i, k), at(i + 1, k), at(i + 1, k + 1));
          mesh->triangles.emplace_back(at(i, k), at(i + 1, k + 1), at(i, k + 1));
        }
      }
    }
  }
  return meshShape(mesh);
}

/// A cup of radius 0.05 m and height 0.1 m with 4 mm walls and a 6 mm bottom: a profile of 200
/// points (outer bottom, outer wall, rim, inner wall, inner bottom) turned through 250 segments,
/// closed at the two centres: 100,000 triangles, not convex (the inside).
Shape cupMesh() {
  constexpr int kSegments = 250;
  const double radius = 0.05, height = 0.1, wall = 0.004, bottom = 0.006;
  std::vector<Eigen::Vector2d> profile;  // (r, z)
  for (int i = 1; i <= 20; ++i) {
    profile.emplace_back(radius * i / 20.0, 0.0);
  }
  for (int j = 1; j <= 80; ++j) {
    profile.emplace_back(radius, height * j / 80.0);
  }
  profile.emplace_back(radius - wall, height);
  for (int j = 1; j <= 79; ++j) {
    profile.emplace_back(radius - wall, height - (height - bottom) * j / 79.0);
  }
  for (int i = 1; i <= 20; ++i) {
    profile.emplace_back((radius - wall) * (1.0 - i / 21.0), bottom);
  }
  const int rings = static_cast<int>(profile.size());
  auto mesh = std::make_shared<Mesh>();
  mesh->vertices.emplace_back(0.0, 0.0, 0.0);
  for (const Eigen::Vector2d& rz : profile) {
    for (int k = 0; k < kSegments; ++k) {
      const double t = 2.0 * M_PI * k / kSegments;
      mesh->vertices.emplace_back(rz.x() * std::cos(t), rz.x() * std::sin(t), rz.y());
    }
  }
  mesh->vertices.emplace_back(0.0, 0.0, bottom);
  const int last = static_cast<int>(mesh->vertices.size()) - 1;
  auto at = [](int ring, int k) { return 1 + (ring - 1) * kSegments + k % kSegments; };
  for (int k = 0; k < kSegments; ++k) {
    mesh->triangles.emplace_back(0, at(1, k + 1), at(1, k));
    mesh->triangles.emplace_back(last, at(rings, k), at(rings, k + 1));
    for (int j = 1; j < rings; ++j) {
      mesh->triangles.emplace_back(at(j, k), at(j + 1, k + 1), at(j + 1, k));
      mesh->triangles.emplace_back(at(j, k), at(j, k + 1), at(j + 1, k + 1));
    }
  }
  return meshShape(mesh);
}

Shape lBlockHullMesh() {
  auto mesh = std::make_shared<Mesh>();
  const double xy[6][2] = {{-0.04, -0.04}, {0.04, -0.04}, {0.04, -0.02},
                           {-0.02, -0.02}, {-0.02, 0.04}, {-0.04, 0.04}};
  for (double z : {-0.015, 0.015}) {
    for (const auto& p : xy) {
      mesh->vertices.emplace_back(p[0], p[1], z);
    }
  }
  return meshShape(mesh);  // vertices are all the hull needs
}

struct Case {
  std::string name;
  std::string triangles;
  std::vector<Shape> shapes;
};

}  // namespace

void benchResting(int repetitions) {
  Shape handle = Shape::box(Eigen::Vector3d(0.03, 0.012, 0.06));
  handle.pose.translation() = Eigen::Vector3d(0.055, 0.0, 0.0);
  const Shape ellipsoid = ellipsoidMesh();
  Shape ellipsoidVertices = ellipsoid;
  auto bare = std::make_shared<Mesh>(*ellipsoid.mesh);
  bare->triangles.clear();
  ellipsoidVertices.mesh = bare;
  const std::vector<Case> cases = {
      {"ellipsoid mesh (convex)", "100000", {ellipsoid}},
      {"ellipsoid vertices (quickhull)", "", {ellipsoidVertices}},
      {"cup mesh (not convex: quickhull)", "100000", {cupMesh()}},
      {"tessellated box (quickhull)", "99372", {tessellatedBoxMesh()}},
      {"mug: cylinder + box handle", "", {Shape::cylinder(0.04, 0.1), handle}},
      {"L-block (12 vertices)", "", {lBlockHullMesh()}},
      {"box (closed form)", "", {Shape::box(Eigen::Vector3d(0.2, 0.1, 0.05))}},
  };
  std::printf("\nrestingPoses(), median of %d calls [ms]\n", repetitions);
  std::printf("%-32s %10s %8s %6s %12s\n", "object", "triangles", "poses", "rolls", "time [ms]");
  for (const Case& c : cases) {
    std::vector<double> ms;
    std::size_t poses = 0, rolling = 0;
    RestingOptions withRolling;
    withRolling.allowRolling = true;
    rolling = restingPoses(c.shapes, withRolling).size();
    for (int r = 0; r <= repetitions; ++r) {
      const Clock::time_point start = Clock::now();
      poses = restingPoses(c.shapes).size();
      if (r > 0) {  // the first call warms up
        ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
      }
    }
    std::sort(ms.begin(), ms.end());
    std::printf("%-32s %10s %8zu %6zu %12.3f\n", c.name.c_str(), c.triangles.c_str(), poses,
                rolling - poses, ms[ms.size() / 2]);
  }
}

}  // namespace placement_samplers::benchmark
