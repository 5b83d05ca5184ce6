// FclChecker and CombinedChecker: exact tests against robosuite's circles, touching versus
// penetrating, margins, bins from URDF, meshes, request fixtures, and the packing comparison.
// Accepted scenes are checked with independent geometry (separating axes, point distances),
// not with FCL.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "placement_samplers/collision/collision_checker.hpp"
#include "placement_samplers/collision/combined_checker.hpp"
#include "placement_samplers/collision/make_collision_checker.hpp"
#include "placement_samplers/collision/radius_checker.hpp"
#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/collision/fcl_checker.hpp"
#include "placement_samplers/config/object_config.hpp"
#include "placement_samplers/sampling/sample_context.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {
namespace {

const std::string kSourceDir = PLACEMENT_SAMPLERS_SOURCE_DIR;

BuildOptions sourceOptions() {
  BuildOptions options;
  options.packageResolver = [](const std::string& package) {
    return package == "placement_samplers" ? kSourceDir : std::string();
  };
  options.baseDirectory = kSourceDir;
  return options;
}

std::shared_ptr<SceneConfig> build(const std::string& yaml) {
  return buildSceneConfig(parseYaml(yaml, "test.yaml"), sourceOptions());
}

std::shared_ptr<SceneConfig> buildFile(const std::string& relativePath) {
  return buildSceneConfig(loadYamlFile(kSourceDir + "/" + relativePath), sourceOptions());
}

ObjectPtr object(const std::string& name, std::vector<Shape> shapes,
                 const ObjectOverrides& overrides = ObjectOverrides()) {
  return std::make_shared<ObjectModel>(
      makeObject(name, std::move(shapes), Eigen::Quaterniond::Identity(), overrides));
}

ObjectPtr stick(const std::string& name, const ObjectOverrides& overrides = ObjectOverrides()) {
  return object(name, {Shape::box(Eigen::Vector3d(0.2, 0.02, 0.02))}, overrides);
}

Eigen::Quaterniond yaw(double angle) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
}

/// Entries and a checker, filled as SampleContext does.
struct Scene {
  explicit Scene(std::unique_ptr<CollisionChecker> c) : checker(std::move(c)) {}

  void add(const std::string& name, const ObjectPtr& object, const Eigen::Vector3d& position,
           const Eigen::Quaterniond& orientation = Eigen::Quaterniond::Identity(),
           bool fixture = false) {
    objects.push_back(object);
    names.push_back(name);  // entries hold views
    entries.push_back(PlacedEntry{names.back(), object.get(), position, orientation, fixture});
    checker->added(entries, entries.size() - 1);
  }

  std::ptrdiff_t test(const ObjectPtr& object, const Eigen::Vector3d& position,
                      const Eigen::Quaterniond& orientation = Eigen::Quaterniond::Identity()) {
    objects.push_back(object);
    return checker->firstCollision(entries, Candidate{object.get(), position, orientation});
  }

  void clear() {
    entries.clear();
    checker->clear();
  }

  std::unique_ptr<CollisionChecker> checker;
  std::vector<PlacedEntry> entries;
  std::vector<ObjectPtr> objects;  // keeps every object alive as long as the checker
  std::deque<std::string> names;   // stable addresses for the entries' names
};

Scene fclScene(double margin = 0.0) { return Scene(std::make_unique<FclChecker>(margin)); }
Scene radiusScene() { return Scene(std::make_unique<RadiusChecker>()); }

constexpr std::ptrdiff_t kNone = CollisionChecker::kNone;

// ---- Independent geometry for checking accepted scenes ----

/// World corners of a box shape of @p object placed at @p position, @p orientation.
std::vector<Eigen::Vector3d> boxCorners(const Shape& shape, const Eigen::Vector3d& position,
                                        const Eigen::Quaterniond& orientation) {
  std::vector<Eigen::Vector3d> corners;
  const Eigen::Vector3d half = 0.5 * shape.size;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d local((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                                (i & 4) ? half.z() : -half.z());
    corners.push_back(position + orientation * (shape.pose * local));
  }
  return corners;
}

