// MJCF objects read as robosuite reads them: the three sites exactly, collision geoms through
// nested bodies (MuJoCo's defaults, fromto and degrees), visual geoms left out, both layouts,
// meshes with their scale, and every error naming its cause.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/geometry/mjcf_geometry.hpp"

namespace placement_samplers {
namespace {

const std::string kData = std::string(PLACEMENT_SAMPLERS_SOURCE_DIR) + "/test/data/mjcf/";

std::string loadError(const std::string& file) {
  try {
    loadMjcfObject(kData + file, 100000);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no ConfigError";
}

TEST(MjcfGeometry, SitesAndCollisionGeomsOfTheCurrentLayout) {
  const MjcfObject o = loadMjcfObject(kData + "box_object.xml", 100000);
  EXPECT_EQ(o.bottomOffset, Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(o.topOffset, Eigen::Vector3d(0, 0, 0.08));
  // robosuite takes the site's x alone (MujocoXMLObject.horizontal_radius), not its x-y norm.
  EXPECT_DOUBLE_EQ(o.horizontalRadius, 0.06);
  EXPECT_EQ(o.visualGeoms, 1u);
  ASSERT_EQ(o.shapes.size(), 2u);
  // The default class gives the box its half sizes: full extents here.
  EXPECT_EQ(o.shapes[0].type, ShapeType::Box);
  EXPECT_TRUE(o.shapes[0].size.isApprox(Eigen::Vector3d(0.04, 0.06, 0.08)));
  EXPECT_TRUE(o.shapes[0].pose.translation().isApprox(Eigen::Vector3d(0, 0, 0.04)));
  // fromto along the handle body's x, that body turned 90 degrees about z: along y here.
  const Shape& bar = o.shapes[1];
  EXPECT_EQ(bar.type, ShapeType::Capsule);
  EXPECT_NEAR(bar.radius, 0.01, 1e-12);
  EXPECT_NEAR(bar.length, 0.1, 1e-12);
  EXPECT_TRUE(bar.pose.translation().isApprox(Eigen::Vector3d(0.1, 0.05, 0.04), 1e-9))
      << bar.pose.translation().transpose();
  EXPECT_NEAR(std::abs((bar.pose.linear() * Eigen::Vector3d::UnitZ()).y()), 1.0, 1e-9);
}

TEST(MjcfGeometry, OlderCollisionAndVisualBodies) {
  const MjcfObject o = loadMjcfObject(kData + "old_layout.xml", 100000);
  ASSERT_EQ(o.shapes.size(), 1u);
  EXPECT_EQ(o.visualGeoms, 1u);
  EXPECT_EQ(o.shapes[0].type, ShapeType::Cylinder);
  EXPECT_NEAR(o.shapes[0].radius, 0.03, 1e-12);
  EXPECT_NEAR(o.shapes[0].length, 0.12, 1e-12);
  EXPECT_EQ(o.topOffset, Eigen::Vector3d(0, 0, 0.12));
  EXPECT_DOUBLE_EQ(o.horizontalRadius, 0.03);
}

// MuJoCo moves a mesh to its centre of mass and turns it to its principal axes; the geom pose
// it returns undoes that, so the vertices land where the file and the scale put them.
TEST(MjcfGeometry, MeshesKeepTheirScaleAndPlace) {
  const MjcfObject o = loadMjcfObject(kData + "mesh_object.xml", 100000);
  ASSERT_EQ(o.shapes.size(), 1u);
  ASSERT_EQ(o.shapes[0].type, ShapeType::Mesh);
  ASSERT_TRUE(o.shapes[0].mesh);
  EXPECT_EQ(o.shapes[0].mesh->triangles.size(), 12u);
  const Bounds b = shapesBounds(o.shapes, Eigen::Quaterniond::Identity());
  EXPECT_NEAR(b.bottomZ, 0.0, 1e-6);
  EXPECT_NEAR(b.topZ, 0.08, 1e-6);
  EXPECT_NEAR(b.horizontalRadius, std::hypot(0.06, 0.04), 1e-6);
  try {
    loadMjcfObject(kData + "mesh_object.xml", 11);
    FAIL() << "expected the triangle limit";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "its meshes have more than 11 triangles (limit)");
  }
}

// Textures change no geometry: a texture file that is missing does not stop the load.
TEST(MjcfGeometry, MissingTexturesDoNotBlockLoading) {
  const MjcfObject o = loadMjcfObject(kData + "missing_texture.xml", 100000);
  ASSERT_EQ(o.shapes.size(), 1u);
  EXPECT_TRUE(o.shapes[0].size.isApprox(Eigen::Vector3d(0.04, 0.04, 0.04)));
}

TEST(MjcfGeometry, ErrorsNameTheCause) {
  EXPECT_EQ(loadError("no_top_site.xml"),
            "no site 'top_site' (robosuite reads bottom_site, top_site and "
            "horizontal_radius_site)");
  // The files a document names are read before MuJoCo sees it.
  EXPECT_EQ(loadError("missing_mesh.xml"), "<mesh> 'gone' (line 2) file 'no_such_mesh.stl' (" +
                                               kData +
                                               "no_such_mesh.stl): cannot read the mesh file: "
                                               "file not found");
  EXPECT_EQ(loadError("malformed.xml"),
            "malformed XML: Error=XML_ERROR_PARSING ErrorID=15 (0xf) Line number=3");
  // MuJoCo would read a URDF file too; robosuite's objects are MJCF.
  EXPECT_EQ(loadError("../urdf/chain.urdf"),
            "not an MJCF file: its root element is <robot>, expected <mujoco>");
  EXPECT_NE(loadError("no_such_file.xml").find("file not found"), std::string::npos)
      << loadError("no_such_file.xml");
}

// The shipped examples (config/robosuite_objects/, used by config/pick_place_mjcf.yaml).
TEST(MjcfGeometry, ShippedExamples) {
  const std::string dir = std::string(PLACEMENT_SAMPLERS_SOURCE_DIR) + "/config/robosuite_objects/";
  const MjcfObject milk = loadMjcfObject(dir + "milk.xml", 100000);
  ASSERT_EQ(milk.shapes.size(), 1u);
  ASSERT_EQ(milk.shapes[0].type, ShapeType::Mesh);
  const Bounds carton = shapesBounds(milk.shapes, Eigen::Quaterniond::Identity());
  EXPECT_NEAR(carton.bottomZ, -0.085, 1e-6);  // the mesh as the file has it
  EXPECT_NEAR(carton.topZ, 0.075, 1e-6);
  EXPECT_DOUBLE_EQ(milk.horizontalRadius, 0.025);
  const MjcfObject bread = loadMjcfObject(dir + "bread.xml", 100000);
  ASSERT_EQ(bread.shapes.size(), 2u);
  EXPECT_EQ(bread.shapes[1].type, ShapeType::Capsule);
  const MjcfObject nut = loadMjcfObject(dir + "square_nut.xml", 100000);
  EXPECT_EQ(nut.shapes.size(), 5u);
  EXPECT_NEAR(shapesBounds(nut.shapes, Eigen::Quaterniond::Identity()).horizontalRadius,
              std::hypot(0.0575, 0.008), 1e-9);
  const MjcfObject can = loadMjcfObject(dir + "can.xml", 100000);
  ASSERT_EQ(can.shapes.size(), 1u);  // the label is visual only
  EXPECT_EQ(can.visualGeoms, 1u);
  EXPECT_NEAR(can.shapes[0].radius, 0.03, 1e-12);
}

// The node's mjcf_param: the same document as text gives the same object.
TEST(MjcfGeometry, TextGivesWhatTheFileGives) {
  std::ifstream in(kData + "box_object.xml");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const MjcfObject fromText = loadMjcfText(text, 100000);
  const MjcfObject fromFile = loadMjcfObject(kData + "box_object.xml", 100000);
  ASSERT_EQ(fromText.shapes.size(), fromFile.shapes.size());
  for (std::size_t i = 0; i < fromFile.shapes.size(); ++i) {
    EXPECT_TRUE(fromText.shapes[i].pose.isApprox(fromFile.shapes[i].pose));
  }
  EXPECT_EQ(fromText.topOffset, fromFile.topOffset);
  EXPECT_EQ(fromText.horizontalRadius, fromFile.horizontalRadius);

  BuildOptions options;
  options.mjcfParam = [&](const std::string& name) {
    if (name != "/box_description") {
      throw ConfigError("no such parameter");
    }
    return text;
  };
  const auto config = buildSceneConfig(
      parseYaml("objects:\n  box: {mjcf_param: /box_description}\n", "t.yaml"), options);
  EXPECT_DOUBLE_EQ(config->findObjectPtr("box")->horizontalRadius, 0.06);
  const auto error = [&](const std::string& yaml, const BuildOptions& o) {
    try {
      buildSceneConfig(parseYaml(yaml, "t.yaml"), o);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no ConfigError");
  };
  EXPECT_EQ(error("objects:\n  box: {mjcf_param: /other}\n", options),
            "objects.box.mjcf_param: object 'box': mjcf_param '/other': no such parameter");
  EXPECT_EQ(error("objects:\n  box: {mjcf_param: /box_description}\n", BuildOptions()),
            "objects.box.mjcf_param: object 'box': mjcf_param is only available in the node "
            "(use mjcf_file here)");
  EXPECT_EQ(error("objects:\n  box: {mjcf_param: /b, mjcf_file: x.xml}\n", options),
            "objects.box: give either mjcf_file or mjcf_param, not both");
}

// In a configuration: robosuite's values come from the sites, the geometry from the geoms.
TEST(MjcfGeometry, ObjectsInAConfiguration) {
  BuildOptions options;
  options.baseDirectory = kData;
  const auto config = buildSceneConfig(parseYaml(R"(
objects:
  box: {mjcf_file: box_object.xml}
  can: {mjcf_file: old_layout.xml, horizontal_radius: 0.05}
)",
                                                 "test.yaml"),
                                       options);
  const ObjectModel& box = *config->findObjectPtr("box");
  EXPECT_EQ(box.topOffset, Eigen::Vector3d(0, 0, 0.08));
  EXPECT_DOUBLE_EQ(box.horizontalRadius, 0.06);
  EXPECT_EQ(box.shapes.size(), 2u);
  EXPECT_DOUBLE_EQ(config->findObjectPtr("can")->horizontalRadius, 0.05);  // override wins
  // init_orientation: the site offsets turn with the object (here a quarter turn about x: the
  // top site (0, 0, 0.08) ends up at (0, -0.08, 0)); the radius is robosuite's number.
  const auto turned = buildSceneConfig(parseYaml(R"(
objects:
  box: {mjcf_file: box_object.xml, init_orientation: [0.7071067811865476, 0, 0, 0.7071067811865476]}
)",
                                                 "test.yaml"),
                                       options);
  const ObjectModel& t = *turned->findObjectPtr("box");
  EXPECT_TRUE(t.topOffset.isApprox(Eigen::Vector3d(0, -0.08, 0), 1e-12)) << t.topOffset.transpose();
  EXPECT_DOUBLE_EQ(t.horizontalRadius, 0.06);
  try {
    buildSceneConfig(parseYaml("objects:\n  x: {mjcf_file: no_top_site.xml}\n", "t.yaml"), options);
    FAIL();
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("objects.x.mjcf_file: object 'x': mjcf_file 'no_top_site.xml' (", 0), 0u)
        << m;
    EXPECT_NE(m.find("): no site 'top_site'"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace placement_samplers
