// Support surface extraction (findSupportSurfaces): generated meshes of 10,000 and 100,000
// triangles (vertices shared, and repeated per triangle as in an STL file), a rough sheet of
// 100,000 triangles few of which are coplanar, the package's shelf, bin and counter.

#include "../../test/unit/slab_mesh.hpp"
#include "bench_support.hpp"
#include "placement_samplers/geometry/support_surfaces.hpp"
#include "placement_samplers/geometry/urdf_geometry.hpp"

namespace bench {
namespace {

ps::Shape meshShape(ps::Mesh mesh) {
  ps::Shape shape;
  shape.type = ps::ShapeType::Mesh;
  shape.mesh = std::make_shared<const ps::Mesh>(std::move(mesh));
  return shape;
}

void row(const Options& options, const char* name, std::size_t triangles,
         const std::vector<ps::Shape>& shapes) {
  const ps::SurfaceSearch found = ps::findSupportSurfaces(shapes, Eigen::Isometry3d::Identity());
  const double ns = nsPerOp(options, [&](std::uint64_t n) {
    for (std::uint64_t i = 0; i < n; ++i) {
      gSink = gSink +
              static_cast<double>(
                  ps::findSupportSurfaces(shapes, Eigen::Isometry3d::Identity()).surfaces.size());
    }
  });
  std::printf("%-42s %7zu %9zu %9zu %12.3f\n", name, shapes.size(), triangles,
              found.surfaces.size(), ns * 1e-6);
}

}  // namespace

void benchSurfaces(const Options& options) {
  std::printf(
      "\nSupport surfaces: findSupportSurfaces per call, one thread (median of %d), target "
      "<= 50 ms for 100,000 triangles\n",
      options.repetitions);
  std::printf("%-42s %7s %9s %9s %12s\n", "geometry", "shapes", "triangles", "surfaces",
              "time [ms]");
  for (int n : {68, 222}) {
    ps::Mesh slab = ps::test::makeSlabMesh(1.2, 0.8, -0.05, 0.05, n);
    const std::size_t triangles = slab.triangles.size();
    const std::string name = "mesh slab, top " + std::to_string(n) + " x " + std::to_string(n);
    // As an STL file stores it: three vertices of its own per triangle, welded again.
    ps::Mesh repeated;
    for (const Eigen::Vector3i& t : slab.triangles) {
      const int first = static_cast<int>(repeated.vertices.size());
      for (int k = 0; k < 3; ++k) {
        repeated.vertices.push_back(slab.vertices[t[k]]);
      }
      repeated.triangles.emplace_back(first, first + 1, first + 2);
    }
    row(options, name.c_str(), triangles, {meshShape(std::move(slab))});
    row(options, (name + ", STL vertices").c_str(), triangles, {meshShape(std::move(repeated))});
  }
  ps::Mesh rough = ps::test::makeRoughMesh(224);
  const std::size_t roughTriangles = rough.triangles.size();
  row(options, "rough sheet 224 x 224", roughTriangles, {meshShape(std::move(rough))});
  const std::string package = options.configDir + "/..";
  ps::MeshLoader meshes;
  for (const char* urdf : {"shelf.urdf", "bin.urdf"}) {
    const std::string path = package + "/urdf/" + urdf;
    row(options, (std::string("urdf/") + urdf).c_str(), 0,
        ps::urdfCollisionShapes(ps::readTextFile(path), "", meshes, package + "/urdf"));
  }
  ps::Mesh counter = ps::loadMeshFile(package + "/meshes/counter.stl", Eigen::Vector3d::Ones(),
                                      "meshes/counter.stl");
  const std::size_t triangles = counter.triangles.size();
  row(options, "meshes/counter.stl", triangles, {meshShape(std::move(counter))});
}

}  // namespace bench
