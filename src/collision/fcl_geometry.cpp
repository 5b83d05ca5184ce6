#include "collision/fcl_geometry.hpp"

#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace fcl_compat {
namespace {

/// BVHs of meshes, built once per Mesh for the whole process and shared by every checker:
/// FCL only reads an OBBRSS model during queries. Keyed by address, checked through a weak
/// pointer so that a new mesh at a freed address is not mistaken for the old one.
class MeshGeometryCache {
 public:
  GeometryPtr get(const std::shared_ptr<const Mesh>& mesh) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = entries_.find(mesh.get());
    if (it != entries_.end() && it->second.first.lock() == mesh) {
      return it->second.second;
    }
    for (auto e = entries_.begin(); e != entries_.end();) {
      e = e->second.first.expired() ? entries_.erase(e) : std::next(e);
    }
    auto model = std::make_shared<MeshModel>();
    std::vector<Vector3> vertices(mesh->vertices.begin(), mesh->vertices.end());
    std::vector<Triangle> triangles;
    triangles.reserve(mesh->triangles.size());
    for (const Eigen::Vector3i& t : mesh->triangles) {
      triangles.emplace_back(t[0], t[1], t[2]);
    }
    if (model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size())) !=
            fcl::BVH_OK ||
        model->addSubModel(vertices, triangles) != fcl::BVH_OK ||
        model->endModel() != fcl::BVH_OK) {
      throw std::runtime_error("FCL could not build a BVH for mesh " + quoteText(mesh->source));
    }
    model->computeLocalAABB();
    entries_[mesh.get()] = {mesh, model};
    return model;
  }

 private:
  std::mutex mutex_;
  std::map<const Mesh*, std::pair<std::weak_ptr<const Mesh>, GeometryPtr>> entries_;
};

MeshGeometryCache& meshGeometryCache() {
  static MeshGeometryCache cache;
  return cache;
}

}  // namespace

GeometryPtr makeGeometry(const Shape& shape) {
  GeometryPtr g;
  switch (shape.type) {
    case ShapeType::Box:
      g = std::make_shared<Box>(shape.size);
      break;
    case ShapeType::Cylinder:  // FCL: axis z, centred, lz = full length, as Shape
      g = std::make_shared<Cylinder>(shape.radius, shape.length);
      break;
    case ShapeType::Sphere:
      g = std::make_shared<Sphere>(shape.radius);
      break;
    case ShapeType::Capsule:  // FCL: lz = distance between the cap centres, as Shape
      g = std::make_shared<Capsule>(shape.radius, shape.length);
      break;
    case ShapeType::Mesh:
      if (!shape.mesh || shape.mesh->triangles.empty()) {
        throw std::invalid_argument("mesh shape without triangles");
      }
      return meshGeometryCache().get(shape.mesh);
  }
  g->computeLocalAABB();
  return g;
}

}  // namespace fcl_compat
}  // namespace placement_samplers
