// MJCF objects as robosuite ships them, and MJCF content that must not hang or exhaust the
// process: materials from robosuite's arena, special files (FIFOs) and large files named by a
// document, its includes, and what MuJoCo allocates for (textures, <size>, height fields,
// composites). Special and large files are made at test time.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/geometry/mjcf_geometry.hpp"
#include "placement_samplers/limits.hpp"
#include "temp_dir.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

namespace fs = std::filesystem;
using test::configError;
using test::TempDir;

const std::string kData = std::string(PLACEMENT_SAMPLERS_SOURCE_DIR) + "/test/data/mjcf/";

/// Sites that make a robosuite object of a document's top-level body.
const std::string kSites =
    "<site name='bottom_site' pos='0 0 -0.01'/><site name='top_site' pos='0 0 0.01'/>"
    "<site name='horizontal_radius_site' pos='0.01 0 0'/>";

/// An object whose body holds @p body (and the sites), with @p head before the worldbody.
std::string document(const std::string& head, const std::string& body) {
  return "<mujoco>" + head + "<worldbody><body>" + body + kSites + "</body></worldbody></mujoco>";
}

std::string loadError(const std::string& path) {
  return configError([&] { loadMjcfObject(path, limits::kMeshTriangles); });
}

std::string mkfifoAt(const TempDir& dir, const std::string& name) {
  const std::string path = dir.path(name);
  EXPECT_EQ(::mkfifo(path.c_str(), 0600), 0) << path;
  return path;
}

// robosuite's objects name materials of the arena they are merged into (its NutAssembly nut
// names "smetal"): materials change no geometry, so such a file loads, with a warning each.
TEST(MjcfLimits, MaterialsTheFileDoesNotDefineAreWarnings) {
  const MjcfObject o = loadMjcfObject(kData + "arena_material.xml", limits::kMeshTriangles);
  ASSERT_EQ(o.shapes.size(), 3u);
  EXPECT_TRUE(o.shapes[0].size.isApprox(Eigen::Vector3d(0.04, 0.06, 0.02)));
  EXPECT_DOUBLE_EQ(o.horizontalRadius, 0.04);
  const std::vector<std::string> expected = {
      "material 'lightwood' names texture 'woodgrain', which the file does not define: left "
      "out (textures change no geometry)",
      "material 'darkwood' is not defined in the file (robosuite's arena defines its "
      "materials): left out (materials change no geometry)",
      "material 'brushed_metal' is not defined in the file (robosuite's arena defines its "
      "materials): left out (materials change no geometry)"};
  EXPECT_EQ(o.warnings, expected);
  // A configuration passes them on, naming the object and the file.
  BuildOptions options;
  options.baseDirectory = kData;
  const auto config = buildSceneConfig(
      parseYaml("objects:\n  nut: {mjcf_file: arena_material.xml}\nsamplers:\n  - {name: S, "
                "objects: [nut], x_range: [-1, 1], y_range: [-1, 1]}\n",
                "t.yaml"),
      options);
  ASSERT_EQ(config->warnings.size(), 3u);
  EXPECT_EQ(config->warnings[2],
            "object 'nut': mjcf_file 'arena_material.xml' (" + kData +
                "arena_material.xml): material 'brushed_metal' is not defined in the file "
                "(robosuite's arena defines its materials): left out (materials change no "
                "geometry)");
  // A file that defines its materials has nothing to warn about.
  EXPECT_TRUE(loadMjcfObject(kData + "missing_texture.xml", 100000).warnings.empty());
}

// A class may change sizes and types: a missing one stays MuJoCo's error, at its line.
TEST(MjcfLimits, MissingClassIsAnError) {
  EXPECT_EQ(loadError(kData + "missing_class.xml"),
            "MuJoCo could not load it: XML Error: unknown default class; Element 'geom', line 5");
}

