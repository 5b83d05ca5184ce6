// Resting poses of objects: the centre of mass the physics uses, the closed forms of the
// primitives, the hull of composites and meshes with toppling, checked against Monte Carlo
// drops, MuJoCo's mass model and hand-computed values.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/mujoco_compile.hpp"
#include "geometry/resting_hull.hpp"
#include "physics/physics_buffers.hpp"
#include "physics/physics_mjcf.hpp"
#include "placement_samplers/geometry/mesh_loader.hpp"
#include "placement_samplers/geometry/object_model.hpp"
#include "placement_samplers/geometry/resting_poses.hpp"

namespace placement_samplers {
namespace {

using Vec = Eigen::Vector3d;

Shape at(Shape shape, const Vec& position,
         const Eigen::Quaterniond& rotation = Eigen::Quaterniond::Identity()) {
  shape.pose = Eigen::Translation3d(position) * rotation;
  return shape;
}

/// A closed box mesh of 12 triangles, outward.
Shape boxMesh(const Vec& size) {
  auto mesh = std::make_shared<Mesh>();
  const Vec h = 0.5 * size;
  for (int i = 0; i < 8; ++i) {
    mesh->vertices.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                                (i & 4) ? h.z() : -h.z());
  }
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    mesh->triangles.emplace_back(q[0], q[1], q[2]);
    mesh->triangles.emplace_back(q[0], q[2], q[3]);
  }
  mesh->source = "box mesh";
  Shape shape;
  shape.type = ShapeType::Mesh;
  shape.mesh = mesh;
  return shape;
}

Shape lBlockMesh() {
  Shape shape;
  shape.type = ShapeType::Mesh;
  shape.mesh = std::make_shared<Mesh>(loadMeshFile(
      std::string(PLACEMENT_SAMPLERS_SOURCE_DIR) + "/meshes/l_block.stl", Vec::Ones(), "l_block"));
  return shape;
}

double sumOf(const std::vector<RestingPose>& poses) {
  double total = 0.0;
  for (const RestingPose& p : poses) {
    total += p.probability;
  }
  return total;
}

/// The pose whose normal is @p n (to 1e-6), or nullptr.
const RestingPose* poseWithNormal(const std::vector<RestingPose>& poses, const Vec& n) {
  for (const RestingPose& p : poses) {
    if ((p.normal - n).norm() < 1e-6) {
      return &p;
    }
  }
  return nullptr;
}

std::vector<Vec> randomDirections(std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  std::vector<Vec> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    out.push_back(Vec(g(rng), g(rng), g(rng)).normalized());
  }
  return out;
}

// ---- Centre of mass ----

TEST(CentreOfMass, CompositesAsMujocoSumsGeoms) {
  // Two boxes: 0.1 x 0.02 x 0.03 at the origin (6e-5 m^3) and 0.02 x 0.06 x 0.03 at
  // (-0.04, 0.04, 0) (3.6e-5 m^3): the L's centroid.
  const Vec c = centreOfMass({Shape::box(Vec(0.1, 0.02, 0.03)),
                              at(Shape::box(Vec(0.02, 0.06, 0.03)), Vec(-0.04, 0.04, 0.0))});
  EXPECT_NEAR(c.x(), -0.04 * 3.6e-5 / 9.6e-5, 1e-15);
  EXPECT_NEAR(c.y(), 0.04 * 3.6e-5 / 9.6e-5, 1e-15);
  EXPECT_NEAR(c.z(), 0.0, 1e-15);
  // A sphere of radius 0.1 (4.18879e-3 m^3) at x = 0.2 and a cylinder r 0.05, l 0.2
  // (1.570796e-3 m^3) at the origin, lying along x: overlapping volumes count twice.
  const double sphere = 4.0 / 3.0 * M_PI * 1e-3, cylinder = M_PI * 0.0025 * 0.2;
  const Vec d = centreOfMass({at(Shape::sphere(0.1), Vec(0.2, 0.0, 0.0)),
                              at(Shape::cylinder(0.05, 0.2), Vec::Zero(),
                                 Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Vec::UnitY())))});
  EXPECT_NEAR(d.x(), 0.2 * sphere / (sphere + cylinder), 1e-15);
  // A capsule (cylinder plus a ball) at z = 0.1 and a box at z = -0.1.
  const double capsule = M_PI * 0.0004 * 0.1 + 4.0 / 3.0 * M_PI * 8e-6, box = 0.1 * 0.1 * 0.02;
  const Vec e = centreOfMass({at(Shape::capsule(0.02, 0.1), Vec(0.0, 0.0, 0.1)),
                              at(Shape::box(Vec(0.1, 0.1, 0.02)), Vec(0.0, 0.0, -0.1))});
  EXPECT_NEAR(e.z(), (0.1 * capsule - 0.1 * box) / (capsule + box), 1e-15);
}