/// Penetration depth of two rectangles in the plane (corners counter-clockwise or clockwise),
/// by separating axes: <= 0 when they are apart or touch.
double rectangleOverlap(const std::vector<Eigen::Vector2d>& a,
                        const std::vector<Eigen::Vector2d>& b) {
  double depth = std::numeric_limits<double>::infinity();
  for (const std::vector<Eigen::Vector2d>* poly : {&a, &b}) {
    for (std::size_t i = 0; i < 4; ++i) {
      const Eigen::Vector2d edge = (*poly)[(i + 1) % 4] - (*poly)[i];
      const Eigen::Vector2d axis = Eigen::Vector2d(-edge.y(), edge.x()).normalized();
      double minA = 1e9, maxA = -1e9, minB = 1e9, maxB = -1e9;
      for (const Eigen::Vector2d& p : a) {
        minA = std::min(minA, p.dot(axis));
        maxA = std::max(maxA, p.dot(axis));
      }
      for (const Eigen::Vector2d& p : b) {
        minB = std::min(minB, p.dot(axis));
        maxB = std::max(maxB, p.dot(axis));
      }
      depth = std::min(depth, std::min(maxA, maxB) - std::max(minA, minB));
    }
  }
  return depth;
}

/// The footprint of a z-upright box placement (bottom face corners, in order around it).
std::vector<Eigen::Vector2d> footprint(const ObjectPlacement& p) {
  const Eigen::Vector3d half = 0.5 * p.object->shapes.front().size;
  std::vector<Eigen::Vector2d> out;
  for (const Eigen::Vector2d& c :
       {Eigen::Vector2d(-half.x(), -half.y()), Eigen::Vector2d(half.x(), -half.y()),
        Eigen::Vector2d(half.x(), half.y()), Eigen::Vector2d(-half.x(), half.y())}) {
    out.push_back((p.position + p.orientation * Eigen::Vector3d(c.x(), c.y(), 0.0)).head<2>());
  }
  return out;
}

/// Distance from @p point to a box of full extents @p size at @p pose (0 inside).
double pointBoxDistance(const Eigen::Vector3d& point, const Eigen::Vector3d& size,
                        const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d local = pose.inverse() * point;
  const Eigen::Vector3d outside = (local.cwiseAbs() - 0.5 * size).cwiseMax(0.0);
  return outside.norm();
}

// ---- Long boxes: circles overlap, geometry does not ----

TEST(FclChecker, LongBoxesSideBySideAcceptedWhereRadiusRejects) {
  const ObjectPtr a = stick("a");
  const ObjectPtr b = stick("b");
  // Parallel along x, 0.03 apart in y: a 0.01 gap, circles (0.1005 each) far overlapping.
  Scene radius = radiusScene();
  radius.add("a", a, Eigen::Vector3d(0, 0, 0.01));
  EXPECT_EQ(radius.test(b, Eigen::Vector3d(0, 0.03, 0.01)), 0);

  Scene fcl = fclScene();
  fcl.add("a", a, Eigen::Vector3d(0, 0, 0.01));
  EXPECT_EQ(fcl.test(b, Eigen::Vector3d(0, 0.03, 0.01)), kNone);
  // Side faces touching exactly: touching is not a collision.
  EXPECT_EQ(fcl.test(b, Eigen::Vector3d(0, 0.02, 0.01)), kNone);
  // 0.1 mm into each other: a collision.
  EXPECT_EQ(fcl.test(b, Eigen::Vector3d(0, 0.0199, 0.01)), 0);
  // Crossing at right angles, far inside the circles: a collision.
  EXPECT_EQ(fcl.test(b, Eigen::Vector3d(0.05, 0.0, 0.01), yaw(M_PI / 2)), 0);
  // Head to tail along x, 1 mm apart.
  EXPECT_EQ(fcl.test(b, Eigen::Vector3d(0.201, 0, 0.01)), kNone);
  EXPECT_EQ(fcl.test(b, Eigen::Vector3d(0.199, 0, 0.01)), 0);
}

TEST(FclChecker, CloserThanAPositiveMarginRejected) {
  const ObjectPtr a = stick("a");
  const ObjectPtr b = stick("b");
  const Eigen::Vector3d gap10mm(0, 0.03, 0.01);  // faces 0.01 apart
  for (double margin : {0.0, 0.005, 0.0099}) {
    Scene fcl = fclScene(margin);
    fcl.add("a", a, Eigen::Vector3d(0, 0, 0.01));
    EXPECT_EQ(fcl.test(b, gap10mm), kNone) << "margin " << margin;
  }
  for (double margin : {0.0101, 0.02, 0.5}) {
    Scene fcl = fclScene(margin);
    fcl.add("a", a, Eigen::Vector3d(0, 0, 0.01));
    EXPECT_EQ(fcl.test(b, gap10mm), 0) << "margin " << margin;
  }
  // The margin reaches past the boxes' bounds: 0.05 m end to end with a 0.06 m margin.
  Scene wide = fclScene(0.06);
  wide.add("a", a, Eigen::Vector3d(0, 0, 0.01));
  EXPECT_EQ(wide.test(b, Eigen::Vector3d(0.25, 0, 0.01)), 0);
  EXPECT_EQ(wide.test(b, Eigen::Vector3d(0.27, 0, 0.01)), kNone);
  // With a positive margin, touching is too close.
  Scene touching = fclScene(0.001);
  touching.add("a", a, Eigen::Vector3d(0, 0, 0.01));
  EXPECT_EQ(touching.test(b, Eigen::Vector3d(0, 0.02, 0.01)), 0);
}