TEST(MjcfLimits, IncludedFilesAreMergedRelativeToTheDocument) {
  const MjcfObject o = loadMjcfObject(kData + "include_object.xml", limits::kMeshTriangles);
  ASSERT_EQ(o.shapes.size(), 1u);
  EXPECT_EQ(o.shapes[0].type, ShapeType::Mesh);
  EXPECT_EQ(o.shapes[0].mesh->triangles.size(), 12u);
  EXPECT_DOUBLE_EQ(o.horizontalRadius, 0.05);
  EXPECT_TRUE(o.warnings.empty());
  EXPECT_EQ(loadError(kData + "included_twice.xml"),
            "<include> (line 3) file 'parts/materials.xml' (" + kData +
                "parts/materials.xml): the file is included twice");
}

// A FIFO that no one writes to blocked the load for ever; a directory or device is no better.
TEST(MjcfLimits, SpecialFilesAreRefusedWithoutWaiting) {
  const TempDir dir("placement_samplers_mjcf");
  const std::string fifo = mkfifoAt(dir, "object.xml");
  EXPECT_EQ(loadError(fifo), "cannot read the MJCF file: not a regular file");
  EXPECT_EQ(loadError("/dev/zero"), "cannot read the MJCF file: not a regular file");
  EXPECT_EQ(loadError(dir.path("")), "cannot read the MJCF file: it is a directory");

  mkfifoAt(dir, "part.stl");
  const std::string mesh = dir.file(
      "mesh.xml",
      document("<asset><mesh name='m' file='part.stl'/></asset>", "<geom type='mesh' mesh='m'/>"));
  EXPECT_EQ(loadError(mesh), "<mesh> 'm' (line 1) file 'part.stl' (" + dir.path("part.stl") +
                                 "): cannot read the mesh file: not a regular file");

  mkfifoAt(dir, "part.xml");
  const std::string include = dir.file("include.xml", document("<include file='part.xml'/>", ""));
  EXPECT_EQ(loadError(include), "<include> (line 1) file 'part.xml' (" + dir.path("part.xml") +
                                    "): cannot read the included file: not a regular file");

  mkfifoAt(dir, "ground.png");
  const std::string hfield =
      dir.file("hfield.xml",
               document("<asset><hfield name='h' file='ground.png' size='1 1 1 1'/></asset>", ""));
  EXPECT_EQ(loadError(hfield), "<hfield> 'h' (line 1) file 'ground.png' (" +
                                   dir.path("ground.png") +
                                   "): cannot read the height field file: not a regular file");
}

// MuJoCo read a mesh file named in an MJCF file whatever its size (1 GB for a 1 GiB sparse
// file before its own error); the files are now read here, within the mesh limit.
TEST(MjcfLimits, LargeFilesAreRefusedBeforeTheyAreRead) {
  const TempDir dir("placement_samplers_mjcf");
  const std::string big = dir.path("big.stl");
  { std::ofstream(big) << "solid x\n"; }
  fs::resize_file(big, std::uintmax_t{1} << 30);  // sparse: nothing is written
  const std::string mesh =
      dir.file("mesh.xml",
               document("<compiler meshdir='.'/>\n<asset><mesh name='m' file='big.stl'/></asset>",
                        "<geom type='mesh' mesh='m'/>"));
  EXPECT_EQ(loadError(mesh), "<mesh> 'm' (line 2) file 'big.stl' (" + dir.path("./big.stl") +
                                 "): the mesh file is larger than the limit of 16777216 bytes "
                                 "(16 MiB): it has 1073741824 bytes");
  // The document with its includes: limits::kUrdfBytes together.
  const std::string padding(limits::kUrdfBytes / 2 + 1, ' ');
  dir.file("a.xml", "<mujoco>" + padding + "</mujoco>");
  dir.file("b.xml", "<mujoco>" + padding + "</mujoco>");
  const std::string two =
      dir.file("two.xml", document("<include file='a.xml'/><include file='b.xml'/>", ""));
  EXPECT_EQ(loadError(two),
            "<include> (line 1) file 'b.xml' (" + dir.path("b.xml") +
                "): the document and its included files are larger than the limit of 8388608 "
                "bytes together");
  // MuJoCo's own messages about a file name the file, not its name inside MuJoCo.
  dir.file("empty.stl", std::string(84, '\0'));
  const std::string empty = dir.file(
      "empty.xml",
      document("<asset><mesh name='m' file='empty.stl'/></asset>", "<geom type='mesh' mesh='m'/>"));
  const std::string message = loadError(empty);
  EXPECT_NE(message.find("'" + dir.path("empty.stl") + "'"), std::string::npos) << message;
  EXPECT_EQ(message.find("placement_samplers_file"), std::string::npos) << message;
}