TEST(CentreOfMass, MeshIsItsConvexHullAsInThePhysics) {
  // The L-shaped block: MuJoCo is given its vertices only and takes their hull, a pentagonal
  // prism: a 0.08 square less the corner triangle of legs 0.06 at (0.04, 0.04).
  const Vec c = centreOfMass({lBlockMesh()});
  const double square = 0.0064, corner = 0.0018;
  EXPECT_NEAR(c.x(), -0.02 * corner / (square - corner), 1e-7);
  EXPECT_NEAR(c.y(), -0.02 * corner / (square - corner), 1e-7);
  EXPECT_NEAR(c.z(), 0.0, 1e-9);
  // Beside a box, MuJoCo 2.2.2 weighs a mesh by the volume of the box with its inertia: for
  // the tetrahedron (0, 0, 0), (s, 0, 0), (0, s, 0), (0, 0, s) that is 0.232379 s^3, not s^3 / 6
  // (worked out with numpy from the tetrahedron's principal moments).
  auto tetrahedron = std::make_shared<Mesh>();
  tetrahedron->vertices = {Vec(0, 0, 0), Vec(0.1, 0, 0), Vec(0, 0.1, 0), Vec(0, 0, 0.1)};
  Shape tetra;
  tetra.type = ShapeType::Mesh;
  tetra.mesh = tetrahedron;
  const double weight = 0.23237900077244517e-3, box = 1e-3;
  const Vec e = centreOfMass({tetra, at(Shape::box(Vec(0.1, 0.1, 0.1)), Vec(1, 0, 0))});
  EXPECT_NEAR(e.x(), (0.025 * weight + box) / (weight + box), 1e-12);
  EXPECT_NEAR(e.y(), 0.025 * weight / (weight + box), 1e-12);
  // A box mesh moved and turned in the object frame: its centre.
  const Vec d = centreOfMass({at(boxMesh(Vec(0.1, 0.2, 0.3)), Vec(0.1, -0.2, 0.3),
                                 Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vec::UnitX())))});
  EXPECT_LT((d - Vec(0.1, -0.2, 0.3)).norm(), 1e-15);
}

TEST(CentreOfMass, SameAsMujocoBuildsIt) {
  // The body the physics would simulate: its inertial frame's position is the centre of mass.
  const std::vector<Shape> shapes = {
      Shape::box(Vec(0.1, 0.02, 0.03)),
      at(Shape::cylinder(0.02, 0.05), Vec(0.03, 0.02, 0.01),
         Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Vec(1, 1, 0).normalized()))),
      at(Shape::sphere(0.015), Vec(-0.05, 0.0, 0.02)),
      at(Shape::capsule(0.01, 0.04), Vec(0.0, -0.03, 0.0)),
      at(lBlockMesh(), Vec(0.02, 0.05, -0.02),
         Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Vec::UnitZ())))};
  const ObjectModel object = makeObject("composite", shapes, Eigen::Quaterniond::Identity());
  PhysicsBody body;
  body.object = &object;
  const std::string xml =
      detail::physicsMjcf({}, {body}, PhysicsSettings(), detail::physicsBuffers(100, 6));
  detail::MujocoVfsPtr vfs = detail::makeVfs();
  detail::addVfsFile(*vfs, "scene.xml", xml);
  const detail::MujocoModelPtr model = detail::compileMjcf("scene.xml", vfs.get());
  ASSERT_EQ(model->nbody, 2);
  const Vec mujoco(model->body_ipos[3], model->body_ipos[4], model->body_ipos[5]);
  EXPECT_LT((centreOfMass(shapes) - mujoco).norm(), 1e-9) << mujoco.transpose();
}

