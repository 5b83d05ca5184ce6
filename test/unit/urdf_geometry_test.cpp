// Geometry from URDF: primitives, rotated primitives, fixed-joint chains and meshes against
// values computed by hand; urdf_file / urdf_param objects in the configuration; every error
// with its message.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/config/object_config.hpp"
#include "placement_samplers/geometry/urdf_geometry.hpp"

namespace placement_samplers {
namespace {

const std::string kSourceDir = PLACEMENT_SAMPLERS_SOURCE_DIR;
const std::string kData = kSourceDir + "/test/data";

std::vector<Shape> shapesOf(const std::string& relativeFile, const std::string& link = "") {
  MeshLoader meshes;
  const std::string path = kData + "/urdf/" + relativeFile;
  return urdfCollisionShapes(readTextFile(path), link, meshes, kData + "/urdf");
}

ObjectModel objectOf(const std::vector<Shape>& shapes) {
  return makeObject("o", shapes, Eigen::Quaterniond::Identity());
}

/// The ConfigError message of urdfCollisionShapes on @p xml.
std::string urdfError(const std::string& xml, const std::string& link = "") {
  MeshLoader meshes;
  try {
    urdfCollisionShapes(xml, link, meshes, kData + "/urdf");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

std::string fileError(const std::string& relativeFile, const std::string& link = "") {
  return urdfError(readTextFile(kData + "/urdf/" + relativeFile), link);
}

std::string oneLink(const std::string& collision) {
  return "<robot name='r'><link name='base'><collision>" + collision +
         "</collision></link></robot>";
}

BuildOptions options() {
  BuildOptions o;
  o.baseDirectory = kData;
  o.packageResolver = [](const std::string& package) {
    return package == "placement_samplers" ? kSourceDir : std::string();
  };
  return o;
}

ObjectModel configObject(const std::string& entry, const BuildOptions& o = options()) {
  const ConfigNode root = parseYaml("objects:\n  part: " + entry + "\n", "test.yaml");
  MeshLoader meshes(o.packageResolver, o.baseDirectory);
  return parseObject("part", root.at("objects").at("part"), o, meshes);
}

std::string configError(const std::string& entry, const BuildOptions& o = options()) {
  try {
    configObject(entry, o);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

// ---- Derived values ----

TEST(UrdfGeometry, PrimitivesOfOneLink) {
  const std::vector<Shape> shapes = shapesOf("primitives.urdf");
  ASSERT_EQ(shapes.size(), 3u);
  EXPECT_EQ(shapes[0].type, ShapeType::Box);
  EXPECT_EQ(shapes[0].size, Eigen::Vector3d(0.2, 0.1, 0.1));
  EXPECT_TRUE(shapes[0].pose.translation().isApprox(Eigen::Vector3d(0.1, 0, 0.05)));
  EXPECT_EQ(shapes[1].type, ShapeType::Cylinder);
  EXPECT_DOUBLE_EQ(shapes[1].radius, 0.03);
  EXPECT_DOUBLE_EQ(shapes[1].length, 0.2);
  // rpy (pi/2, 0, 0) lays the cylinder's axis along -y.
  EXPECT_NEAR(std::abs(shapes[1].pose.linear().col(2).y()), 1.0, 1e-12);
  EXPECT_EQ(shapes[2].type, ShapeType::Sphere);

  // By hand: box x [0, 0.2], y [-0.05, 0.05], z [0, 0.1], farthest corner (0.2, 0.05);
  // cylinder y [-0.1, 0.1], x and z [-0.03, 0.03]; sphere z [-0.14, -0.06].
  const ObjectModel o = objectOf(shapes);
  EXPECT_NEAR(o.bottomOffset.z(), -0.14, 1e-12);
  EXPECT_NEAR(o.topOffset.z(), 0.1, 1e-12);
  EXPECT_NEAR(o.horizontalRadius, std::sqrt(0.2 * 0.2 + 0.05 * 0.05), 1e-12);
  // The cylinder alone: rim points (0.03, 0.1) at the ends.
  const ObjectModel cylinder = objectOf({shapes[1]});
  EXPECT_NEAR(cylinder.horizontalRadius, std::sqrt(0.03 * 0.03 + 0.1 * 0.1), 1e-9);
  EXPECT_NEAR(cylinder.bottomOffset.z(), -0.03, 1e-12);
  EXPECT_NEAR(cylinder.topOffset.z(), 0.03, 1e-12);
}

TEST(UrdfGeometry, WholeModelThroughJointOriginsAtZero) {
  const std::vector<Shape> shapes = shapesOf("chain.urdf");
  ASSERT_EQ(shapes.size(), 3u);  // base, hand, finger; arm has none
  // hand: up 0.1, turned 90 deg, then 0.2 along the turned x = +y.
  EXPECT_TRUE(shapes[1].pose.translation().isApprox(Eigen::Vector3d(0, 0.2, 0.1), 1e-12));
  // finger: 0.05 further along the hand's x (+y), its cylinder axis along the hand's x.
  EXPECT_TRUE(shapes[2].pose.translation().isApprox(Eigen::Vector3d(0, 0.25, 0.1), 1e-12));
  EXPECT_NEAR(std::abs(shapes[2].pose.linear().col(2).y()), 1.0, 1e-12);

  // By hand: base z [-0.05, 0.05]; hand box x [-0.05, 0.05], y [0.15, 0.25], z [0.05, 0.15];
  // finger cylinder along y from 0.2 to 0.3, radius 0.01 around (x, z) = (0, 0.1): its far rim
  // point (0.01, 0.3) sets the radius.
  const ObjectModel o = objectOf(shapes);
  EXPECT_NEAR(o.bottomOffset.z(), -0.05, 1e-12);
  EXPECT_NEAR(o.topOffset.z(), 0.15, 1e-12);
  EXPECT_NEAR(o.horizontalRadius, std::sqrt(0.01 * 0.01 + 0.3 * 0.3), 1e-9);
}

TEST(UrdfGeometry, OneLinkInItsOwnFrame) {
  const std::vector<Shape> hand = shapesOf("chain.urdf", "hand");
  ASSERT_EQ(hand.size(), 1u);
  EXPECT_TRUE(hand[0].pose.isApprox(Eigen::Isometry3d::Identity()));
  const ObjectModel o = objectOf(hand);
  EXPECT_NEAR(o.bottomOffset.z(), -0.05, 1e-12);
  EXPECT_NEAR(o.topOffset.z(), 0.05, 1e-12);
  EXPECT_NEAR(o.horizontalRadius, std::sqrt(0.005), 1e-12);

  const ObjectModel finger = objectOf(shapesOf("chain.urdf", "finger"));
  EXPECT_NEAR(finger.bottomOffset.z(), -0.05, 1e-12);
  EXPECT_NEAR(finger.horizontalRadius, 0.01, 1e-9);
}

TEST(UrdfGeometry, MeshScaledAndRelativeToTheUrdfFile) {
  const std::vector<Shape> shapes = shapesOf("mesh.urdf");
  ASSERT_EQ(shapes.size(), 1u);
  ASSERT_EQ(shapes[0].type, ShapeType::Mesh);
  ASSERT_TRUE(shapes[0].mesh);
  EXPECT_EQ(shapes[0].mesh->source, "../meshes/tetra.stl");
  // tetra.stl vertices (0.1, 0, 0), (0, 0.2, 0), (0, 0, 0.3), (-0.04, -0.03, -0.05), scaled by
  // (3, 1, 0.5) and raised 0.1: z from 0.075 to 0.25, farthest (0.3, 0).
  const ObjectModel o = objectOf(shapes);
  EXPECT_NEAR(o.bottomOffset.z(), 0.075, 1e-7);  // STL stores 32-bit floats
  EXPECT_NEAR(o.topOffset.z(), 0.25, 1e-7);
  EXPECT_NEAR(o.horizontalRadius, 0.3, 1e-7);
}

TEST(UrdfGeometry, ExampleUrdfs) {
  const ObjectModel bin = configObject("{urdf_file: package://placement_samplers/urdf/bin.urdf}");
  EXPECT_EQ(bin.shapes.size(), 5u);
  EXPECT_NEAR(bin.bottomOffset.z(), 0.0, 1e-12);
  EXPECT_NEAR(bin.topOffset.z(), 0.1, 1e-12);
  EXPECT_NEAR(bin.horizontalRadius, std::sqrt(0.2 * 0.2 + 0.25 * 0.25), 1e-12);

  const ObjectModel table =
      configObject("{urdf_file: package://placement_samplers/urdf/table.urdf}");
  EXPECT_EQ(table.shapes.size(), 5u);
  EXPECT_NEAR(table.bottomOffset.z(), -0.74, 1e-12);
  EXPECT_NEAR(table.topOffset.z(), 0.0, 1e-12);
  EXPECT_NEAR(table.horizontalRadius, std::sqrt(0.5 * 0.5 + 0.4 * 0.4), 1e-12);
  const ObjectModel leg = configObject(
      "{urdf_file: package://placement_samplers/urdf/table.urdf, link: leg_front_left}");
  EXPECT_NEAR(leg.bottomOffset.z(), -0.7, 1e-12);
  EXPECT_NEAR(leg.topOffset.z(), 0.0, 1e-12);

  const ObjectModel block =
      configObject("{urdf_file: package://placement_samplers/urdf/l_block.urdf}");
  ASSERT_EQ(block.shapes.size(), 1u);
  EXPECT_EQ(block.shapes[0].type, ShapeType::Mesh);
  EXPECT_NEAR(block.bottomOffset.z(), -0.015, 1e-7);
  EXPECT_NEAR(block.topOffset.z(), 0.015, 1e-7);
  EXPECT_NEAR(block.horizontalRadius, std::sqrt(0.04 * 0.04 * 2), 1e-7);
}

// ---- Configuration ----

TEST(UrdfGeometry, OverridesAndInitOrientationApplyToUrdfObjects) {
  const ObjectModel o = configObject(
      "{urdf_file: urdf/chain.urdf, link: hand, horizontal_radius: 0.02, "
      "bottom_offset: [0, 0, -0.2], top_offset: [0, 0, 0.3]}");
  EXPECT_DOUBLE_EQ(o.horizontalRadius, 0.02);
  EXPECT_FALSE(o.radiusBoundsGeometry);  // smaller than the hand's 0.0707
  EXPECT_DOUBLE_EQ(o.bottomOffset.z(), -0.2);
  EXPECT_DOUBLE_EQ(o.topOffset.z(), 0.3);
  // Standing the finger cylinder on its side about x: z span becomes its radius.
  const ObjectModel lying = configObject(
      "{urdf_file: urdf/chain.urdf, link: finger, init_orientation: [0.7071067811865476, 0, 0, "
      "0.7071067811865476]}");
  EXPECT_NEAR(lying.bottomOffset.z(), -0.01, 1e-9);
  EXPECT_NEAR(lying.horizontalRadius, std::sqrt(0.01 * 0.01 + 0.05 * 0.05), 1e-9);
}

TEST(UrdfGeometry, UrdfParamComesFromTheCaller) {
  BuildOptions o = options();
  EXPECT_EQ(configError("{urdf_param: /bin_description}", o),
            "objects.part.urdf_param: object 'part': urdf_param is only available in the node "
            "(use urdf_file here)");
  std::vector<std::string> asked;
  o.urdfParam = [&](const std::string& name) {
    asked.push_back(name);
    if (name != "/bin_description") {
      throw std::runtime_error("parameter '" + name + "' is not set");
    }
    return readTextFile(kSourceDir + "/urdf/bin.urdf");
  };
  const ObjectModel bin = configObject("{urdf_param: /bin_description}", o);
  EXPECT_EQ(bin.shapes.size(), 5u);
  EXPECT_NEAR(bin.topOffset.z(), 0.1, 1e-12);
  EXPECT_EQ(asked, std::vector<std::string>{"/bin_description"});
  EXPECT_EQ(configError("{urdf_param: other}", o),
            "objects.part.urdf_param: object 'part': urdf_param 'other': parameter 'other' is not "
            "set");
  EXPECT_EQ(configError("{urdf_param: /bin_description, link: lid}", o),
            "objects.part.urdf_param: object 'part': urdf_param '/bin_description': link 'lid' "
            "does not exist (links: bin)");
  // The whole build passes the options down.
  const auto config = buildSceneConfig(
      parseYaml("objects:\n  bin: {urdf_param: /bin_description}\n", "test.yaml"), o);
  EXPECT_EQ(config->findObject("bin")->shapes.size(), 5u);
}

TEST(UrdfGeometry, ConfigurationErrors) {
  EXPECT_EQ(configError("{urdf_file: urdf/bin.urdf, urdf_param: /bin}"),
            "objects.part: give either urdf_file or urdf_param, not both");
  EXPECT_EQ(configError("{urdf_file: urdf/bin.urdf, shape: box}"),
            "objects.part: unknown key 'shape' (expected one of: urdf_file, urdf_param, link, "
            "horizontal_radius, bottom_offset, top_offset, init_orientation, density)");
  EXPECT_EQ(configError("{urdf_file: urdf/chain.urdf, link: ''}"),
            "objects.part.link: expected a link name");
  EXPECT_EQ(configError("{urdf_file: urdf/nope.urdf}"),
            "objects.part.urdf_file: object 'part': urdf_file 'urdf/nope.urdf' (" + kData +
                "/urdf/nope.urdf): file not found");
  EXPECT_EQ(configError("{urdf_file: package://no_such_package/x.urdf}"),
            "objects.part.urdf_file: object 'part': urdf_file 'package://no_such_package/x.urdf': "
            "package 'no_such_package' not found by the package resolver");
  EXPECT_EQ(configError("{urdf_file: urdf/missing_mesh.urdf}"),
            "objects.part.urdf_file: object 'part': urdf_file 'urdf/missing_mesh.urdf' (" + kData +
                "/urdf/missing_mesh.urdf): link 'part', collision 0: mesh "
                "'../meshes/does_not_exist.stl' (" +
                kData +
                "/meshes/does_not_exist.stl): file "
                "not found");
  EXPECT_EQ(
      configError("{urdf_file: urdf/no_collision.urdf}"),
      "objects.part.urdf_file: object 'part': urdf_file 'urdf/no_collision.urdf' (" + kData +
          "/urdf/no_collision.urdf): no collision geometry in robot 'no_collision' (2 links)");
  // The build names the object under its own key.
  try {
    buildSceneConfig(parseYaml("objects:\n  crate: {urdf_file: urdf/malformed.urdf}\n", "c.yaml"),
                     options());
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("objects.crate.urdf_file: object 'crate': urdf_file "
                                          "'urdf/malformed.urdf' (" +
                                              kData + "/urdf/malformed.urdf): malformed URDF: ",
                                          0),
              0u)
        << e.what();
  }
}

// ---- Errors of the URDF itself ----

TEST(UrdfGeometry, MalformedDocuments) {
  EXPECT_EQ(fileError("malformed.urdf").rfind("malformed URDF: ", 0), 0u)
      << fileError("malformed.urdf");
  EXPECT_EQ(urdfError(""), "malformed URDF: Error document empty.");
  EXPECT_EQ(urdfError("<notarobot/>"),
            "malformed URDF: Could not find the 'robot' element in the xml file");
  EXPECT_EQ(urdfError("<robot name='r'><link name='a'/><link name='b'/></robot>"),
            "malformed URDF: Failed to find root link: Two root links found: [a] and [b]");
  // urdfdom drops a collision element it cannot parse; here that is an error, not less geometry.
  EXPECT_EQ(urdfError(oneLink("<geometry><capsule radius='0.1' length='0.1'/></geometry>")),
            "malformed URDF: Unknown geometry type 'capsule'; Could not parse collision element "
            "for Link [base]");
}

TEST(UrdfGeometry, NonFiniteAndNonPositiveSizes) {
  EXPECT_EQ(urdfError(oneLink("<geometry><box size='0.1 nan 0.1'/></geometry>")),
            "malformed URDF: Unable to parse component [nan] to a double (while parsing a vector "
            "value); Could not parse collision element for Link [base]");
  EXPECT_EQ(urdfError(oneLink("<geometry><sphere radius='1e999'/></geometry>")),
            "malformed URDF: radius [1e999] is not a valid float; Could not parse collision "
            "element for Link [base]");
  EXPECT_EQ(urdfError(oneLink("<origin xyz='0 0 inf'/><geometry><sphere radius='1'/></geometry>")),
            "malformed URDF: Unable to parse component [inf] to a double (while parsing a vector "
            "value); Could not parse collision element for Link [base]");
  EXPECT_EQ(urdfError(oneLink("<geometry><box size='0.1 0 0.1'/></geometry>")),
            "link 'base', collision 0: box size y must be finite and positive, got 0");
  EXPECT_EQ(urdfError(oneLink("<geometry><cylinder radius='-0.1' length='1'/></geometry>")),
            "link 'base', collision 0: cylinder radius must be finite and positive, got -0.1");
  EXPECT_EQ(urdfError(oneLink("<geometry><cylinder radius='0.1' length='0'/></geometry>")),
            "link 'base', collision 0: cylinder length must be finite and positive, got 0");
  EXPECT_EQ(urdfError(oneLink("<geometry><sphere radius='0'/></geometry>")),
            "link 'base', collision 0: sphere radius must be finite and positive, got 0");
  EXPECT_EQ(urdfError("<robot name='r'><link name='base'><collision name='lid'><geometry><mesh "
                      "filename='../meshes/tetra.stl' scale='1 0 1'/></geometry></collision>"
                      "</link></robot>"),
            "link 'base', collision 0 'lid': mesh scale must be three finite positive factors, "
            "got [1, 0, 1]");
}

TEST(UrdfGeometry, MissingLinksAndGeometry) {
  EXPECT_EQ(fileError("chain.urdf", "paw"),
            "link 'paw' does not exist (links: arm, base, finger, hand)");
  EXPECT_EQ(fileError("chain.urdf", "arm"), "link 'arm' has no collision geometry");
  EXPECT_EQ(fileError("no_collision.urdf"),
            "no collision geometry in robot 'no_collision' (2 links)");
}

TEST(UrdfGeometry, MissingUnreadableAndEmptyMeshes) {
  EXPECT_EQ(fileError("missing_mesh.urdf"),
            "link 'part', collision 0: mesh '../meshes/does_not_exist.stl' (" + kData +
                "/meshes/does_not_exist.stl): file not found");
  EXPECT_EQ(fileError("corrupt_mesh.urdf"),
            "link 'part', collision 0: mesh '../meshes/corrupt.stl' (" + kData +
                "/meshes/corrupt.stl): cannot read it as a mesh: Failed to determine STL storage "
                "representation for " +
                kData + "/meshes/corrupt.stl.");
  EXPECT_EQ(fileError("empty_mesh.urdf")
                .rfind("link 'part', collision 0: mesh '../meshes/empty.stl' (" + kData +
                           "/meshes/empty.stl): ",
                       0),
            0u)
      << fileError("empty_mesh.urdf");
  EXPECT_EQ(
      urdfError(oneLink("<geometry><mesh filename='../meshes'/></geometry>")),
      "link 'base', collision 0: mesh '../meshes' (" + kData + "/meshes): not a regular file");
}

TEST(UrdfGeometry, ReadTextFileErrors) {
  EXPECT_THROW(readTextFile(kData + "/urdf/nope.urdf"), ConfigError);
  try {
    readTextFile(kData);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "not a regular file");
  }
}

}  // namespace
}  // namespace placement_samplers
