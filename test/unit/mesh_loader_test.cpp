// Mesh loading: URIs (package://, file://, paths), ROS_PACKAGE_PATH, STL (ASCII and binary),
// OBJ and COLLADA, scale, the per-build cache, mesh objects in the configuration, and errors.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <unistd.h>

#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/geometry/mesh_loader.hpp"
#include "placement_samplers/config/object_config.hpp"

namespace placement_samplers {
namespace {

namespace fs = std::filesystem;

const std::string kSourceDir = PLACEMENT_SAMPLERS_SOURCE_DIR;
const std::string kData = kSourceDir + "/test/data";

/// A fresh directory removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = fs::temp_directory_path() / ("placement_samplers_test_" + std::to_string(::getpid()) +
                                         "_" + std::to_string(counter++));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

  void write(const std::string& relative, const std::string& text) const {
    fs::create_directories((path_ / relative).parent_path());
    std::ofstream(path_ / relative, std::ios::binary) << text;
  }

 private:
  fs::path path_;
};

/// Sets ROS_PACKAGE_PATH for the scope, then puts the old value back.
class PackagePath {
 public:
  explicit PackagePath(const std::optional<std::string>& value) {
    if (const char* old = std::getenv("ROS_PACKAGE_PATH")) {
      old_ = old;
    }
    set(value);
  }
  ~PackagePath() { set(old_); }

 private:
  static void set(const std::optional<std::string>& value) {
    if (value) {
      ::setenv("ROS_PACKAGE_PATH", value->c_str(), 1);
    } else {
      ::unsetenv("ROS_PACKAGE_PATH");
    }
  }
  std::optional<std::string> old_;
};

std::string packageXml(const std::string& name) {
  return "<?xml version=\"1.0\"?>\n<package format=\"3\">\n  <name>" + name +
         "</name>\n  <version>0.0.0</version>\n</package>\n";
}

Eigen::Vector3d lowest(const Mesh& mesh) {
  Eigen::Vector3d lo = mesh.vertices.front();
  for (const Eigen::Vector3d& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
  }
  return lo;
}

Eigen::Vector3d highest(const Mesh& mesh) {
  Eigen::Vector3d hi = mesh.vertices.front();
  for (const Eigen::Vector3d& v : mesh.vertices) {
    hi = hi.cwiseMax(v);
  }
  return hi;
}

