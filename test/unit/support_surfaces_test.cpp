// Support surfaces: primitives' faces and caps, the package's bin, shelf, counter and cabinet,
// merging, cuts, clearance, dropping, order, moving, a 100,000-triangle mesh and broken meshes.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "placement_samplers/geometry/mesh_loader.hpp"
#include "placement_samplers/geometry/mjcf_geometry.hpp"
#include "placement_samplers/geometry/support_surfaces.hpp"
#include "placement_samplers/geometry/urdf_geometry.hpp"
#include "slab_mesh.hpp"

namespace placement_samplers {
namespace {

using Ring = std::vector<Eigen::Vector2d>;
const std::string kSource = PLACEMENT_SAMPLERS_SOURCE_DIR;
constexpr double kInf = std::numeric_limits<double>::infinity();

Shape boxAt(const Eigen::Vector3d& size, const Eigen::Vector3d& position,
            const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity()) {
  Shape shape = Shape::box(size);
  shape.pose.linear() = rotation;
  shape.pose.translation() = position;
  return shape;
}

Shape withPose(Shape shape, const Eigen::Vector3d& position,
               const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity()) {
  shape.pose.linear() = rotation;
  shape.pose.translation() = position;
  return shape;
}

Shape meshShape(Mesh mesh) {
  Shape shape;
  shape.type = ShapeType::Mesh;
  shape.mesh = std::make_shared<const Mesh>(std::move(mesh));
  return shape;
}

SurfaceSearch find(const std::vector<Shape>& shapes,
                   const SurfaceOptions& options = SurfaceOptions()) {
  return findSupportSurfaces(shapes, Eigen::Isometry3d::Identity(), options);
}

double signedArea(const Ring& ring) {
  double twice = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Eigen::Vector2d& a = ring[i];
    const Eigen::Vector2d& b = ring[(i + 1) % ring.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}

Ring rectangle(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

/// @p ring is @p expected (same vertices, same cyclic order, any first vertex) within @p tol.
::testing::AssertionResult sameRing(const Ring& ring, const Ring& expected, double tol) {
  if (ring.size() != expected.size()) {
    return ::testing::AssertionFailure()
           << ring.size() << " vertices, expected " << expected.size();
  }
  for (std::size_t shift = 0; shift < ring.size(); ++shift) {
    bool all = true;
    for (std::size_t i = 0; i < ring.size() && all; ++i) {
      all = (ring[(i + shift) % ring.size()] - expected[i]).cwiseAbs().maxCoeff() <= tol;
    }
    if (all) {
      return ::testing::AssertionSuccess();
    }
  }
  ::testing::AssertionResult failure = ::testing::AssertionFailure();
  for (const Eigen::Vector2d& p : ring) {
    failure << "(" << p.x() << ", " << p.y() << ") ";
  }
  return failure;
}

/// Every ring oriented as the header says: outline counter-clockwise, holes clockwise; the
/// area the outline's minus the holes'.
void expectWellFormed(const SupportSurface& s) {
  EXPECT_GT(signedArea(s.outer), 0.0);
  double area = signedArea(s.outer);
  for (const Ring& hole : s.holes) {
    EXPECT_LT(signedArea(hole), 0.0);
    area += signedArea(hole);
  }
  EXPECT_NEAR(s.area, area, 1e-12);
}

std::vector<Shape> urdfShapes(const std::string& file) {
  MeshLoader meshes;
  return urdfCollisionShapes(readTextFile(kSource + "/urdf/" + file), "", meshes,
                             kSource + "/urdf");
}

TEST(SupportSurfaces, BoxTopIsItsRectangle) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(1.0, 2.0, 0.5);
  const SurfaceSearch search = findSupportSurfaces(
      {boxAt(Eigen::Vector3d(0.4, 0.3, 0.2), Eigen::Vector3d(0, 0, 0.1))}, pose);
  ASSERT_EQ(search.surfaces.size(), 1u);
  const SupportSurface& top = search.surfaces[0];
  EXPECT_NEAR(top.z, 0.7, 1e-12);
  EXPECT_TRUE(sameRing(top.outer, rectangle(0.8, 1.85, 1.2, 2.15), 1e-12));
  EXPECT_TRUE(top.holes.empty());
  EXPECT_NEAR(top.area, 0.12, 1e-12);
  EXPECT_EQ(top.clearance, kInf);
  EXPECT_EQ(search.largestDroppedArea, 0.0);
  expectWellFormed(top);
}

TEST(SupportSurfaces, TurnedBoxHasTheFaceThatPointsUp) {
  const Eigen::Vector3d size(0.1, 0.2, 0.3);
  // About x by 90 degrees: the local y axis points up, the local z axis along -y.
  const Eigen::Matrix3d aboutX = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).matrix();
  SurfaceSearch search = find({boxAt(size, Eigen::Vector3d::Zero(), aboutX)});
  ASSERT_EQ(search.surfaces.size(), 1u);
  EXPECT_NEAR(search.surfaces[0].z, 0.1, 1e-12);
  EXPECT_TRUE(sameRing(search.surfaces[0].outer, rectangle(-0.05, -0.15, 0.05, 0.15), 1e-12));
  EXPECT_NEAR(search.surfaces[0].area, 0.03, 1e-12);
  // About y by -90 degrees: the local x axis points up.
  const Eigen::Matrix3d aboutY = Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitY()).matrix();
  search = find({boxAt(size, Eigen::Vector3d::Zero(), aboutY)});
  ASSERT_EQ(search.surfaces.size(), 1u);
  EXPECT_NEAR(search.surfaces[0].z, 0.05, 1e-12);
  EXPECT_TRUE(sameRing(search.surfaces[0].outer, rectangle(-0.15, -0.1, 0.15, 0.1), 1e-12));
  expectWellFormed(search.surfaces[0]);
}

TEST(SupportSurfaces, TiltedBoxWithinTheToleranceOnlyHasItsHighestPointAsHeight) {
  const Eigen::Vector3d size(0.1, 0.2, 0.3);
  const auto tilted = [&](double angle) {
    return boxAt(size, Eigen::Vector3d::Zero(),
                 Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()).matrix());
  };
  EXPECT_TRUE(find({tilted(0.2)}).surfaces.empty());
  EXPECT_TRUE(find({tilted(0.2)}, SurfaceOptions{0.19, 0.0025, 1e-3}).surfaces.empty());
  ASSERT_EQ(find({tilted(0.2)}, SurfaceOptions{0.21, 0.0025, 1e-3}).surfaces.size(), 1u);
  const SurfaceSearch search = find({tilted(0.05)});
  ASSERT_EQ(search.surfaces.size(), 1u);
  const double c = std::cos(0.05);
  const double s = std::sin(0.05);
  EXPECT_NEAR(search.surfaces[0].z, 0.1 * s + 0.15 * c, 1e-12);
  EXPECT_NEAR(search.surfaces[0].area, 0.1 * 0.2 * c, 1e-12);
  EXPECT_TRUE(sameRing(search.surfaces[0].outer,
                       rectangle(-0.05, -0.1 * c - 0.15 * s, 0.05, 0.1 * c - 0.15 * s), 1e-12));
}