TEST(FclChecker, MarginMustBeFiniteAndNonNegative) {
  EXPECT_THROW(FclChecker(-0.01), ConfigError);
  EXPECT_THROW(FclChecker(std::nan("")), ConfigError);
  EXPECT_DOUBLE_EQ(FclChecker(0.02).margin(), 0.02);
  EXPECT_THROW(makeCollisionChecker(CollisionMode::Fcl, -1.0), ConfigError);
}

TEST(FclChecker, ReturnsTheIndexOfTheCollidingEntry) {
  const ObjectPtr cube = object("cube", {Shape::box(Eigen::Vector3d(0.1, 0.1, 0.1))});
  Scene fcl = fclScene();
  fcl.add("c0", cube, Eigen::Vector3d(0, 0, 0));
  fcl.add("c1", cube, Eigen::Vector3d(1, 0, 0));
  fcl.add("c2", cube, Eigen::Vector3d(2, 0, 0));
  fcl.add("c3", cube, Eigen::Vector3d(3, 0, 0));
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(2.05, 0, 0)), 2);
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(0.95, 0.05, 0.05)), 1);
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(1.5, 0, 0)), kNone);
  // After clear(), the same checker starts an empty scene, and pooled bodies are reused.
  fcl.clear();
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(2.05, 0, 0)), kNone);
  fcl.add("d0", cube, Eigen::Vector3d(2, 0, 0));
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(2.05, 0, 0)), 0);
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(0, 0, 0)), kNone);
}

TEST(FclChecker, CirclesDoNotSkipWhenTheRadiusIsOverriddenSmaller) {
  // Overridden radii of 1 cm: their circles are 0.15 m apart, the sticks cross.
  ObjectOverrides small;
  small.hasHorizontalRadius = true;
  small.horizontalRadius = 0.01;
  const ObjectPtr a = stick("a", small);
  const ObjectPtr b = stick("b", small);
  ASSERT_FALSE(a->radiusBoundsGeometry);
  Scene radius = radiusScene();
  radius.add("a", a, Eigen::Vector3d(0, 0, 0.01));
  EXPECT_EQ(radius.test(b, Eigen::Vector3d(0.09, 0.06, 0.01), yaw(M_PI / 2)), kNone);
  Scene fcl = fclScene();
  fcl.add("a", a, Eigen::Vector3d(0, 0, 0.01));
  EXPECT_EQ(fcl.test(b, Eigen::Vector3d(0.09, 0.06, 0.01), yaw(M_PI / 2)), 0);
  // A larger override still bounds the geometry.
  ObjectOverrides large;
  large.hasHorizontalRadius = true;
  large.horizontalRadius = 0.3;
  EXPECT_TRUE(stick("c", large)->radiusBoundsGeometry);
}

