// Bounds of primitives (bottom and top z offsets, horizontal radius) under an initial
// orientation, against values worked out by hand, and ObjectModel's overrides.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "placement_samplers/geometry/object_model.hpp"
#include "placement_samplers/geometry/shape.hpp"

namespace placement_samplers {
namespace {

// Closed forms are exact; the cylinder rim uses a numeric search, still good to ~1e-12.
constexpr double kTol = 1e-12;

Eigen::Quaterniond about(double angle, const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis));
}

void expectBounds(const Bounds& b, double bottom, double top, double radius) {
  EXPECT_NEAR(b.bottomZ, bottom, kTol);
  EXPECT_NEAR(b.topZ, top, kTol);
  EXPECT_NEAR(b.horizontalRadius, radius, kTol);
}

TEST(Shape, BoxUpright) {
  const Shape box = Shape::box(Eigen::Vector3d(0.2, 0.4, 0.1));
  expectBounds(shapeBounds(box, Eigen::Quaterniond::Identity()), -0.05, 0.05, std::hypot(0.1, 0.2));
}

TEST(Shape, BoxRotatedAboutZKeepsHalfDiagonal) {
  // A yaw never changes the distance of the corners from the z axis nor their heights.
  const Shape box = Shape::box(Eigen::Vector3d(0.2, 0.4, 0.1));
  expectBounds(shapeBounds(box, about(M_PI / 4.0, Eigen::Vector3d::UnitZ())), -0.05, 0.05,
               std::hypot(0.1, 0.2));
}

TEST(Shape, BoxRotatedAboutXSwapsExtents) {
  // 90 deg about x: the y extent becomes vertical, the z extent horizontal.
  const Shape box = Shape::box(Eigen::Vector3d(0.2, 0.4, 0.1));
  expectBounds(shapeBounds(box, about(M_PI / 2.0, Eigen::Vector3d::UnitX())), -0.2, 0.2,
               std::hypot(0.1, 0.05));
}

TEST(Shape, CubeTiltedOnAnEdge) {
  // A cube of side a rolled 45 deg about x stands on an edge: half height a / sqrt(2); the
  // farthest corner is at (a/2, a/sqrt(2)) horizontally.
  const double a = 0.1;
  const Shape cube = Shape::box(Eigen::Vector3d(a, a, a));
  const double h = a / std::sqrt(2.0);
  expectBounds(shapeBounds(cube, about(M_PI / 4.0, Eigen::Vector3d::UnitX())), -h, h,
               std::hypot(a / 2.0, h));
}

TEST(Shape, CylinderUpright) {
  const Shape cylinder = Shape::cylinder(0.03, 0.1);
  expectBounds(shapeBounds(cylinder, Eigen::Quaterniond::Identity()), -0.05, 0.05, 0.03);
  // Symmetric about its axis: a yaw changes nothing.
  expectBounds(shapeBounds(cylinder, about(1.0, Eigen::Vector3d::UnitZ())), -0.05, 0.05, 0.03);
}

TEST(Shape, CylinderLyingOnItsSide) {
  // 90 deg about x: the axis is horizontal; top = radius, and the farthest points are the rim
  // points at the ends, at sqrt((L/2)^2 + r^2).
  const double r = 0.03;
  const double length = 0.2;
  expectBounds(shapeBounds(Shape::cylinder(r, length), about(M_PI / 2.0, Eigen::Vector3d::UnitX())),
               -r, r, std::hypot(length / 2.0, r));
}

TEST(Shape, CylinderSlightlyTilted) {
  // Tilt t about x, (L/2) cos t >= r sin t: the farthest point is the top rim point leaning
  // out, at (L/2) sin t + r cos t; the height is (L/2) cos t + r sin t.
  const double r = 0.03;
  const double half = 0.1;
  const double t = M_PI / 6.0;
  ASSERT_GE(half * std::cos(t), r * std::sin(t));
  expectBounds(shapeBounds(Shape::cylinder(r, 2.0 * half), about(t, Eigen::Vector3d::UnitX())),
               -(half * std::cos(t) + r * std::sin(t)), half * std::cos(t) + r * std::sin(t),
               half * std::sin(t) + r * std::cos(t));
}

TEST(Shape, CylinderSteeplyTilted) {
  // (L/2) cos t < r sin t: the maximum of |c + r cos(s) u + r sin(s) v| over the rim is inside
  // the rim, at sqrt(r^2 + (L/2)^2) (worked out by maximising over sin s).
  const double r = 0.03;
  const double half = 0.1;
  const double t = 80.0 * M_PI / 180.0;
  ASSERT_LT(half * std::cos(t), r * std::sin(t));
  expectBounds(shapeBounds(Shape::cylinder(r, 2.0 * half), about(t, Eigen::Vector3d::UnitX())),
               -(half * std::cos(t) + r * std::sin(t)), half * std::cos(t) + r * std::sin(t),
               std::hypot(r, half));
}