std::string loadError(const std::string& path,
                      const Eigen::Vector3d& scale = Eigen::Vector3d::Ones()) {
  try {
    loadMeshFile(path, scale, path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

/// A binary STL of @p triangles (three vertices each, 32-bit floats).
std::string binaryStl(const std::vector<std::array<Eigen::Vector3f, 3>>& triangles) {
  std::string out(80, ' ');
  const std::uint32_t n = static_cast<std::uint32_t>(triangles.size());
  out.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : triangles) {
    const float normal[3] = {0.0f, 0.0f, 0.0f};
    out.append(reinterpret_cast<const char*>(normal), 12);
    for (const Eigen::Vector3f& v : t) {
      out.append(reinterpret_cast<const char*>(v.data()), 12);
    }
    out.append(2, '\0');
  }
  return out;
}

// ---- URIs ----

TEST(MeshLoader, ResolvesUris) {
  const PackageResolver resolver = [](const std::string& package) {
    return package == "assets" ? std::string("/opt/assets") : std::string();
  };
  EXPECT_EQ(resolveUri("package://assets/meshes/a.stl", resolver, ""), "/opt/assets/meshes/a.stl");
  EXPECT_EQ(resolveUri("package://assets/meshes/../b.stl", resolver, "/base"), "/opt/assets/b.stl");
  EXPECT_EQ(resolveUri("file:///data/c.dae", resolver, "/base"), "/data/c.dae");
  EXPECT_EQ(resolveUri("/data/d.obj", resolver, "/base"), "/data/d.obj");
  EXPECT_EQ(resolveUri("meshes/e.stl", resolver, "/base/config"), "/base/config/meshes/e.stl");
  EXPECT_EQ(resolveUri("file://meshes/e.stl", resolver, "/base"), "/base/meshes/e.stl");
  EXPECT_EQ(resolveUri("meshes/e.stl", resolver, ""), "meshes/e.stl");  // the current directory

  auto error = [&](const std::string& uri) {
    try {
      resolveUri(uri, resolver, "/base");
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("package://other/a.stl"),
            "'package://other/a.stl': package 'other' not found by the package resolver");
  EXPECT_EQ(error("package://assets"), "'package://assets': expected package://PACKAGE/PATH");
  EXPECT_EQ(error("package:///a.stl"), "'package:///a.stl': expected package://PACKAGE/PATH");
  EXPECT_EQ(
      error("http://example.com/a.stl"),
      "'http://example.com/a.stl': unsupported URI scheme (use package://, file:// or a path)");
  EXPECT_EQ(error(""), "'': empty path");
  EXPECT_EQ(error("file://"), "'file://': empty path");
}

TEST(MeshLoader, FindsPackagesThroughRosPackagePath) {
  TempDir dir;
  dir.write("ws/src/group/my_assets/package.xml", packageXml("my_assets"));
  dir.write("ws/src/group/my_assets/inner/package.xml", packageXml("nested"));  // not searched
  dir.write("ws/src/ignored/CATKIN_IGNORE", "");
  dir.write("ws/src/ignored/hidden_assets/package.xml", packageXml("hidden_assets"));
  dir.write("checkout/package.xml", packageXml("renamed_assets"));  // directory name differs
  dir.write("share/direct_assets/package.xml", packageXml("direct_assets"));
  const std::string root = dir.path().string();
  {
    PackagePath env(root + "/ws:" + root + "/checkout::" + root + "/share");
    EXPECT_EQ(findPackageInRosPackagePath("my_assets"), root + "/ws/src/group/my_assets");
    EXPECT_EQ(findPackageInRosPackagePath("renamed_assets"), root + "/checkout");
    EXPECT_EQ(findPackageInRosPackagePath("direct_assets"), root + "/share/direct_assets");
    EXPECT_EQ(findPackageInRosPackagePath("nested"), "");
    EXPECT_EQ(findPackageInRosPackagePath("hidden_assets"), "");
    EXPECT_EQ(findPackageInRosPackagePath("unknown"), "");
    // The default resolver of resolveUri and MeshLoader.
    EXPECT_EQ(resolveUri("package://renamed_assets/m/x.stl", PackageResolver(), ""),
              root + "/checkout/m/x.stl");
    try {
      resolveUri("package://unknown/x.stl", PackageResolver(), "");
      FAIL() << "no error";
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()),
                "'package://unknown/x.stl': package 'unknown' not found in "
                "ROS_PACKAGE_PATH (" +
                    root + "/ws:" + root + "/checkout::" + root + "/share)");
    }
  }
  {
    PackagePath env(std::nullopt);
    EXPECT_EQ(findPackageInRosPackagePath("my_assets"), "");
    try {
      resolveUri("package://my_assets/x.stl", PackageResolver(), "");
      FAIL() << "no error";
    } catch (const ConfigError& e) {
      EXPECT_STREQ(e.what(),
                   "'package://my_assets/x.stl': package 'my_assets' not found (ROS_PACKAGE_PATH "
                   "is not set)");
    }
  }
}

// ---- Formats ----

TEST(MeshLoader, ReadsAsciiStl) {
  const Mesh mesh = loadMeshFile(kData + "/meshes/tetra.stl", Eigen::Vector3d::Ones(), "tetra");
  EXPECT_EQ(mesh.source, "tetra");
  EXPECT_EQ(mesh.vertices.size(), 4u);  // the facets' copies of each corner are merged
  EXPECT_EQ(mesh.triangles.size(), 4u);
  EXPECT_TRUE(lowest(mesh).isApprox(Eigen::Vector3d(-0.04, -0.03, -0.05), 1e-6));
  EXPECT_TRUE(highest(mesh).isApprox(Eigen::Vector3d(0.1, 0.2, 0.3), 1e-6));
}

TEST(MeshLoader, ReadsBinaryStlWithScale) {
  TempDir dir;
  dir.write(
      "two.stl",
      binaryStl({{Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(1, 0, 0), Eigen::Vector3f(0, 1, 0)},
                 {Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(0, 1, 0), Eigen::Vector3f(0, 0, 1)}}));
  const Mesh mesh =
      loadMeshFile((dir.path() / "two.stl").string(), Eigen::Vector3d(0.1, 0.2, 0.3), "two");
  EXPECT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.vertices.size(), 4u);
  EXPECT_TRUE(highest(mesh).isApprox(Eigen::Vector3d(0.1, 0.2, 0.3), 1e-9));
  EXPECT_TRUE(lowest(mesh).isApprox(Eigen::Vector3d::Zero()));
}