TEST(FclChecker, CirclesDoNotSkipObjectsTiltedOutOfTheirInitOrientation) {
  // A standing pole (radius 0.014 m) laid down about x reaches 0.1 m along y: its circle no
  // longer bounds it, and the pole 0.08 m away along y is hit.
  const ObjectPtr pole = object("pole", {Shape::box(Eigen::Vector3d(0.02, 0.02, 0.2))});
  const ObjectPtr post = object("post", {Shape::box(Eigen::Vector3d(0.02, 0.02, 0.2))});
  ASSERT_TRUE(pole->radiusBoundsGeometry);
  Scene fcl = fclScene();
  fcl.add("post", post, Eigen::Vector3d(0, 0.08, 0.1));
  const Eigen::Quaterniond laid(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
  EXPECT_EQ(fcl.test(pole, Eigen::Vector3d(0, 0, 0.1), laid), 0);
  EXPECT_EQ(fcl.test(pole, Eigen::Vector3d(0, 0, 0.1)), kNone);
}

// ---- Touching supports ----

TEST(FclChecker, ObjectsRestingOnTheirSupportWithZOffsetZeroAreAccepted) {
  // Every primitive, a mesh and a URDF, on a plain table and on the legged URDF table, with
  // on_top and z_offset 0: each rests exactly on the surface and touches it.
  const std::string yaml = R"(
collision_check: fcl
max_attempts: 500
objects:
  slab: {shape: box, size: [1.0, 1.0, 0.05]}
  table_urdf: {urdf_file: urdf/table.urdf}
  cube: {shape: box, size: [0.05, 0.05, 0.05]}
  can: {shape: cylinder, radius: 0.03, length: 0.1}
  ball: {shape: sphere, radius: 0.03}
  pill: {shape: capsule, radius: 0.02, length: 0.06}
  lying_can: {shape: cylinder, radius: 0.03, length: 0.1, init_orientation: [0.7071067811865476, 0, 0, 0.7071067811865476]}
  block: {shape: mesh, mesh: package://placement_samplers/meshes/l_block.stl}
  wedge: {urdf_file: test/data/urdf/mesh.urdf}
  cube2: {shape: box, size: [0.05, 0.05, 0.05]}
  can2: {shape: cylinder, radius: 0.03, length: 0.1}
  block2: {shape: mesh, mesh: meshes/l_block.stl}
fixtures:
  - {name: table, object: slab, position: [0.3, -0.2, 0.775]}
  - {name: legged, object: table_urdf, position: [2.0, 0.0, 0.74]}
samplers:
  - name: OnSlab
    objects: [cube, can, ball, pill, lying_can, block, wedge]
    x_range: [-0.4, 0.4]
    y_range: [-0.4, 0.4]
    z_offset: 0.0
    sample_args: {reference: table, on_top: true}
  - name: OnLegged
    objects: [cube2, can2, block2]
    x_range: [-0.4, 0.4]
    y_range: [-0.3, 0.3]
    z_offset: 0.0
    sample_args: {reference: legged, on_top: true}
)";
  const SceneGenerator generator(build(yaml));
  const PreparedRequest request = generator.prepare(SampleRequest());
  ASSERT_EQ(request.collisionCheck, CollisionMode::Fcl);
  const std::vector<SceneResult> scenes = generator.sampleScenes(request, 11, 40, 2);
  for (const SceneResult& scene : scenes) {
    ASSERT_TRUE(scene.success) << scene.message;
    ASSERT_EQ(scene.placements.size(), 10u);
    for (const ObjectPlacement& p : scene.placements) {
      const double surface = p.sampler == "OnSlab" ? 0.8 : 0.74;
      // The bottom is on the surface (the mesh's float vertices round to ~1e-9).
      EXPECT_NEAR(p.position.z() + p.object->bottomOffset.z(), surface, 1e-8) << p.name;
    }
  }
}

TEST(FclChecker, RestingContactIsNotACollisionButSinkingIs) {
  const ObjectPtr table = object("table", {Shape::box(Eigen::Vector3d(1.0, 1.0, 0.05))});
  const std::vector<ObjectPtr> shapes = {
      object("cube", {Shape::box(Eigen::Vector3d(0.05, 0.05, 0.05))}),
      object("can", {Shape::cylinder(0.03, 0.1)}),
      object("ball", {Shape::sphere(0.03)}),
      object("pill", {Shape::capsule(0.02, 0.06)}),
  };
  Scene fcl = fclScene();
  fcl.add("table", table, Eigen::Vector3d(0.1, -0.25, 0.775), Eigen::Quaterniond::Identity(), true);
  const double top = 0.775 + table->topOffset.z();
  for (const ObjectPtr& o : shapes) {
    for (double angle : {0.0, 0.3, 1.1, 2.5}) {
      const Eigen::Vector3d resting(0.13, -0.21, top - o->bottomOffset.z());
      EXPECT_EQ(fcl.test(o, resting, yaw(angle)), kNone) << o->name << " at " << angle;
      EXPECT_EQ(fcl.test(o, resting - Eigen::Vector3d(0, 0, 1e-4), yaw(angle)), 0)
          << o->name << " sunk 0.1 mm at " << angle;
      EXPECT_EQ(fcl.test(o, resting + Eigen::Vector3d(0, 0, 1e-4), yaw(angle)), kNone);
    }
  }
}

// ---- Bins from URDF ----

TEST(FclChecker, ObjectInsideABinAcceptedThroughItsWallRejected) {
  const auto config = build("objects:\n  bin: {urdf_file: urdf/bin.urdf}\n");
  const ObjectPtr bin = config->findObjectPtr("bin");
  ASSERT_TRUE(bin);
  ASSERT_EQ(bin->shapes.size(), 5u);
  const ObjectPtr cube = object("cube", {Shape::box(Eigen::Vector3d(0.04, 0.04, 0.04))});
  const Eigen::Vector3d binPos(0.1, -0.25, 0.8);
  const double floorZ = 0.8 + 0.01 + 0.02;  // the cube's centre when it rests on the floor

  Scene radius = radiusScene();
  radius.add("bin", bin, binPos, Eigen::Quaterniond::Identity(), true);
  EXPECT_EQ(radius.test(cube, Eigen::Vector3d(0.1, -0.25, floorZ)), 0);  // robosuite: never

  Scene fcl = fclScene();
  fcl.add("bin", bin, binPos, Eigen::Quaterniond::Identity(), true);
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(0.1, -0.25, floorZ)), kNone);         // centre
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(0.1 + 0.17, -0.25, floorZ)), kNone);  // touches +x
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(0.1, -0.25 - 0.22, floorZ)), kNone);  // touches -y
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(0.1 + 0.18, -0.25, floorZ)), 0);      // into +x
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(0.1 + 0.195, -0.25, floorZ)), 0);     // through +x
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(0.1 - 0.195, -0.1, floorZ)), 0);      // through -x
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(0.1, -0.25 + 0.245, floorZ)), 0);     // through +y
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(0.1, -0.25, floorZ - 0.005)), 0);     // into floor
  // A corner turned into the wall: centre 0.165 from the wall's inner face, half-diagonal 0.028.
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(0.1 + 0.165, -0.25, floorZ), yaw(M_PI / 4)), 0);
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(0.1 + 0.16, -0.25, floorZ), yaw(M_PI / 4)), kNone);
  // Above the walls: free.
  EXPECT_EQ(fcl.test(cube, Eigen::Vector3d(0.1 + 0.195, -0.25, 0.8 + 0.1 + 0.02)), kNone);
}