TEST(SupportSurfaces, CylinderCapIsAnInscribedPolygon) {
  const Eigen::Vector2d centre(0.5, -0.5);
  for (double flip : {0.0, M_PI}) {
    const Shape cylinder = withPose(Shape::cylinder(0.1, 0.2), Eigen::Vector3d(0.5, -0.5, 0.1),
                                    Eigen::AngleAxisd(flip, Eigen::Vector3d::UnitX()).matrix());
    const SurfaceSearch search = find({cylinder});
    ASSERT_EQ(search.surfaces.size(), 1u) << flip;
    const SupportSurface& cap = search.surfaces[0];
    EXPECT_NEAR(cap.z, 0.2, 1e-12);
    ASSERT_EQ(cap.outer.size(), 64u);
    for (const Eigen::Vector2d& p : cap.outer) {
      EXPECT_NEAR((p - centre).norm(), 0.1, 1e-12);
    }
    EXPECT_NEAR(cap.area, 32 * 0.01 * std::sin(2 * M_PI / 64), 1e-12);
    EXPECT_GT(cap.area, 0.998 * M_PI * 0.01);
    EXPECT_LT(cap.area, M_PI * 0.01);
    expectWellFormed(cap);
  }
}

TEST(SupportSurfaces, SpheresAndCapsulesHaveNone) {
  EXPECT_TRUE(find({Shape::sphere(0.5)}).surfaces.empty());
  EXPECT_TRUE(find({Shape::capsule(0.2, 1.0)}).surfaces.empty());
  const Eigen::Matrix3d lying = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).matrix();
  EXPECT_TRUE(
      find({withPose(Shape::capsule(0.2, 1.0), Eigen::Vector3d::Zero(), lying)}).surfaces.empty());
  EXPECT_TRUE(find({}).surfaces.empty());
}