TEST(CentreOfMass, NoVolumeIsAnError) {
  auto flat = std::make_shared<Mesh>();
  flat->vertices = {Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0), Vec(1, 1, 0)};
  Shape shape;
  shape.type = ShapeType::Mesh;
  shape.mesh = flat;
  try {
    centreOfMass({shape});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "centre of mass: the shapes enclose no volume");
  }
  // Beside a box it weighs nothing.
  EXPECT_LT(
      (centreOfMass({shape, at(Shape::box(Vec::Ones()), Vec(3, 0, 0))}) - Vec(3, 0, 0)).norm(),
      1e-15);
}

// ---- Boxes ----

TEST(RestingPoses, BoxSixFacesBySolidAngle) {
  const Vec size(0.2, 0.1, 0.05);
  const std::vector<RestingPose> poses = restingPoses({Shape::box(size)});
  ASSERT_EQ(poses.size(), 6u);
  EXPECT_NEAR(sumOf(poses), 1.0, 1e-12);
  // Closed form: a face of half sides a, b at distance d takes 4 atan(ab / (d sqrt(a²+b²+d²))).
  const Vec h = 0.5 * size;
  for (int k = 0; k < 3; ++k) {
    const double a = h[(k + 1) % 3], b = h[(k + 2) % 3], d = h[k];
    const double expected = std::atan(a * b / (d * std::sqrt(a * a + b * b + d * d))) / M_PI;
    for (double sign : {-1.0, 1.0}) {
      const RestingPose* p = poseWithNormal(poses, sign * Vec::Unit(k));
      ASSERT_NE(p, nullptr);
      EXPECT_NEAR(p->probability, expected, 1e-15);
      EXPECT_FALSE(p->rolling);
    }
  }
  // Monte Carlo: directions from the centre, each to the face it leaves the box through.
  std::map<int, double> hits;
  const std::vector<Vec> directions = randomDirections(1000000, 1);
  for (const Vec& d : directions) {
    int axis = 0;
    d.cwiseQuotient(h).cwiseAbs().maxCoeff(&axis);
    hits[d[axis] > 0.0 ? axis + 1 : -axis - 1] += 1.0 / static_cast<double>(directions.size());
  }
  for (const RestingPose& p : poses) {
    int axis = 0;
    p.normal.cwiseAbs().maxCoeff(&axis);
    EXPECT_NEAR(p.probability, hits[p.normal[axis] > 0.0 ? axis + 1 : -axis - 1], 0.005);
  }
  // The largest faces first; the two faces of an axis by their normals' x, y, z.
  EXPECT_EQ(poses[0].normal, Vec(0, 0, -1));
  EXPECT_EQ(poses[1].normal, Vec(0, 0, 1));
  EXPECT_EQ(poses[2].normal, Vec(0, -1, 0));
  EXPECT_EQ(poses[5].normal, Vec(1, 0, 0));
}

TEST(RestingPoses, OrientationPutsTheFaceDownAndBoundsFollow) {
  const Vec size(0.2, 0.1, 0.05);
  const std::vector<RestingPose> poses = restingPoses({Shape::box(size)});
  for (const RestingPose& p : poses) {
    EXPECT_LT((p.orientation * p.normal - Vec(0, 0, -1)).norm(), 1e-15);
    EXPECT_GE(p.orientation.w(), 0.0);
  }
  // Lying on its bottom: unturned; on its top: half a turn about x, x kept.
  const RestingPose* bottom = poseWithNormal(poses, Vec(0, 0, -1));
  EXPECT_LT(bottom->orientation.angularDistance(Eigen::Quaterniond::Identity()), 1e-15);
  const RestingPose* top = poseWithNormal(poses, Vec(0, 0, 1));
  EXPECT_LT(
      top->orientation.angularDistance(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Vec::UnitX()))),
      1e-15);
  // On its +x side: x down, the y and z extents horizontal.
  const RestingPose* side = poseWithNormal(poses, Vec(1, 0, 0));
  EXPECT_NEAR(side->bounds.bottomZ, -0.1, 1e-15);
  EXPECT_NEAR(side->bounds.topZ, 0.1, 1e-15);
  EXPECT_NEAR(side->bounds.horizontalRadius, std::hypot(0.05, 0.025), 1e-15);
  EXPECT_LT((side->orientation * Vec::UnitY() - Vec::UnitY()).norm(), 1e-15);
  const RestingPose* front = poseWithNormal(poses, Vec(0, -1, 0));
  EXPECT_NEAR(front->bounds.bottomZ, -0.05, 1e-15);
  EXPECT_NEAR(front->bounds.horizontalRadius, std::hypot(0.1, 0.025), 1e-15);
}