TEST(FclChecker, PickPlaceBinsKeepsObjectsInsideTheBins) {
  const auto config = buildFile("config/pick_place_bins.yaml");
  const SceneGenerator generator(config);
  const PreparedRequest request = generator.prepare(SampleRequest());
  ASSERT_EQ(request.collisionCheck, CollisionMode::Fcl);
  const std::vector<SceneResult> scenes = generator.sampleScenes(request, 5, 200, 2);
  for (const SceneResult& scene : scenes) {
    ASSERT_TRUE(scene.success) << scene.message;
    for (const ObjectPlacement& p : scene.placements) {
      const Eigen::Vector2d binCentre(0.1, p.sampler == "Bin1Sampler" ? -0.25 : 0.28);
      // Every extreme point inside the walls (the inside is convex, so is each shape).
      std::vector<Eigen::Vector3d> points;
      for (const Shape& shape : p.object->shapes) {
        const Eigen::Isometry3d pose =
            Eigen::Translation3d(p.position) * p.orientation * shape.pose;
        if (shape.type == ShapeType::Box) {
          const std::vector<Eigen::Vector3d> c = boxCorners(shape, p.position, p.orientation);
          points.insert(points.end(), c.begin(), c.end());
        } else if (shape.type == ShapeType::Cylinder) {
          for (int k = 0; k < 360; ++k) {  // rim points; the chord error is below 1e-6 m
            const double t = 2.0 * M_PI * k / 360.0;
            for (double z : {-0.5, 0.5}) {
              points.push_back(pose * Eigen::Vector3d(shape.radius * std::cos(t),
                                                      shape.radius * std::sin(t),
                                                      z * shape.length));
            }
          }
        } else if (shape.type == ShapeType::Mesh) {
          for (const Eigen::Vector3d& v : shape.mesh->vertices) {
            points.push_back(pose * v);
          }
        }
      }
      ASSERT_FALSE(points.empty()) << p.name;
      for (const Eigen::Vector3d& q : points) {
        EXPECT_LE(std::abs(q.x() - binCentre.x()), 0.19 + 1e-5) << p.name;
        EXPECT_LE(std::abs(q.y() - binCentre.y()), 0.24 + 1e-5) << p.name;
        EXPECT_GE(q.z(), 0.81 - 1e-6) << p.name;
      }
    }
  }
  // robosuite's circles reject every candidate in a bin.
  SampleRequest radius;
  radius.collisionCheck = CollisionMode::Radius;
  radius.maxAttempts = 200;
  const SceneResult failed = generator.sampleScene(generator.prepare(radius), 5, 0);
  EXPECT_FALSE(failed.success);
  EXPECT_NE(failed.message.find("fixture 'bin1'"), std::string::npos) << failed.message;
}