TEST(SupportSurfaces, BinFloorIsTheInsideAndItsRimOneRing) {
  const SurfaceSearch search = find(urdfShapes("bin.urdf"));
  ASSERT_EQ(search.surfaces.size(), 2u);
  const SupportSurface& floor = search.surfaces[0];
  EXPECT_NEAR(floor.z, 0.01, 1e-12);
  EXPECT_TRUE(sameRing(floor.outer, rectangle(-0.19, -0.24, 0.19, 0.24), 1e-12));
  EXPECT_TRUE(floor.holes.empty());
  EXPECT_NEAR(floor.area, 0.38 * 0.48, 1e-12);
  EXPECT_EQ(floor.clearance, kInf);
  // The four wall tops touch at the corners and are one surface: a ring around the inside.
  const SupportSurface& rim = search.surfaces[1];
  EXPECT_NEAR(rim.z, 0.10, 1e-12);
  EXPECT_TRUE(sameRing(rim.outer, rectangle(-0.2, -0.25, 0.2, 0.25), 1e-12));
  ASSERT_EQ(rim.holes.size(), 1u);
  Ring inside = rectangle(-0.19, -0.24, 0.19, 0.24);
  std::reverse(inside.begin(), inside.end());
  EXPECT_TRUE(sameRing(rim.holes[0], inside, 1e-12));
  EXPECT_NEAR(rim.area, 2 * 0.005 + 2 * 0.0038, 1e-12);
  expectWellFormed(floor);
  expectWellFormed(rim);
}

void expectShelfBoards(const SurfaceSearch& search) {
  ASSERT_EQ(search.surfaces.size(), 5u);
  const double tops[] = {0.02, 0.28, 0.54};
  for (int i = 0; i < 3; ++i) {
    const SupportSurface& board = search.surfaces[i];
    EXPECT_NEAR(board.z, tops[i], 1e-12) << i;
    EXPECT_TRUE(sameRing(board.outer, rectangle(-0.3, -0.15, 0.3, 0.15), 1e-12)) << i;
    EXPECT_TRUE(board.holes.empty());
    EXPECT_NEAR(board.area, 0.18, 1e-12);
    if (i < 2) {
      EXPECT_NEAR(board.clearance, tops[i + 1] - 0.02 - tops[i], 1e-12) << i;
    } else {
      EXPECT_EQ(board.clearance, kInf);
    }
  }
  EXPECT_NEAR(search.surfaces[3].z, 0.6, 1e-12);
  EXPECT_TRUE(sameRing(search.surfaces[3].outer, rectangle(-0.32, -0.15, -0.3, 0.15), 1e-12));
  EXPECT_NEAR(search.surfaces[4].z, 0.6, 1e-12);
  EXPECT_TRUE(sameRing(search.surfaces[4].outer, rectangle(0.3, -0.15, 0.32, 0.15), 1e-12));
}

TEST(SupportSurfaces, ShelfBoardsWithTheClearanceUpToTheNextBoard) {
  expectShelfBoards(find(urdfShapes("shelf.urdf")));
}

TEST(SupportSurfaces, ShelfPanelsThroughTheBoardsAreCutOut) {
  std::vector<Shape> shapes;
  for (double top : {0.02, 0.28, 0.54}) {
    shapes.push_back(boxAt(Eigen::Vector3d(0.64, 0.3, 0.02), Eigen::Vector3d(0, 0, top - 0.01)));
  }
  for (double x : {-0.31, 0.31}) {
    shapes.push_back(boxAt(Eigen::Vector3d(0.02, 0.3, 0.6), Eigen::Vector3d(x, 0, 0.3)));
  }
  expectShelfBoards(find(shapes));
}

TEST(SupportSurfaces, CounterMeshKeepsItsSinkAsAHole) {
  const Mesh counter =
      loadMeshFile(kSource + "/meshes/counter.stl", Eigen::Vector3d::Ones(), "meshes/counter.stl");
  const SurfaceSearch search = find({meshShape(counter)});
  ASSERT_EQ(search.surfaces.size(), 2u);
  const SupportSurface& basin = search.surfaces[0];
  EXPECT_NEAR(basin.z, -0.18, 1e-6);
  EXPECT_TRUE(sameRing(basin.outer, rectangle(0.1, -0.15, 0.5, 0.15), 1e-6));
  EXPECT_TRUE(basin.holes.empty());
  EXPECT_EQ(basin.clearance, kInf);
  const SupportSurface& top = search.surfaces[1];
  EXPECT_EQ(top.z, 0.0);
  EXPECT_TRUE(sameRing(top.outer, rectangle(-0.6, -0.3, 0.6, 0.3), 1e-6));
  ASSERT_EQ(top.holes.size(), 1u);
  EXPECT_NEAR(signedArea(top.holes[0]), -0.12, 1e-6);
  EXPECT_NEAR(top.area, 0.6, 1e-6);
  EXPECT_EQ(top.clearance, kInf);
  expectWellFormed(basin);
  expectWellFormed(top);

  // A box level with the counter, touching its end: one surface, the sink still a hole.
  const SurfaceSearch merged =
      find({meshShape(counter), boxAt(Eigen::Vector3d(0.4, 0.6, 0.04), {0.8, 0.0, -0.02})});
  ASSERT_EQ(merged.surfaces.size(), 2u);
  // (The mesh's float coordinates differ from the box's by 1e-8: steps of that size remain.)
  const SupportSurface& longer = merged.surfaces[1];
  double minX = kInf, maxX = -kInf;
  for (const Eigen::Vector2d& p : longer.outer) {
    minX = std::min(minX, p.x());
    maxX = std::max(maxX, p.x());
  }
  EXPECT_NEAR(minX, -0.6, 1e-6);
  EXPECT_NEAR(maxX, 1.0, 1e-12);
  ASSERT_EQ(longer.holes.size(), 1u);
  EXPECT_NEAR(signedArea(longer.holes[0]), -0.12, 1e-6);
  EXPECT_NEAR(longer.area, 0.84, 1e-6);
  expectWellFormed(longer);
}