TEST(RestingPoses, BoxMeshThroughTheHullMatchesTheClosedForm) {
  // With its 12 triangles (a closed convex mesh is its own hull) and as vertices alone
  // (quickhull).
  const Vec size(0.2, 0.1, 0.05);
  const std::vector<RestingPose> exact = restingPoses({Shape::box(size)});
  Shape vertices = boxMesh(size);
  auto bare = std::make_shared<Mesh>(*vertices.mesh);
  bare->triangles.clear();
  vertices.mesh = bare;
  for (const Shape& mesh : {boxMesh(size), vertices}) {
    const std::vector<RestingPose> hull = restingPoses({mesh});
    ASSERT_EQ(hull.size(), exact.size());
    for (std::size_t i = 0; i < exact.size(); ++i) {
      EXPECT_NEAR(hull[i].probability, exact[i].probability, 1e-9);
      EXPECT_LT((hull[i].normal - exact[i].normal).norm(), 1e-12);
      EXPECT_LT(hull[i].orientation.angularDistance(exact[i].orientation), 1e-9);
      EXPECT_NEAR(hull[i].bounds.bottomZ, exact[i].bounds.bottomZ, 1e-12);
      EXPECT_FALSE(hull[i].rolling);
    }
  }
}

TEST(RestingPoses, PosedBoxTurnsItsFaces) {
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.5, Vec(1, 2, 3).normalized()));
  const std::vector<RestingPose> poses =
      restingPoses({at(Shape::box(Vec(0.2, 0.1, 0.05)), Vec(0.3, 0.1, 0.0), turn)});
  ASSERT_EQ(poses.size(), 6u);
  const RestingPose* p = poseWithNormal(poses, turn * Vec(0, 0, -1));
  ASSERT_NE(p, nullptr);
  EXPECT_NEAR(p->probability, restingPoses({Shape::box(Vec(0.2, 0.1, 0.05))})[0].probability,
              1e-15);
}

TEST(RestingPoses, ThinStripLiesFlat) {
  // 1 mm thick: its edges and ends are narrower than twice the margin, so not stable, and pass
  // their shares on to the flat sides.
  const std::vector<RestingPose> poses = restingPoses({Shape::box(Vec(0.001, 0.004, 0.2))});
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].normal, Vec(-1, 0, 0));
  EXPECT_EQ(poses[1].normal, Vec(1, 0, 0));
  EXPECT_NEAR(poses[0].probability, 0.5, 1e-15);
  RestingOptions noMargin;
  noMargin.margin = 0.0;
  EXPECT_EQ(restingPoses({Shape::box(Vec(0.001, 0.004, 0.2))}, noMargin).size(), 6u);
}

// ---- Round primitives ----