// What changes no geometry is left out of what MuJoCo compiles: the 20000 x 20000 texture
// (1.2 GB, held after a reload), njmax 15000, the sensor of 10^8 values and the keyframes no
// longer cost anything.
TEST(MjcfLimits, ContentThatChangesNoGeometryIsLeftOut) {
  const MjcfObject o = loadMjcfObject(kData + "heavy_content.xml", limits::kMeshTriangles);
  ASSERT_EQ(o.shapes.size(), 1u);
  EXPECT_TRUE(o.shapes[0].size.isApprox(Eigen::Vector3d(0.04, 0.04, 0.04)));
  EXPECT_DOUBLE_EQ(o.topOffset.z(), 0.02);
  EXPECT_TRUE(o.warnings.empty());
}

TEST(MjcfLimits, WhatMujocoAllocatesForIsBounded) {
  EXPECT_EQ(loadError(kData + "huge_hfield.xml"),
            "<hfield> 'terrain' (line 4): more than 4194304 height samples (limit)");
  EXPECT_EQ(loadError(kData + "huge_composite.xml"),
            "<composite> (line 10): count makes more than 10000 bodies (limit)");
  std::string bodies;
  for (std::size_t i = 0; i < limits::kMjcfBodies; ++i) {
    bodies += "<body/>";
  }
  EXPECT_EQ(configError([&] { loadMjcfText(document("", bodies), 100); }),
            "it has 10001 bodies, more than the limit of 10000");
  std::string geoms;
  for (std::size_t i = 0; i <= limits::kMjcfGeoms; ++i) {
    geoms += "<geom size='0.01'/>";
  }
  EXPECT_EQ(configError([&] { loadMjcfText(document("", geoms), 100); }),
            "it has 10001 geoms, more than the limit of 10000");
  // A height field file's size is its header's.
  const TempDir dir("placement_samplers_mjcf");
  std::string png("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16);
  png += std::string("\0\0\x10\0\0\0\x10\0", 8);  // 4096 x 4096 pixels
  dir.file("ground.png", png);
  const std::string hfield =
      dir.file("hfield.xml",
               document("<asset><hfield name='h' file='ground.png' size='1 1 1 1'/></asset>", ""));
  EXPECT_EQ(loadError(hfield), "<hfield> 'h' (line 1): more than 4194304 height samples (limit)");
}

// MuJoCo's messages point at the line of the user's file, whatever was left out before it.
TEST(MjcfLimits, MujocoErrorsKeepTheFilesLineNumbers) {
  const MjcfObject o = loadMjcfObject(kData + "box_object.xml", limits::kMeshTriangles);
  EXPECT_FALSE(o.shapes.empty());
  const TempDir dir("placement_samplers_mjcf");
  const std::string bad = dir.file("bad.xml",
                                   "<mujoco>\n<size njmax='10'/>\n<asset>\n<texture name='t' "
                                   "builtin='flat' width='2' height='2'/>\n</asset>\n<worldbody>\n"
                                   "<body>\n<geom type='box' size='1 1 1' bogus='1'/>\n</body>\n"
                                   "</worldbody>\n</mujoco>\n");
  EXPECT_EQ(loadError(bad),
            "MuJoCo could not load it: XML Error: Schema violation: unrecognized attribute: "
            "'bogus'; ; Element 'geom', line 8");
}

}  // namespace
}  // namespace placement_samplers