TEST(Shape, OffsetCylinderTakesTheFartherRim) {
  // Axis along +x or -x through (0.1, 0, 0): the rims are at x = 0 and x = 0.2; the farthest
  // points are on the rim at 0.2, r off the axis, whichever way the axis points.
  const double r = 0.03;
  for (double angle : {M_PI / 2.0, -M_PI / 2.0}) {
    Shape cylinder = Shape::cylinder(r, 0.2);
    cylinder.pose = Eigen::Translation3d(0.1, 0.0, 0.0) * about(angle, Eigen::Vector3d::UnitY());
    expectBounds(shapeBounds(cylinder, Eigen::Quaterniond::Identity()), -r, r, std::hypot(0.2, r));
  }
}

TEST(Shape, SphereIgnoresOrientation) {
  const Shape sphere = Shape::sphere(0.04);
  expectBounds(shapeBounds(sphere, Eigen::Quaterniond::Identity()), -0.04, 0.04, 0.04);
  expectBounds(shapeBounds(sphere, about(0.7, Eigen::Vector3d(1, 2, 3).normalized())), -0.04, 0.04,
               0.04);
}

TEST(Shape, OffsetSphereFollowsTheObjectFrame) {
  // The shape pose is in the object frame; the init orientation rotates it about the origin.
  Shape sphere = Shape::sphere(0.02);
  sphere.pose.translation() = Eigen::Vector3d(0.1, 0.0, 0.05);
  expectBounds(shapeBounds(sphere, Eigen::Quaterniond::Identity()), 0.03, 0.07, 0.12);
  // 90 deg about x maps (0.1, 0, 0.05) to (0.1, -0.05, 0).
  expectBounds(shapeBounds(sphere, about(M_PI / 2.0, Eigen::Vector3d::UnitX())), -0.02, 0.02,
               std::hypot(0.1, 0.05) + 0.02);
}

TEST(Shape, CapsuleUprightAndTilted) {
  // length is the distance between the cap centres.
  const double r = 0.02;
  const double half = 0.04;
  const Shape capsule = Shape::capsule(r, 2.0 * half);
  expectBounds(shapeBounds(capsule, Eigen::Quaterniond::Identity()), -(half + r), half + r, r);
  // Tilted by t: the cap centres move to height (L/2) cos t and radius (L/2) sin t.
  const double t = 0.5;
  expectBounds(shapeBounds(capsule, about(t, Eigen::Vector3d::UnitY())), -(half * std::cos(t) + r),
               half * std::cos(t) + r, half * std::sin(t) + r);
  // Lying: as high as its radius, as wide as half its total length.
  expectBounds(shapeBounds(capsule, about(M_PI / 2.0, Eigen::Vector3d::UnitX())), -r, r, half + r);
}

TEST(Shape, UnionOfShapes) {
  // A tall thin box and a wide sphere above it: the union takes the extreme of each bound.
  Shape sphere = Shape::sphere(0.1);
  sphere.pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.3);
  const Bounds b = shapesBounds({Shape::box(Eigen::Vector3d(0.02, 0.02, 0.4)), sphere},
                                Eigen::Quaterniond::Identity());
  expectBounds(b, -0.2, 0.4, 0.1);
}

TEST(Shape, NoShapesThrows) {
  EXPECT_THROW(shapesBounds({}, Eigen::Quaterniond::Identity()), std::invalid_argument);
  EXPECT_THROW(makeObject("empty", {}, Eigen::Quaterniond::Identity()), std::invalid_argument);
}

/// Turns that keep the z axis vertical: none, about z (several angles), upside down.
std::vector<Eigen::Quaterniond> verticalTurns() {
  std::vector<Eigen::Quaterniond> turns{Eigen::Quaterniond::Identity(),
                                        Eigen::Quaterniond(0.0, 1.0, 0.0, 0.0),
                                        Eigen::Quaterniond(0.0, 0.0, 0.0, 1.0)};
  for (double angle : {0.3, 1.0, 2.5, -0.7, M_PI / 4.0}) {
    turns.push_back(Eigen::Quaterniond(std::cos(angle / 2.0), 0.0, 0.0, std::sin(angle / 2.0)));
  }
  return turns;
}