TEST(RestingPoses, CylinderCapsAndRollingSide) {
  const double r = 0.03, h = 0.06;
  const std::vector<RestingPose> caps = restingPoses({Shape::cylinder(r, 2 * h)});
  ASSERT_EQ(caps.size(), 2u);
  EXPECT_NEAR(caps[0].probability, 0.5, 1e-15);
  EXPECT_EQ(caps[0].normal, Vec(0, 0, -1));
  EXPECT_EQ(caps[1].normal, Vec(0, 0, 1));
  RestingOptions rolling;
  rolling.allowRolling = true;
  const std::vector<RestingPose> all = restingPoses({Shape::cylinder(r, 2 * h)}, rolling);
  ASSERT_EQ(all.size(), 3u);
  const double side = h / std::hypot(h, r);
  EXPECT_NEAR(sumOf(all), 1.0, 1e-15);
  const RestingPose& lying = all[0];  // h > r: the side is the likeliest
  EXPECT_TRUE(lying.rolling);
  EXPECT_NEAR(lying.probability, side, 1e-15);
  EXPECT_NEAR(all[1].probability, 0.5 * (1.0 - side), 1e-15);
  EXPECT_FALSE(all[1].rolling);
  // On its side: the axis horizontal, resting on the rim.
  EXPECT_NEAR((lying.orientation * Vec::UnitZ()).z(), 0.0, 1e-15);
  EXPECT_NEAR(lying.bounds.bottomZ, -r, 1e-12);
  EXPECT_NEAR(lying.bounds.topZ, r, 1e-12);
  EXPECT_NEAR(lying.bounds.horizontalRadius, std::hypot(h, r), 1e-12);
}

TEST(RestingPoses, CylinderCapsMatchMonteCarlo) {
  const double r = 0.05, h = 0.02;
  RestingOptions rolling;
  rolling.allowRolling = true;
  const std::vector<RestingPose> poses = restingPoses({Shape::cylinder(r, 2 * h)}, rolling);
  double capHits = 0.0;
  const std::vector<Vec> directions = randomDirections(200000, 2);
  for (const Vec& d : directions) {
    // Through a cap when the ray reaches the cap's plane within the radius.
    if (std::abs(d.z()) > 0.0 && std::hypot(d.x(), d.y()) * h / std::abs(d.z()) <= r) {
      capHits += 0.5 / static_cast<double>(directions.size());
    }
  }
  EXPECT_NEAR(poseWithNormal(poses, Vec(0, 0, -1))->probability, capHits, 0.005);
}

TEST(RestingPoses, SphereAndCapsule) {
  RestingOptions rolling;
  rolling.allowRolling = true;
  EXPECT_TRUE(restingPoses({Shape::sphere(0.05)}).empty());
  EXPECT_TRUE(restingPoses({Shape::sphere(0.05)}, rolling).empty());
  EXPECT_TRUE(restingPoses({Shape::capsule(0.02, 0.1)}).empty());
  const std::vector<RestingPose> capsule = restingPoses({Shape::capsule(0.02, 0.1)}, rolling);
  ASSERT_EQ(capsule.size(), 1u);
  EXPECT_TRUE(capsule[0].rolling);
  EXPECT_EQ(capsule[0].probability, 1.0);
  EXPECT_NEAR(capsule[0].bounds.bottomZ, -0.02, 1e-12);
}

TEST(RestingPoses, CompositeCylinderRollsLikeOne) {
  // A bottle: a body and a narrower neck, through the hull. Its sides are polygons, but the
  // true contact of each is a line: no stable side, the caps take it all unless rolling.
  const std::vector<Shape> bottle = {Shape::cylinder(0.04, 0.16),
                                     at(Shape::cylinder(0.015, 0.06), Vec(0, 0, 0.1))};
  const std::vector<RestingPose> upright = restingPoses(bottle);
  ASSERT_EQ(upright.size(), 2u);
  EXPECT_NEAR(std::abs(upright[0].normal.z()), 1.0, 1e-9);
  EXPECT_NEAR(std::abs(upright[1].normal.z()), 1.0, 1e-9);
  RestingOptions rolling;
  rolling.allowRolling = true;
  const std::vector<RestingPose> all = restingPoses(bottle, rolling);
  ASSERT_EQ(all.size(), 3u);
  int rollingPoses = 0;
  for (const RestingPose& p : all) {
    if (p.rolling) {
      ++rollingPoses;
      EXPECT_NEAR(p.normal.z(), 0.0, 1e-9);
      EXPECT_GT(p.probability, 0.5);
    }
  }
  EXPECT_EQ(rollingPoses, 1);
}

// ---- Hull with toppling ----