TEST(SupportSurfaces, TouchingTopsAtOneHeightAreOneSurface) {
  const Shape a = boxAt(Eigen::Vector3d(1, 1, 0.5), Eigen::Vector3d(0.5, 0.5, 0.25));
  const SurfaceSearch one =
      find({a, boxAt(Eigen::Vector3d(1, 0.5, 0.5), Eigen::Vector3d(1.5, 0.25, 0.25))});
  ASSERT_EQ(one.surfaces.size(), 1u);
  EXPECT_TRUE(
      sameRing(one.surfaces[0].outer, {{0, 0}, {2, 0}, {2, 0.5}, {1, 0.5}, {1, 1}, {0, 1}}, 1e-12));
  EXPECT_NEAR(one.surfaces[0].area, 1.5, 1e-12);
  // One higher: two surfaces, neither cut (the higher box only touches the lower top).
  const SurfaceSearch two =
      find({a, boxAt(Eigen::Vector3d(1, 0.5, 0.6), Eigen::Vector3d(1.5, 0.25, 0.3))});
  ASSERT_EQ(two.surfaces.size(), 2u);
  EXPECT_NEAR(two.surfaces[0].area, 1.0, 1e-12);
  EXPECT_NEAR(two.surfaces[1].z, 0.6, 1e-12);
  EXPECT_NEAR(two.surfaces[1].area, 0.5, 1e-12);
}

TEST(SupportSurfaces, StandingGeometryIsCutOutConservatively) {
  const Shape board = boxAt(Eigen::Vector3d(1, 1, 0.02), Eigen::Vector3d(0, 0, 0.01));
  const Shape post = withPose(Shape::cylinder(0.05, 0.3), Eigen::Vector3d(0.2, 0.2, 0.17));
  const Shape block = boxAt(Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector3d(-0.2, -0.2, 0.07));
  // Within the standing gap above the board: cut out too.
  const Shape hovering =
      boxAt(Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector3d(0.2, -0.2, 0.0705 + 0.0004));
  const SurfaceSearch search = find({board, post, block, hovering});
  ASSERT_EQ(search.surfaces.size(), 4u);
  const SupportSurface& floor = search.surfaces[0];
  EXPECT_NEAR(floor.z, 0.02, 1e-12);
  ASSERT_EQ(floor.holes.size(), 3u);
  // The post as the circumscribed 32-gon: never smaller than the post.
  const double postCut = 32 * 0.05 * 0.05 * std::tan(M_PI / 32);
  EXPECT_NEAR(floor.area, 1.0 - 0.01 - 0.01 - postCut, 1e-12);
  EXPECT_EQ(floor.clearance, kInf);
  EXPECT_NEAR(search.surfaces[1].z, 0.12, 1e-12);    // the block's top
  EXPECT_NEAR(search.surfaces[2].z, 0.1209, 1e-12);  // the hovering block's top
  EXPECT_NEAR(search.surfaces[3].z, 0.32, 1e-12);    // the post's cap
  expectWellFormed(floor);
}

TEST(SupportSurfaces, ClearanceFromOverlappingGeometryAboveOnly) {
  const Shape board = boxAt(Eigen::Vector3d(1, 1, 0.02), Eigen::Vector3d(0, 0, 0.01));
  // Beyond the standing gap: not cut, it bounds the clearance.
  const Shape low = boxAt(Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector3d(0.2, -0.2, 0.072));
  // Higher, half over the board.
  const Shape roof = boxAt(Eigen::Vector3d(1, 1, 0.02), Eigen::Vector3d(0.5, 0, 0.51));
  // Lower, but beside the board: its footprint only touches the board's.
  const Shape beside = boxAt(Eigen::Vector3d(0.2, 1, 0.02), Eigen::Vector3d(0.6, 0, 0.3));
  SurfaceSearch search = find({board, roof, beside});
  ASSERT_FALSE(search.surfaces.empty());
  EXPECT_TRUE(search.surfaces[0].holes.empty());
  EXPECT_NEAR(search.surfaces[0].clearance, 0.48, 1e-12);
  search = find({board, roof, beside, low});
  ASSERT_FALSE(search.surfaces.empty());
  EXPECT_TRUE(search.surfaces[0].holes.empty());
  EXPECT_NEAR(search.surfaces[0].clearance, 0.002, 1e-12);
}