// robosuite's primitive objects, bit for bit (robosuite/models/objects/primitive/): a cylinder
// of radius 0.03 has horizontal radius 0.03, not 0.030000000000000002 (one bit more moves its
// boundary shrink and every position sampled with it), upright, turned about z or upside down.
TEST(Shape, UprightPrimitivesGiveRobosuitesNumbersExactly) {
  for (const Eigen::Quaterniond& turn : verticalTurns()) {
    for (double r : {0.03, 0.033, 0.0271, 0.09, 1.0 / 3.0, 7e-4}) {
      const double half = 0.0617;
      const Bounds cylinder = shapeBounds(Shape::cylinder(r, 2.0 * half), turn);
      EXPECT_EQ(cylinder.horizontalRadius, r);
      EXPECT_EQ(cylinder.bottomZ, -half);
      EXPECT_EQ(cylinder.topZ, half);
      const Bounds capsule = shapeBounds(Shape::capsule(r, 2.0 * half), turn);
      EXPECT_EQ(capsule.horizontalRadius, r);
      EXPECT_EQ(capsule.bottomZ, -(r + half));
      EXPECT_EQ(capsule.topZ, r + half);
      const Bounds sphere = shapeBounds(Shape::sphere(r), turn);
      EXPECT_EQ(sphere.horizontalRadius, r);
      EXPECT_EQ(sphere.bottomZ, -r);
      EXPECT_EQ(sphere.topZ, r);
    }
  }
}

// A box: np.linalg.norm(size[0:2]) of the half sizes, which numpy computes as the square root
// of the dot product (x*x + y*y, no FMA); a yaw must not move it by a bit.
TEST(Shape, BoxRadiusIsNumpysNormUprightAndTurnedAboutZ) {
  for (const Eigen::Quaterniond& turn : verticalTurns()) {
    for (const Eigen::Vector3d& size :
         {Eigen::Vector3d(0.042, 0.042, 0.042), Eigen::Vector3d(0.063, 0.037, 0.05),
          Eigen::Vector3d(0.32, 0.218, 0.09), Eigen::Vector3d(0.012, 0.292, 0.423)}) {
      const double hx = size.x() / 2.0;
      const double hy = size.y() / 2.0;
      const Bounds b = shapeBounds(Shape::box(size), turn);
      EXPECT_EQ(b.horizontalRadius, std::sqrt(hx * hx + hy * hy));
      EXPECT_EQ(b.bottomZ, -size.z() / 2.0);
      EXPECT_EQ(b.topZ, size.z() / 2.0);
    }
  }
}

// A part on the object's z axis (a composite's) keeps the closed forms, at its height.
TEST(Shape, PartOnTheAxisIsExactAtItsHeight) {
  Shape cylinder = Shape::cylinder(0.03, 0.1);
  cylinder.pose = Eigen::Translation3d(0.0, 0.0, 0.2) * about(0.4, Eigen::Vector3d::UnitZ());
  const Bounds b = shapeBounds(cylinder, about(1.1, Eigen::Vector3d::UnitZ()));
  EXPECT_EQ(b.horizontalRadius, 0.03);
  EXPECT_EQ(b.bottomZ, 0.2 - 0.05);
  EXPECT_EQ(b.topZ, 0.2 + 0.05);
}

TEST(Shape, TypeNames) {
  EXPECT_STREQ(shapeTypeName(ShapeType::Box), "box");
  EXPECT_STREQ(shapeTypeName(ShapeType::Cylinder), "cylinder");
  EXPECT_STREQ(shapeTypeName(ShapeType::Sphere), "sphere");
  EXPECT_STREQ(shapeTypeName(ShapeType::Capsule), "capsule");
  EXPECT_STREQ(shapeTypeName(ShapeType::Mesh), "mesh");
}

TEST(ObjectModel, DerivesOffsetsUnderInitOrientation) {
  const double r = 0.03;
  const double length = 0.2;
  const ObjectModel can =
      makeObject("can", {Shape::cylinder(r, length)}, about(M_PI / 2.0, Eigen::Vector3d::UnitX()));
  EXPECT_EQ(can.name, "can");
  // Offsets are vectors along z, as robosuite's bottom_offset / top_offset.
  EXPECT_NEAR((can.bottomOffset - Eigen::Vector3d(0, 0, -r)).norm(), 0.0, kTol);
  EXPECT_NEAR((can.topOffset - Eigen::Vector3d(0, 0, r)).norm(), 0.0, kTol);
  EXPECT_NEAR(can.horizontalRadius, std::hypot(length / 2.0, r), kTol);
  EXPECT_TRUE(can.radiusBoundsGeometry);
}