/// Drops the hull of @p r's object in @p count random directions: the face each direction
/// leaves through, then toppling worked out here from the polygons alone (across the edge the
/// centre of mass lies farthest beyond, to the face that shares that edge) until a face holds
/// it by the margin. The share of each final face, by face index.
std::map<int, double> dropWithToppling(const detail::RestingHull& r, double margin,
                                       std::size_t count) {
  const detail::ConvexHull& hull = r.hull;
  const Vec& c = r.centreOfMass;
  auto corners = [&](int f) {
    std::vector<Vec> out;
    for (int k = hull.start[f]; k < hull.start[f + 1]; ++k) {
      out.push_back(r.input.points[static_cast<std::size_t>(hull.vertices[k])]);
    }
    return out;
  };
  const int faces = static_cast<int>(hull.faceCount());
  std::vector<int> final(static_cast<std::size_t>(faces), -1);
  for (int f = 0; f < faces; ++f) {
    int g = f;
    for (int step = 0; step <= faces; ++step) {
      const std::vector<Vec> p = corners(g);
      const Vec& n = hull.normals[static_cast<std::size_t>(g)];
      double farthest = -1e300;
      std::size_t edge = 0;
      for (std::size_t k = 0; k < p.size(); ++k) {
        const Vec out = (p[(k + 1) % p.size()] - p[k]).cross(n).normalized();
        if (out.dot(c - p[k]) > farthest) {
          farthest = out.dot(c - p[k]);
          edge = k;
        }
      }
      if (-farthest >= margin) {
        break;
      }
      const Vec a = p[edge], b = p[(edge + 1) % p.size()];
      for (int h = 0; h < faces; ++h) {
        int shared = 0;
        for (const Vec& q : corners(h)) {
          shared += (q == a || q == b) ? 1 : 0;
        }
        if (h != g && shared == 2) {
          g = h;
          break;
        }
      }
    }
    final[static_cast<std::size_t>(f)] = g;
  }
  std::map<int, double> share;
  for (const Vec& d : randomDirections(count, 3)) {
    int hit = -1;
    double nearest = 1e300;
    for (int f = 0; f < faces; ++f) {
      const Vec& n = hull.normals[static_cast<std::size_t>(f)];
      const double along = n.dot(d);
      const double t = along > 0.0 ? n.dot(corners(f)[0] - c) / along : 1e300;
      if (t < nearest) {
        nearest = t;
        hit = f;
      }
    }
    share[final[static_cast<std::size_t>(hit)]] += 1.0 / static_cast<double>(count);
  }
  return share;
}

void expectToppling(const std::vector<Shape>& shapes, const std::string& what) {
  SCOPED_TRACE(what);
  const RestingOptions options;
  const detail::RestingHull r = detail::restingHull(shapes, options);
  double total = 0.0, unstableShare = 0.0;
  int unstable = 0;
  for (std::size_t f = 0; f < r.share.size(); ++f) {
    total += r.share[f];
    if (r.next[f] >= 0) {
      ++unstable;
      unstableShare += r.share[f];
      // Its share ends on a stable face, not on a rolling sink.
      const detail::RestingHull::Sink& sink = r.sinks[static_cast<std::size_t>(r.sink[f])];
      EXPECT_FALSE(sink.rolling);
      EXPECT_LT(r.next[static_cast<std::size_t>(sink.face)], 0);
    }
  }
  EXPECT_NEAR(total, 1.0, 1e-12);
  EXPECT_GE(unstable, 2);  // the two short ends of the L's arms
  EXPECT_GT(unstableShare, 0.01);
  const std::vector<RestingPose> poses = restingPoses(shapes, options);
  EXPECT_NEAR(sumOf(poses), 1.0, 1e-12);
  EXPECT_EQ(poses.size(), r.sinks.size());
  const std::map<int, double> dropped = dropWithToppling(r, options.margin, 200000);
  for (const RestingPose& p : poses) {
    double expected = -1.0;
    for (const auto& [face, share] : dropped) {
      if ((r.hull.normals[static_cast<std::size_t>(face)] - p.normal).norm() < 1e-9) {
        expected = share;
      }
    }
    EXPECT_NEAR(p.probability, expected, 0.01) << p.normal.transpose();
  }
}