TEST(SupportSurfaces, ClosedMeshStandingOnABoardIsCutOutByItsSection) {
  const Shape board = boxAt(Eigen::Vector3d(1, 1, 0.02), Eigen::Vector3d(0, 0, 0.01));
  // A 0.2 x 0.1 block, 0.3 high, standing on the board: its sides have no footprint of their
  // own; its cross-section just above the board is what stands there.
  Shape block = meshShape(test::makeSlabMesh(0.2, 0.1, 0.0, 0.3, 3));
  block.pose.translation() = Eigen::Vector3d(-0.1, 0.2, 0.02);
  const SurfaceSearch search = find({board, block});
  ASSERT_EQ(search.surfaces.size(), 2u);
  ASSERT_EQ(search.surfaces[0].holes.size(), 1u);
  Ring hole = rectangle(-0.2, 0.15, 0.0, 0.25);
  std::reverse(hole.begin(), hole.end());
  EXPECT_TRUE(sameRing(search.surfaces[0].holes[0], hole, 1e-12));
  EXPECT_NEAR(search.surfaces[0].area, 0.98, 1e-12);
  EXPECT_NEAR(search.surfaces[1].z, 0.32, 1e-12);
  EXPECT_NEAR(search.surfaces[1].area, 0.02, 1e-12);
}

TEST(SupportSurfaces, SmallSurfacesAreDroppedAndTheLargestRemembered) {
  const std::vector<Shape> shapes = {
      boxAt(Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector3d(0, 0, 0.05)),     // 0.01
      boxAt(Eigen::Vector3d(0.04, 0.05, 0.1), Eigen::Vector3d(1, 0, 0.05)),   // 0.002
      boxAt(Eigen::Vector3d(0.02, 0.05, 0.1), Eigen::Vector3d(2, 0, 0.05))};  // 0.001
  SurfaceSearch search = find(shapes);
  ASSERT_EQ(search.surfaces.size(), 1u);
  EXPECT_NEAR(search.surfaces[0].area, 0.01, 1e-12);
  EXPECT_NEAR(search.largestDroppedArea, 0.002, 1e-12);
  SurfaceOptions options;
  options.minArea = 0.02;
  search = find(shapes, options);
  EXPECT_TRUE(search.surfaces.empty());
  EXPECT_NEAR(search.largestDroppedArea, 0.01, 1e-12);
  options.minArea = 0.0;
  search = find(shapes, options);
  EXPECT_EQ(search.surfaces.size(), 3u);
  EXPECT_EQ(search.largestDroppedArea, 0.0);
  // What a cut leaves counts: a board cut in two pieces of 0.0024 and 0.0016.
  options.minArea = 0.0025;
  search = find({boxAt(Eigen::Vector3d(0.1, 0.04, 0.02), Eigen::Vector3d(0, 0, 0.01)),
                 boxAt(Eigen::Vector3d(0.02, 0.1, 0.3), Eigen::Vector3d(0.02, 0, 0.15))},
                options);
  EXPECT_TRUE(search.surfaces.empty());  // the panel's own top (0.002) is too small as well
  EXPECT_NEAR(search.largestDroppedArea, 0.0024, 1e-12);
}

TEST(SupportSurfaces, SortedByHeightThenLowestXVertex) {
  const Eigen::Vector3d size(0.1, 0.1, 0.1);
  const SurfaceSearch search = find({
      boxAt(size, Eigen::Vector3d(1, 0, 0.05)),              // z 0.1, x 0.95
      boxAt(size, Eigen::Vector3d(-1, 0.5, 0.05)),           // z 0.1, x -1.05, y 0.45
      boxAt(size, Eigen::Vector3d(5, 0, 0.0)),               // z 0.05
      boxAt(size, Eigen::Vector3d(-1, -0.5, 0.05)),          // z 0.1, x -1.05, y -0.55
      boxAt(size, Eigen::Vector3d(-1.0, 2.0, 0.05 + 1e-9)),  // level within 1e-6: z 0.1 + 1e-9
  });
  ASSERT_EQ(search.surfaces.size(), 5u);
  EXPECT_NEAR(search.surfaces[0].z, 0.05, 1e-12);
  EXPECT_NEAR(search.surfaces[1].outer[0].y() + search.surfaces[1].outer[2].y(), -1.0, 1e-9);
  EXPECT_NEAR(search.surfaces[2].outer[0].y() + search.surfaces[2].outer[2].y(), 1.0, 1e-9);
  EXPECT_NEAR(search.surfaces[3].outer[0].y() + search.surfaces[3].outer[2].y(), 4.0, 1e-9);
  EXPECT_NEAR(search.surfaces[4].outer[0].x() + search.surfaces[4].outer[2].x(), 2.0, 1e-9);
  // Tops level within 1e-6 are one height: the highest of them.
  for (int i = 1; i < 5; ++i) {
    EXPECT_NEAR(search.surfaces[i].z, 0.1 + 1e-9, 1e-15);
    EXPECT_EQ(search.surfaces[i].z, search.surfaces[1].z);
  }
}