TEST(MeshLoader, ReadsObjAndTriangulatesQuads) {
  const Mesh mesh = loadMeshFile(kData + "/meshes/cube.obj", Eigen::Vector3d::Ones(), "cube");
  EXPECT_EQ(mesh.vertices.size(), 8u);
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_TRUE(lowest(mesh).isApprox(Eigen::Vector3d(-0.01, -0.02, 0.0), 1e-6));
  EXPECT_TRUE(highest(mesh).isApprox(Eigen::Vector3d(0.03, 0.02, 0.04), 1e-6));
  // A mesh object's derived values: bottom 0, top 0.04, radius over the corners (0.03, 0.02).
  Shape shape;
  shape.type = ShapeType::Mesh;
  shape.mesh = std::make_shared<const Mesh>(mesh);
  const ObjectModel o = makeObject("cube", {shape}, Eigen::Quaterniond::Identity());
  EXPECT_NEAR(o.bottomOffset.z(), 0.0, 1e-7);
  EXPECT_NEAR(o.topOffset.z(), 0.04, 1e-7);
  EXPECT_NEAR(o.horizontalRadius, std::sqrt(0.03 * 0.03 + 0.02 * 0.02), 1e-7);
}

TEST(MeshLoader, ReadsColladaInMetresWithZKeptUp) {
  // Centimetres and Z_UP: assimp would turn the model to y up; ROS keeps z up.
  const Mesh mesh = loadMeshFile(kData + "/meshes/cm_zup.dae", Eigen::Vector3d::Ones(), "dae");
  EXPECT_EQ(mesh.triangles.size(), 4u);
  EXPECT_TRUE(lowest(mesh).isApprox(Eigen::Vector3d::Zero()));
  EXPECT_TRUE(highest(mesh).isApprox(Eigen::Vector3d(0.1, 0.2, 0.3), 1e-6));
  const Mesh scaled = loadMeshFile(kData + "/meshes/cm_zup.dae", Eigen::Vector3d(2, 2, 2), "dae");
  EXPECT_TRUE(highest(scaled).isApprox(Eigen::Vector3d(0.2, 0.4, 0.6), 1e-6));
}

// ---- Errors ----

TEST(MeshLoader, MissingUnreadableEmptyAndCorruptFiles) {
  EXPECT_EQ(loadError(kData + "/meshes/nope.stl"),
            "mesh '" + kData + "/meshes/nope.stl': file not found");
  EXPECT_EQ(loadError(kData + "/meshes"), "mesh '" + kData + "/meshes': not a regular file");
  EXPECT_EQ(loadError(kData + "/meshes/corrupt.stl"),
            "mesh '" + kData +
                "/meshes/corrupt.stl': cannot read it as a mesh: Failed to determine "
                "STL storage representation for " +
                kData + "/meshes/corrupt.stl.");
  // An STL with no facets.
  EXPECT_EQ(
      loadError(kData + "/meshes/empty.stl").rfind("mesh '" + kData + "/meshes/empty.stl': ", 0),
      0u);
  TempDir dir;
  dir.write("zero.stl", "");
  EXPECT_EQ(loadError((dir.path() / "zero.stl").string()),
            "mesh '" + (dir.path() / "zero.stl").string() + "': the file is empty");
  dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n");
  EXPECT_EQ(loadError((dir.path() / "points.obj").string()).rfind("mesh '", 0), 0u);
  EXPECT_EQ(loadError(kData + "/meshes/tetra.stl", Eigen::Vector3d(1, -1, 1)),
            "mesh '" + kData +
                "/meshes/tetra.stl': scale must be three finite positive factors, "
                "got [1, -1, 1]");
  EXPECT_EQ(loadError(kData + "/meshes/tetra.stl", Eigen::Vector3d(1, std::nan(""), 1)),
            "mesh '" + kData +
                "/meshes/tetra.stl': scale must be three finite positive factors, "
                "got [1, nan, 1]");
  // The source named in messages is the URI, with the path it resolved to.
  try {
    loadMeshFile("/x/y.stl", Eigen::Vector3d::Ones(), "package://p/y.stl");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "mesh 'package://p/y.stl' (/x/y.stl): file not found");
  }
}

// ---- Cache ----