TEST(RestingPoses, LShapedCompositeTopplesOffItsArmEnds) {
  expectToppling({Shape::box(Vec(0.08, 0.02, 0.03)),
                  at(Shape::box(Vec(0.02, 0.06, 0.03)), Vec(-0.03, 0.04, 0.0))},
                 "composite");
}

TEST(RestingPoses, LBlockMeshTopplesOffItsArmEnds) {
  expectToppling({lBlockMesh()}, "l_block.stl");
  // Its arm ends (x = 0.04 and y = 0.04) are not poses; the diagonal of its hull is.
  const std::vector<RestingPose> poses = restingPoses({lBlockMesh()});
  EXPECT_EQ(poses.size(), 5u);
  EXPECT_EQ(poseWithNormal(poses, Vec(1, 0, 0)), nullptr);
  EXPECT_EQ(poseWithNormal(poses, Vec(0, 1, 0)), nullptr);
  EXPECT_NE(poseWithNormal(poses, Vec(1, 1, 0).normalized()), nullptr);
}

TEST(RestingPoses, MugLiesOnItsHandle) {
  const std::vector<Shape> mug = {Shape::cylinder(0.04, 0.1),
                                  at(Shape::box(Vec(0.03, 0.012, 0.06)), Vec(0.055, 0, 0))};
  RestingOptions rolling;
  rolling.allowRolling = true;
  for (const RestingOptions& options : {RestingOptions(), rolling}) {
    const std::vector<RestingPose> poses = restingPoses(mug, options);
    EXPECT_NEAR(sumOf(poses), 1.0, 1e-12);
    int onHandle = 0;
    for (const RestingPose& p : poses) {
      EXPECT_FALSE(p.rolling);  // the centre of mass lies towards the handle: it rolls onto it
      if (p.normal.x() > 0.5 && std::abs(p.normal.z()) < 1e-9) {
        ++onHandle;
        EXPECT_GT(p.probability, 0.01);
        EXPECT_LT(p.bounds.bottomZ, -0.05);  // the handle reaches farther than the body
      }
    }
    EXPECT_GE(onHandle, 1);
    EXPECT_NE(poseWithNormal(poses, Vec(0, 0, -1)), nullptr);
  }
}

// ---- Determinism and degenerate input ----

TEST(RestingPoses, SameResultEveryTime) {
  const std::vector<Shape> shapes = {lBlockMesh(), at(Shape::sphere(0.02), Vec(0.02, 0.0, 0.02))};
  const std::vector<RestingPose> a = restingPoses(shapes), b = restingPoses(shapes);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].probability, b[i].probability);
    EXPECT_EQ(a[i].orientation.coeffs(), b[i].orientation.coeffs());
    EXPECT_EQ(a[i].bounds.horizontalRadius, b[i].bounds.horizontalRadius);
  }
}

std::string restingError(const std::vector<Shape>& shapes,
                         const RestingOptions& options = RestingOptions()) {
  try {
    restingPoses(shapes, options);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(RestingPoses, DegenerateGeometryIsAClearError) {
  auto flat = std::make_shared<Mesh>();
  auto line = std::make_shared<Mesh>();
  for (int i = 0; i < 6; ++i) {
    flat->vertices.emplace_back(0.01 * (i % 3), 0.01 * (i / 3), 0.0);
    line->vertices.emplace_back(0.01 * i, 0.0, 0.0);
  }
  Shape shape;
  shape.type = ShapeType::Mesh;
  shape.mesh = flat;
  EXPECT_EQ(restingError({shape}), "convex hull: all 6 points lie on a plane, they span no volume");
  shape.mesh = line;
  EXPECT_EQ(restingError({shape}), "convex hull: all 6 points lie on a line, they span no volume");
  EXPECT_EQ(restingError({}), "resting poses: the object has no shapes");
  RestingOptions negative;
  negative.margin = -1.0;
  EXPECT_EQ(restingError({Shape::box(Vec::Ones())}, negative),
            "resting poses: the margin must be finite and at least 0 m, got -1");
}

}  // namespace
}  // namespace placement_samplers