TEST(SupportSurfaces, MovedSurfaceTurnsAboutZThenShifts) {
  SupportSurface surface;
  surface.z = 0.5;
  surface.outer = rectangle(0, 0, 2, 1);
  surface.holes = {{{0.5, 0.5}, {0.5, 0.7}, {0.7, 0.7}, {0.7, 0.5}}};
  surface.area = 1.96;
  surface.clearance = 0.3;
  const SupportSurface moved = movedSurface(surface, M_PI / 2, Eigen::Vector3d(1, 2, 3));
  EXPECT_NEAR(moved.z, 3.5, 1e-12);
  EXPECT_TRUE(sameRing(moved.outer, {{1, 2}, {1, 4}, {0, 4}, {0, 2}}, 1e-12));
  ASSERT_EQ(moved.holes.size(), 1u);
  EXPECT_TRUE(sameRing(moved.holes[0], {{0.5, 2.5}, {0.3, 2.5}, {0.3, 2.7}, {0.5, 2.7}}, 1e-12));
  EXPECT_EQ(moved.area, 1.96);
  EXPECT_EQ(moved.clearance, 0.3);
  expectWellFormed(moved);
}

TEST(SupportSurfaces, HundredThousandTrianglesGiveOneRectangle) {
  const Mesh slab = test::makeSlabMesh(1.2, 0.8, -0.05, 0.05, 222);
  ASSERT_GE(slab.triangles.size(), 100000u);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0.3, 0.0, 1.0);
  const SurfaceSearch search = findSupportSurfaces({meshShape(slab)}, pose);
  ASSERT_EQ(search.surfaces.size(), 1u);
  EXPECT_NEAR(search.surfaces[0].z, 1.05, 1e-12);
  EXPECT_TRUE(sameRing(search.surfaces[0].outer, rectangle(-0.3, -0.4, 0.9, 0.4), 1e-12));
  EXPECT_TRUE(search.surfaces[0].holes.empty());
  EXPECT_NEAR(search.surfaces[0].area, 0.96, 1e-12);
  EXPECT_EQ(search.surfaces[0].clearance, kInf);
}

TEST(SupportSurfaces, CabinetShelvesInsideTheCarcass) {
  const MjcfObject cabinet = loadMjcfObject(kSource + "/config/objects/cabinet.xml", 100000);
  const SurfaceSearch search = find(cabinet.shapes);
  ASSERT_EQ(search.surfaces.size(), 3u);
  const double heights[] = {0.02, 0.41};
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(search.surfaces[i].z, heights[i], 1e-9);
    EXPECT_TRUE(sameRing(search.surfaces[i].outer, rectangle(-0.28, -0.2, 0.28, 0.18), 1e-9));
    EXPECT_NEAR(search.surfaces[i].area, 0.56 * 0.38, 1e-9);
    EXPECT_NEAR(search.surfaces[i].clearance, 0.37, 1e-9);
  }
  EXPECT_NEAR(search.surfaces[2].z, 0.8, 1e-9);
  EXPECT_TRUE(sameRing(search.surfaces[2].outer, rectangle(-0.3, -0.2, 0.3, 0.2), 1e-9));
  EXPECT_EQ(search.surfaces[2].clearance, kInf);
}