TEST(ObjectModel, NormalizesInitOrientation) {
  // A scaled quaternion is the same rotation; bounds must not grow with its norm.
  const Eigen::Quaterniond scaled(2.0, 0.0, 0.0, 0.0);
  const ObjectModel cube = makeObject("cube", {Shape::box(Eigen::Vector3d(0.1, 0.1, 0.1))}, scaled);
  EXPECT_NEAR(cube.initOrientation.norm(), 1.0, kTol);
  EXPECT_NEAR(cube.topOffset.z(), 0.05, kTol);
}

// The gaps between given offsets and the geometry: what physics counts as clearance.
TEST(ObjectModel, GapsBetweenOffsetsAndGeometry) {
  const Shape box = Shape::box(Eigen::Vector3d(0.1, 0.1, 0.12));
  const ObjectModel derived = makeObject("box", {box}, Eigen::Quaterniond::Identity());
  EXPECT_EQ(derived.bottomGap, 0.0);
  EXPECT_EQ(derived.topGap, 0.0);
  ObjectOverrides sites;
  sites.hasBottomOffset = true;
  sites.bottomOffset = Eigen::Vector3d(0.0, 0.0, -0.085);  // 2.5 cm below the box
  sites.hasTopOffset = true;
  sites.topOffset = Eigen::Vector3d(0.0, 0.0, 0.05);  // 1 cm inside it
  const ObjectModel carton = makeObject("carton", {box}, Eigen::Quaterniond::Identity(), sites);
  EXPECT_NEAR(carton.bottomGap, 0.025, kTol);
  EXPECT_NEAR(carton.topGap, -0.01, kTol);
}

TEST(ObjectModel, OverridesWin) {
  ObjectOverrides overrides;
  overrides.hasHorizontalRadius = true;
  overrides.horizontalRadius = 0.5;
  overrides.hasBottomOffset = true;
  overrides.bottomOffset = Eigen::Vector3d(0.0, 0.0, -0.3);
  overrides.hasTopOffset = true;
  overrides.topOffset = Eigen::Vector3d(0.0, 0.0, 0.4);
  const ObjectModel cube = makeObject("cube", {Shape::box(Eigen::Vector3d(0.1, 0.1, 0.1))},
                                      Eigen::Quaterniond::Identity(), overrides);
  EXPECT_EQ(cube.bottomOffset, overrides.bottomOffset);
  EXPECT_EQ(cube.topOffset, overrides.topOffset);
  EXPECT_EQ(cube.horizontalRadius, 0.5);
  // A larger radius still bounds the geometry.
  EXPECT_TRUE(cube.radiusBoundsGeometry);
}

TEST(ObjectModel, PartialOverridesKeepTheRest) {
  ObjectOverrides overrides;
  overrides.hasTopOffset = true;
  overrides.topOffset = Eigen::Vector3d(0.0, 0.0, 0.2);
  const ObjectModel ball =
      makeObject("ball", {Shape::sphere(0.05)}, Eigen::Quaterniond::Identity(), overrides);
  EXPECT_EQ(ball.topOffset.z(), 0.2);
  EXPECT_NEAR(ball.bottomOffset.z(), -0.05, kTol);
  EXPECT_NEAR(ball.horizontalRadius, 0.05, kTol);
}

TEST(ObjectModel, SmallerRadiusOverrideNoLongerBoundsGeometry) {
  ObjectOverrides overrides;
  overrides.hasHorizontalRadius = true;
  overrides.horizontalRadius = 0.01;
  const ObjectModel ball =
      makeObject("ball", {Shape::sphere(0.05)}, Eigen::Quaterniond::Identity(), overrides);
  EXPECT_EQ(ball.horizontalRadius, 0.01);
  EXPECT_FALSE(ball.radiusBoundsGeometry);
}

TEST(ObjectModel, ReorientedObjectRederivesBoundsAndKeepsOverrides) {
  ObjectOverrides overrides;
  overrides.hasHorizontalRadius = true;
  overrides.horizontalRadius = 0.5;
  const ObjectModel slab = makeObject("slab", {Shape::box(Eigen::Vector3d(0.2, 0.4, 0.1))},
                                      Eigen::Quaterniond::Identity(), overrides);
  const ObjectModel standing = reorientedObject(slab, about(M_PI / 2.0, Eigen::Vector3d::UnitX()));
  EXPECT_EQ(standing.name, "slab");
  EXPECT_NEAR(standing.topOffset.z(), 0.2, kTol);
  EXPECT_NEAR(standing.bottomOffset.z(), -0.2, kTol);
  EXPECT_EQ(standing.horizontalRadius, 0.5);
}

}  // namespace
}  // namespace placement_samplers