// ---- Meshes ----

TEST(FclChecker, NonConvexMeshesNestWhereCirclesCannot) {
  const auto config = build("objects:\n  l: {shape: mesh, mesh: meshes/l_block.stl}\n");
  const ObjectPtr l = config->findObjectPtr("l");
  ASSERT_TRUE(l);
  Scene fcl = fclScene();
  fcl.add("l1", l, Eigen::Vector3d(0, 0, 0.015));
  // Turned half a turn, its arms close the first one's open corner: the nearest corners of the
  // arms are 5 mm apart in x and in y, 7.07 mm in all.
  EXPECT_EQ(fcl.test(l, Eigen::Vector3d(0.025, 0.025, 0.015), yaw(M_PI)), kNone);
  // Arms crossing.
  EXPECT_EQ(fcl.test(l, Eigen::Vector3d(0.0, 0.0, 0.015), yaw(M_PI)), 0);
  EXPECT_EQ(fcl.test(l, Eigen::Vector3d(0.01, 0.005, 0.015), yaw(M_PI / 2)), 0);
  // The 7.07 mm clearance is more than a 7.0 mm margin and less than a 7.2 mm one.
  Scene wide = fclScene(0.0070);
  wide.add("l1", l, Eigen::Vector3d(0, 0, 0.015));
  EXPECT_EQ(wide.test(l, Eigen::Vector3d(0.025, 0.025, 0.015), yaw(M_PI)), kNone);
  Scene wider = fclScene(0.0072);
  wider.add("l1", l, Eigen::Vector3d(0, 0, 0.015));
  EXPECT_EQ(wider.test(l, Eigen::Vector3d(0.025, 0.025, 0.015), yaw(M_PI)), 0);

  Scene radius = radiusScene();
  radius.add("l1", l, Eigen::Vector3d(0, 0, 0.015));
  EXPECT_EQ(radius.test(l, Eigen::Vector3d(0.025, 0.025, 0.015), yaw(M_PI)), 0);
}

TEST(FclChecker, MeshGeometryIsSharedBetweenCheckersAndThreads) {
  // Two generators over the same configuration, many threads: same scenes as one thread.
  const auto config = buildFile("config/pick_place_bins.yaml");
  const SceneGenerator generator(config);
  const PreparedRequest request = generator.prepare(SampleRequest());
  const std::vector<SceneResult> one = generator.sampleScenes(request, 9, 64, 1);
  const std::vector<SceneResult> four = generator.sampleScenes(request, 9, 64, 4);
  ASSERT_EQ(one.size(), four.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    ASSERT_EQ(one[i].placements.size(), four[i].placements.size());
    for (std::size_t k = 0; k < one[i].placements.size(); ++k) {
      EXPECT_EQ(one[i].placements[k].position, four[i].placements[k].position);
      EXPECT_EQ(one[i].placements[k].attempts, four[i].placements[k].attempts);
    }
  }
}

// ---- Request fixtures ----

TEST(FclChecker, RequestFixturesWithShapesAreAvoided) {
  const std::string yaml = R"(
collision_check: fcl
objects:
  b0: {shape: sphere, radius: 0.03}
  b1: {shape: sphere, radius: 0.03}
  b2: {shape: sphere, radius: 0.03}
  b3: {shape: sphere, radius: 0.03}
  b4: {shape: sphere, radius: 0.03}
  b5: {shape: sphere, radius: 0.03}
samplers:
  - name: Balls
    objects: [b0, b1, b2, b3, b4, b5]
    x_range: [-0.25, 0.25]
    y_range: [-0.25, 0.25]
    ensure_object_boundary_in_range: false
    reference_pos: [0, 0, 0]
)";
  const SceneGenerator generator(build(yaml));
  SampleRequest request;
  RequestFixture box;
  box.name = "crate";
  box.shape = Shape::box(Eigen::Vector3d(0.3, 0.1, 0.2));
  box.position = Eigen::Vector3d(0.0, 0.05, 0.05);
  box.orientation = yaw(0.6);
  RequestFixture post;
  post.name = "post";
  post.shape = Shape::cylinder(0.05, 0.4);
  post.position = Eigen::Vector3d(-0.15, -0.15, 0.2);
  request.fixtures = {box, post};
  const PreparedRequest prepared = generator.prepare(request);
  const std::vector<SceneResult> scenes = generator.sampleScenes(prepared, 3, 200, 2);
  Eigen::Isometry3d boxPose = Eigen::Translation3d(box.position) * box.orientation;
  for (const SceneResult& scene : scenes) {
    ASSERT_TRUE(scene.success) << scene.message;
    for (const ObjectPlacement& p : scene.placements) {
      EXPECT_GE(pointBoxDistance(p.position, box.shape->size, boxPose), 0.03 - 1e-6) << p.name;
      const double radial = (p.position.head<2>() - post.position.head<2>()).norm();
      EXPECT_GE(radial, 0.05 + 0.03 - 1e-6) << p.name;  // the post is taller than the balls
    }
  }
  // The same request in radius mode keeps the balls' centres outside the fixtures' circles.
  request.collisionCheck = CollisionMode::Radius;
  const SceneResult r = generator.sampleScene(generator.prepare(request), 3, 0);
  ASSERT_TRUE(r.success) << r.message;
}