TEST(SupportSurfaces, TiltedTopsInOnePlaneMerge) {
  // Two boxes turned alike about x, side by side along x: their tops are one tilted plane.
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()).matrix();
  const Eigen::Vector3d size(0.2, 0.2, 0.1);
  SurfaceSearch search = find(
      {boxAt(size, Eigen::Vector3d(0, 0, 0), tilt), boxAt(size, Eigen::Vector3d(0.2, 0, 0), tilt)});
  ASSERT_EQ(search.surfaces.size(), 1u);
  EXPECT_NEAR(search.surfaces[0].area, 2 * 0.04 * std::cos(0.05), 1e-12);
  EXPECT_NEAR(search.surfaces[0].z, 0.1 * std::sin(0.05) + 0.05 * std::cos(0.05), 1e-12);
  EXPECT_EQ(search.surfaces[0].outer.size(), 4u);
  // Raised by 1e-5 (more than the height tolerance): two surfaces.
  search = find({boxAt(size, Eigen::Vector3d(0, 0, 0), tilt),
                 boxAt(size, Eigen::Vector3d(0.2, 0, 1e-5), tilt)});
  EXPECT_EQ(search.surfaces.size(), 2u);
}

TEST(SupportSurfaces, ManySurfacesOverManyObstacles) {
  // 30 x 30 blocks standing on a 3 x 3 board, a roof over the half x < 0: the board's holes and
  // each block's clearance found through the grid of obstacles.
  std::vector<Shape> shapes = {
      boxAt(Eigen::Vector3d(3, 3, 0.02), Eigen::Vector3d(0, 0, 0.01)),
      boxAt(Eigen::Vector3d(1.5, 3, 0.02), Eigen::Vector3d(-0.75, 0, 1.01))};
  for (int i = 0; i < 30; ++i) {
    for (int j = 0; j < 30; ++j) {
      shapes.push_back(boxAt(Eigen::Vector3d(0.06, 0.06, 0.06),
                             Eigen::Vector3d(-1.45 + 0.1 * i, -1.45 + 0.1 * j, 0.05)));
    }
  }
  const SurfaceSearch search = find(shapes);
  ASSERT_EQ(search.surfaces.size(), 902u);
  EXPECT_NEAR(search.surfaces[0].z, 0.02, 1e-12);
  EXPECT_EQ(search.surfaces[0].holes.size(), 900u);
  EXPECT_NEAR(search.surfaces[0].area, 9 - 900 * 0.0036, 1e-9);
  EXPECT_NEAR(search.surfaces[0].clearance, 0.98, 1e-12);
  int covered = 0;
  for (std::size_t k = 1; k < 901; ++k) {
    const SupportSurface& top = search.surfaces[k];
    EXPECT_NEAR(top.z, 0.08, 1e-12);
    EXPECT_NEAR(top.area, 0.0036, 1e-12);
    if (top.outer[0].x() < 0) {
      EXPECT_NEAR(top.clearance, 0.92, 1e-12);
      ++covered;
    } else {
      EXPECT_EQ(top.clearance, kInf);
    }
  }
  EXPECT_EQ(covered, 450);
  EXPECT_NEAR(search.surfaces[901].z, 1.02, 1e-12);
}

TEST(SupportSurfaces, RoughMeshOfTiltedTrianglesEnds) {
  // 7200 triangles tilted within the tolerance, few neighbours coplanar, at many heights: by
  // default all dropped but for a few patches, and all of them with a minimum area of 0.
  const Mesh rough = test::makeRoughMesh(60);
  SurfaceSearch search = find({meshShape(rough)});
  for (const SupportSurface& s : search.surfaces) {
    EXPECT_GE(s.area, 0.0025);
  }
  EXPECT_GT(search.largestDroppedArea, 0.0);
  EXPECT_LT(search.largestDroppedArea, 0.0025);
  SurfaceOptions all;
  all.minArea = 0.0;
  search = find({meshShape(rough)}, all);
  EXPECT_GT(search.surfaces.size(), 1000u);
  EXPECT_LE(search.surfaces.size(), 7200u);
  for (const SupportSurface& s : search.surfaces) {
    expectWellFormed(s);
  }
}

TEST(SupportSurfaces, RandomTriangleSoupsAndBoxesGiveWellFormedSurfaces) {
  // Overlapping triangles of both windings, shared and repeated vertices, near-level heights,
  // boxes through them: whatever comes out is well formed.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-0.5, 0.5);
  std::uniform_int_distribution<int> level(0, 3);
  std::size_t found = 0;
  for (int round = 0; round < 20; ++round) {
    Mesh soup;
    for (int v = 0; v < 60; ++v) {
      soup.vertices.emplace_back(coordinate(random), coordinate(random),
                                 0.1 * level(random) + (v % 7 == 0 ? 1e-7 : 0.0));
    }
    std::uniform_int_distribution<int> vertex(0, 59);
    for (int t = 0; t < 150; ++t) {
      soup.triangles.emplace_back(vertex(random), vertex(random), vertex(random));
    }
    std::vector<Shape> shapes = {meshShape(soup)};
    for (int b = 0; b < 4; ++b) {
      shapes.push_back(boxAt(Eigen::Vector3d(0.2, 0.3, 0.25),
                             Eigen::Vector3d(coordinate(random), coordinate(random), 0.1 * b)));
    }
    SurfaceOptions options;
    options.minArea = 0.0;
    const SurfaceSearch search = find(shapes, options);
    found += search.surfaces.size();
    for (std::size_t i = 0; i < search.surfaces.size(); ++i) {
      const SupportSurface& surface = search.surfaces[i];
      expectWellFormed(surface);
      EXPECT_GE(surface.outer.size(), 3u);
      EXPECT_TRUE(std::isfinite(surface.z));
      EXPECT_GT(surface.clearance, 0.0);
      if (i > 0) {
        EXPECT_LE(search.surfaces[i - 1].z, surface.z);
      }
    }
  }
  EXPECT_GT(found, 100u);
}