TEST(MeshLoader, EachFileAndScaleIsReadOnce) {
  MeshLoader loader([](const std::string& p) { return p == "data" ? kData : std::string(); },
                    kData);
  const auto a = loader.load("meshes/tetra.stl", Eigen::Vector3d::Ones());
  const auto b = loader.load("package://data/meshes/tetra.stl", Eigen::Vector3d::Ones());
  const auto c = loader.load(kData + "/meshes/../meshes/tetra.stl", Eigen::Vector3d::Ones());
  const auto d = loader.load("meshes/tetra.stl", Eigen::Vector3d(2, 1, 1));
  EXPECT_EQ(a.get(), b.get());
  EXPECT_EQ(a.get(), c.get());
  EXPECT_NE(a.get(), d.get());
  EXPECT_EQ(loader.cachedCount(), 2u);
  EXPECT_NEAR(highest(*d).x(), 0.2, 1e-6);
  // A relative URI against another base directory (a URDF file's).
  const auto e = loader.load("tetra.stl", Eigen::Vector3d::Ones(), kData + "/meshes");
  EXPECT_EQ(a.get(), e.get());
  EXPECT_THROW(loader.load("meshes/nope.stl", Eigen::Vector3d::Ones()), ConfigError);
}

// ---- Mesh objects in the configuration ----

ObjectModel meshObject(const std::string& entry) {
  const ConfigNode root = parseYaml("objects:\n  part: " + entry + "\n", "test.yaml");
  BuildOptions options;
  options.baseDirectory = kData;
  options.packageResolver = [](const std::string& p) {
    return p == "placement_samplers" ? kSourceDir : std::string();
  };
  MeshLoader meshes(options.packageResolver, options.baseDirectory);
  return parseObject("part", root.at("objects").at("part"), options, meshes);
}

std::string meshObjectError(const std::string& entry) {
  try {
    meshObject(entry);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MeshLoader, MeshObjectsDeriveTheirValuesFromVertices) {
  // tetra scaled (3, 1, 0.5): (0.3, 0, 0), (0, 0.2, 0), (0, 0, 0.15), (-0.12, -0.03, -0.025).
  const ObjectModel tetra = meshObject("{shape: mesh, mesh: meshes/tetra.stl, scale: [3, 1, 0.5]}");
  ASSERT_EQ(tetra.shapes.size(), 1u);
  EXPECT_EQ(tetra.shapes[0].type, ShapeType::Mesh);
  EXPECT_NEAR(tetra.bottomOffset.z(), -0.025, 1e-7);
  EXPECT_NEAR(tetra.topOffset.z(), 0.15, 1e-7);
  EXPECT_NEAR(tetra.horizontalRadius, 0.3, 1e-7);
  EXPECT_TRUE(tetra.radiusBoundsGeometry);
  // Turned a quarter about z first: the same radius, the same heights.
  const ObjectModel turned = meshObject(
      "{shape: mesh, mesh: meshes/tetra.stl, scale: [3, 1, 0.5], init_orientation: [0, 0, "
      "0.7071067811865476, 0.7071067811865476], horizontal_radius: 0.5}");
  EXPECT_NEAR(turned.topOffset.z(), 0.15, 1e-7);
  EXPECT_DOUBLE_EQ(turned.horizontalRadius, 0.5);
  // The project's L block, through its package.
  const ObjectModel block =
      meshObject("{shape: mesh, mesh: package://placement_samplers/meshes/l_block.stl}");
  EXPECT_NEAR(block.horizontalRadius, std::sqrt(2.0) * 0.04, 1e-7);
  EXPECT_NEAR(block.bottomOffset.z(), -0.015, 1e-7);
}

TEST(MeshLoader, MeshObjectErrors) {
  EXPECT_EQ(meshObjectError("{shape: mesh, mesh: meshes/nope.stl}"),
            "objects.part.mesh: object 'part': mesh 'meshes/nope.stl' (" + kData +
                "/meshes/nope.stl): file not found");
  EXPECT_EQ(meshObjectError("{shape: mesh, mesh: meshes/tetra.stl, scale: [1, 0, 1]}"),
            "objects.part.scale: expected three positive scale factors [sx, sy, sz]");
  EXPECT_EQ(meshObjectError("{shape: mesh}"), "objects.part: missing required key 'mesh'");
  EXPECT_EQ(meshObjectError("{shape: mesh, mesh: 3}"),
            "objects.part.mesh: expected a string, got an integer (3)");
  EXPECT_EQ(meshObjectError("{shape: mesh, mesh: meshes/tetra.stl, size: [1, 1, 1]}"),
            "objects.part: unknown key 'size' (expected one of: shape, mesh, scale, "
            "horizontal_radius, bottom_offset, top_offset, init_orientation, density)");
  EXPECT_EQ(meshObjectError("{shape: mesh, mesh: package://nowhere/a.stl}"),
            "objects.part.mesh: object 'part': 'package://nowhere/a.stl': package 'nowhere' not "
            "found by the package resolver");
}

}  // namespace
}  // namespace placement_samplers