// ---- radius_and_fcl ----

TEST(CombinedChecker, BothTestsMustPass) {
  const std::unique_ptr<CollisionChecker> both =
      makeCollisionChecker(CollisionMode::RadiusAndFcl, 0.0);
  EXPECT_TRUE(both->needsOrientation());
  EXPECT_TRUE(makeCollisionChecker(CollisionMode::Fcl, 0.0)->needsOrientation());
  EXPECT_FALSE(makeCollisionChecker(CollisionMode::Radius, 0.0)->needsOrientation());

  ObjectOverrides small;
  small.hasHorizontalRadius = true;
  small.horizontalRadius = 0.01;
  const ObjectPtr a = stick("a", small);
  const ObjectPtr b = stick("b", small);
  Scene scene(makeCollisionChecker(CollisionMode::RadiusAndFcl, 0.0));
  scene.add("a", a, Eigen::Vector3d(0, 0, 0.01));
  // Circles apart, geometry crossing: only FCL rejects.
  EXPECT_EQ(scene.test(b, Eigen::Vector3d(0.09, 0.06, 0.01), yaw(M_PI / 2)), 0);
  // Circles overlapping, geometry apart: only the radius test rejects.
  EXPECT_EQ(scene.test(b, Eigen::Vector3d(0.0, 0.015, 0.01)), 0);
  // Both clear.
  EXPECT_EQ(scene.test(b, Eigen::Vector3d(0.0, 0.05, 0.01)), kNone);
  EXPECT_THROW(CombinedChecker(nullptr, std::make_unique<RadiusChecker>()), std::invalid_argument);
}

// ---- Packing ----

/// Placements before the failure, per scene, for @p mode on config/long_boxes.yaml (the
/// placements point into @p config).
std::vector<std::size_t> packedCounts(const std::shared_ptr<SceneConfig>& config,
                                      CollisionMode mode, std::vector<SceneResult>* out = nullptr) {
  const SceneGenerator generator(config);
  SampleRequest request;
  request.collisionCheck = mode;
  const std::vector<SceneResult> scenes =
      generator.sampleScenes(generator.prepare(request), 2024, 10, 2);
  std::vector<std::size_t> counts;
  for (const SceneResult& scene : scenes) {
    EXPECT_FALSE(scene.success);  // 40 sticks never fit
    counts.push_back(scene.placements.size());
  }
  if (out != nullptr) {
    *out = scenes;
  }
  return counts;
}

TEST(FclChecker, PacksClearlyMoreLongBoxesThanRadius) {
  const std::shared_ptr<SceneConfig> config = buildFile("config/long_boxes.yaml");
  std::vector<SceneResult> fclScenes;
  const std::vector<std::size_t> radius = packedCounts(config, CollisionMode::Radius);
  const std::vector<std::size_t> fcl = packedCounts(config, CollisionMode::Fcl, &fclScenes);
  double radiusMean = 0.0;
  double fclMean = 0.0;
  for (std::size_t i = 0; i < radius.size(); ++i) {
    radiusMean += static_cast<double>(radius[i]) / radius.size();
    fclMean += static_cast<double>(fcl[i]) / fcl.size();
    EXPECT_LE(radius[i], 7u);  // circles of 0.1005 m in a 0.4 m square
    EXPECT_GE(fcl[i], 10u);
  }
  EXPECT_GT(fclMean, 3.0 * radiusMean) << "fcl " << fclMean << ", radius " << radiusMean;
  // No two accepted sticks overlap (separating axes on their footprints; all lie on the table).
  for (const SceneResult& scene : fclScenes) {
    for (std::size_t i = 0; i < scene.placements.size(); ++i) {
      for (std::size_t j = i + 1; j < scene.placements.size(); ++j) {
        EXPECT_LE(rectangleOverlap(footprint(scene.placements[i]), footprint(scene.placements[j])),
                  1e-6)
            << scene.placements[i].name << " and " << scene.placements[j].name;
      }
    }
  }
}