TEST(SupportSurfaces, BrokenMeshesGiveWhatIsThere) {
  Mesh slab = test::makeSlabMesh(1.0, 1.0, 0.0, 0.1, 4);
  const std::size_t count = slab.triangles.size();
  for (std::size_t i = 0; i < count; i += 3) {
    slab.triangles.push_back(slab.triangles[i]);  // duplicated triangles
  }
  slab.triangles.emplace_back(0, 0, 1);        // a repeated vertex
  slab.triangles.emplace_back(0, 1, 2);        // collinear: no area
  slab.triangles.emplace_back(0, 1, 1000000);  // out of range
  slab.triangles.emplace_back(-1, 1, 2);       // negative
  slab.vertices.emplace_back(0.0, -0.5, 0.5);  // a fin up from the front edge
  slab.triangles.emplace_back(0, 1, static_cast<int>(slab.vertices.size()) - 1);
  SurfaceSearch search = find({meshShape(slab)});
  ASSERT_EQ(search.surfaces.size(), 1u);
  EXPECT_TRUE(sameRing(search.surfaces[0].outer, rectangle(-0.5, -0.5, 0.5, 0.5), 1e-12));
  EXPECT_NEAR(search.surfaces[0].area, 1.0, 1e-12);

  // Open: the top grid alone, and one of its triangles missing (a hole at a corner).
  Mesh open = test::makeSlabMesh(1.0, 1.0, 0.0, 0.1, 4);
  open.triangles.resize(2 * 4 * 4);
  open.triangles.erase(open.triangles.begin());
  search = find({meshShape(open)});
  ASSERT_EQ(search.surfaces.size(), 1u);
  EXPECT_NEAR(search.surfaces[0].area, 1.0 - 0.03125, 1e-12);
  EXPECT_TRUE(sameRing(
      search.surfaces[0].outer,
      {{-0.5, -0.5}, {-0.25, -0.25}, {-0.25, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}, 1e-12));

  // Overlapping coplanar triangles (a fold): their union.
  Mesh fold;
  fold.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, 0}, {1.2, 0.2, 0}, {0.2, 1.2, 0}};
  fold.triangles = {{0, 1, 2}, {3, 4, 5}, {0, 1, 5}};
  search = find({meshShape(fold)});
  ASSERT_EQ(search.surfaces.size(), 1u);
  EXPECT_GT(search.surfaces[0].area, 0.5);
  EXPECT_LT(search.surfaces[0].area, 1.5);
  expectWellFormed(search.surfaces[0]);

  // Nothing usable: no shapes' mesh, far away vertices, a box without size.
  Shape empty;
  empty.type = ShapeType::Mesh;
  Mesh far = test::makeSlabMesh(1.0, 1.0, 0.0, 0.1, 2);
  for (Eigen::Vector3d& v : far.vertices) {
    v += Eigen::Vector3d(1e13, 0, 0);
  }
  search = find({empty, meshShape(far), Shape::box(Eigen::Vector3d::Zero())});
  EXPECT_TRUE(search.surfaces.empty());
}

TEST(SupportSurfaces, HugeCoordinates) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(1e6, -1e6, 1e6);
  const SurfaceSearch search =
      findSupportSurfaces({boxAt(Eigen::Vector3d(1e5, 2e5, 10), Eigen::Vector3d::Zero()),
                           meshShape(test::makeSlabMesh(1e6, 1e6, 15.0, 16.0, 3))},
                          pose);
  ASSERT_EQ(search.surfaces.size(), 2u);
  EXPECT_EQ(search.surfaces[0].z, 1e6 + 5);
  EXPECT_EQ(search.surfaces[0].area, 2e10);
  EXPECT_EQ(search.surfaces[0].clearance, 10.0);
  EXPECT_EQ(search.surfaces[1].z, 1e6 + 16);
  EXPECT_NEAR(search.surfaces[1].area, 1e12, 1e-3);
}

}  // namespace
}  // namespace placement_samplers
