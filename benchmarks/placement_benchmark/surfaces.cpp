// Support surface extraction (findSupportSurfaces): generated meshes of 10,000 and 100,000
// triangles (vertices shared, and repeated per triangle as in an STL file), a rough sheet of
// 100,000 triangles few of which are coplanar, the package's shelf, bin and counter.

#include "../../test/unit/slab_mesh.hpp"
#include "bench_support.hpp"

#include <ctime>
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

double threadSeconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Median wall-clock and thread CPU time of one call [ms], over options.repetitions blocks of
/// calls lasting about options.secondsPerRep each.
void row(const Options& options, const char* name, std::size_t triangles,
         const std::vector<ps::Shape>& shapes) {
  const auto call = [&] {
    return ps::findSupportSurfaces(shapes, Eigen::Isometry3d::Identity()).surfaces.size();
  };
  const std::size_t surfaces = call();
  const Clock::time_point start = Clock::now();
  call();
  const double once = std::chrono::duration<double>(Clock::now() - start).count();
  const int n = std::max(1, static_cast<int>(options.secondsPerRep / std::max(once, 1e-9)));
  std::vector<double> wall;
  std::vector<double> cpu;
  for (int r = 0; r < options.repetitions; ++r) {
    const Clock::time_point w0 = Clock::now();
    const double c0 = threadSeconds();
    for (int i = 0; i < n; ++i) {
      gSink = gSink + static_cast<double>(call());
    }
    cpu.push_back((threadSeconds() - c0) * 1e3 / n);
    wall.push_back(std::chrono::duration<double, std::milli>(Clock::now() - w0).count() / n);
  }
  std::printf("%-42s %7zu %9zu %9zu %12.3f %12.3f\n", name, shapes.size(), triangles, surfaces,
              median(wall), median(cpu));
}

}  // namespace

void benchSurfaces(const Options& options) {
  std::printf(
      "\nSupport surfaces: findSupportSurfaces per call, one thread, wall-clock and thread CPU "
      "time (median of %d), target <= 50 ms for 100,000 triangles\n",
      options.repetitions);
  std::printf("%-42s %7s %9s %9s %12s %12s\n", "geometry", "shapes", "triangles", "surfaces",
              "wall [ms]", "cpu [ms]");
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