TEST(FclChecker, NoCheckWhenEnsureValidPlacementIsOff) {
  const std::string yaml = R"(
collision_check: fcl
objects:
  slab: {shape: box, size: [1.0, 1.0, 0.2]}
  cube: {shape: box, size: [0.05, 0.05, 0.05]}
fixtures:
  - {name: block, object: slab, position: [0, 0, 0]}
samplers:
  - name: Inside
    objects: [cube]
    x_range: [-0.1, 0.1]
    y_range: [-0.1, 0.1]
    ensure_valid_placement: false
    reference_pos: [0, 0, 0]
    sample_args: {on_top: false}
)";
  const SceneGenerator generator(build(yaml));
  const SceneResult scene = generator.sampleScene(generator.prepare(SampleRequest()), 1, 0);
  ASSERT_TRUE(scene.success) << scene.message;
  EXPECT_EQ(scene.placements.front().attempts, 1u);  // placed inside the slab, unchecked
}

}  // namespace
}  // namespace placement_samplers

namespace placement_samplers {
namespace {

// The broadphase is a list up to FclChecker::kDefaultListLimit placed bodies and FCL's tree
// beyond: both must accept and reject the same candidates, so the same seeds give the same
// scenes with the list only, the tree only and the default switch (60 sticks: the switch is
// crossed in every scene), and no two placed sticks overlap.
TEST(FclChecker, ListAndTreeBroadphaseGiveTheSameScenes) {
  std::ostringstream yaml;
  yaml << "collision_check: fcl\nobjects:\n";
  for (int i = 0; i < 60; ++i) {
    yaml << "  s" << i << ": {shape: box, size: [0.12, 0.02, 0.02]}\n";
  }
  yaml << "samplers:\n  - name: Sticks\n    objects: [";
  for (int i = 0; i < 60; ++i) {
    yaml << (i > 0 ? ", " : "") << "s" << i;
  }
  yaml << "]\n    x_range: [-0.45, 0.45]\n    y_range: [-0.45, 0.45]\n    max_attempts: 200\n";
  const SceneGenerator generator(build(yaml.str()));
  const PreparedRequest request = generator.prepare(SampleRequest());
  std::vector<std::vector<ObjectPlacement>> scenes[3];
  // A list, a tree, and a switch from one to the other within each scene.
  constexpr std::size_t kSwitch = 32;
  const std::size_t limits[3] = {std::numeric_limits<std::size_t>::max(), 0, kSwitch};
  for (int k = 0; k < 3; ++k) {
    FclChecker checker(0.0, limits[k]);
    Engine engine;
    SampleContext context(engine, checker);
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      engine = Engine(seed);
      context.clear();
      request.sampler->sample(context, request.reference, request.onTop);
      scenes[k].push_back(context.placements());
    }
  }
  for (std::size_t s = 0; s < scenes[0].size(); ++s) {
    ASSERT_GT(scenes[0][s].size(), kSwitch + 5) << "scene " << s;
    for (int k = 1; k < 3; ++k) {
      ASSERT_EQ(scenes[k][s].size(), scenes[0][s].size()) << "scene " << s << ", checker " << k;
      for (std::size_t i = 0; i < scenes[0][s].size(); ++i) {
        EXPECT_EQ(scenes[k][s][i].position, scenes[0][s][i].position);
        EXPECT_EQ(scenes[k][s][i].attempts, scenes[0][s][i].attempts);
      }
    }
    for (std::size_t i = 0; i < scenes[0][s].size(); ++i) {
      for (std::size_t j = i + 1; j < scenes[0][s].size(); ++j) {
        EXPECT_LE(rectangleOverlap(footprint(scenes[0][s][i]), footprint(scenes[0][s][j])), 1e-6);
      }
    }
  }
}

TEST(CollisionMode, NamesReadBackAndUnknownNamesAreRefused) {
  for (const CollisionMode mode :
       {CollisionMode::Radius, CollisionMode::Fcl, CollisionMode::RadiusAndFcl}) {
    const std::optional<CollisionMode> back = collisionModeFromName(collisionModeName(mode));
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(*back, mode);
  }
  EXPECT_STREQ(collisionModeName(CollisionMode::RadiusAndFcl), "radius_and_fcl");
  EXPECT_FALSE(collisionModeFromName("Radius").has_value());
  EXPECT_FALSE(collisionModeFromName("").has_value());
}

}  // namespace
}  // namespace placement_samplers
