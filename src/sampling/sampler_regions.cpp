#include "placement_samplers/sampling/sampler_regions.hpp"

#include <optional>

#include "placement_samplers/sampling/region.hpp"
#include "placement_samplers/sampling/sequential_composite_sampler.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"

namespace placement_samplers {
namespace {

struct Walker {
  const PreparedRequest& request;
  const SceneResult& scene;
  std::vector<SamplerRegion> regions;

  std::optional<Eigen::Vector3d> base(const UniformRandomSampler& s, const Reference& reference,
                                      bool onTop) const {
    switch (reference.kind) {
      case Reference::Kind::Default:
        return s.params().referencePos;
      case Reference::Kind::Point:
        return reference.point;
      case Reference::Kind::Name:
        break;
    }
    for (const FixtureSpec& f : request.fixtures) {
      if (f.name == reference.name) {
        return f.position + Eigen::Vector3d(0.0, 0.0, onTop ? f.object->topOffset.z() : 0.0);
      }
    }
    for (const ObjectPlacement& p : scene.placements) {
      if (p.name == reference.name) {
        return p.position + Eigen::Vector3d(0.0, 0.0, onTop ? p.object->topOffset.z() : 0.0);
      }
    }
    return std::nullopt;
  }

  void visit(const PlacementSampler& sampler, const Reference& reference, bool onTop) {
    if (const auto* composite = dynamic_cast<const SequentialCompositeSampler*>(&sampler)) {
      for (const auto& child : composite->children()) {
        visit(*child.sampler, child.args.reference ? *child.args.reference : reference,
              child.args.onTop ? *child.args.onTop : onTop);
      }
      return;
    }
    const auto* uniform = dynamic_cast<const UniformRandomSampler*>(&sampler);
    if (uniform == nullptr || uniform->params().hides) {
      return;
    }
    const std::optional<Eigen::Vector3d> b = base(*uniform, reference, onTop);
    if (!b) {
      return;
    }
    const UniformSamplerParams& p = uniform->params();
    SamplerRegion region;
    region.sampler = uniform->name();
    region.centre = *b + Eigen::Vector3d(0.5 * (p.xRange[0] + p.xRange[1]),
                                         0.5 * (p.yRange[0] + p.yRange[1]), p.zOffset);
    region.size = Eigen::Vector2d(p.xRange[1] - p.xRange[0], p.yRange[1] - p.yRange[0]);
    if (p.region) {
      region.centre = *b + Eigen::Vector3d(0.0, 0.0, p.zOffset);
      region.triangles = lift(shapeTriangles(*p.region), region.centre);
    }
    regions.push_back(region);
    for (const KeepOutZone& zone : p.keepOut) {
      SamplerRegion keepOut;
      keepOut.sampler = uniform->name();
      keepOut.keepOut = true;
      keepOut.centre = *b + Eigen::Vector3d(0.0, 0.0, p.zOffset);
      if (zone.world) {
        keepOut.centre.head<2>().setZero();
      }
      keepOut.triangles = lift(shapeTriangles(zone.shape), keepOut.centre);
      regions.push_back(keepOut);
    }
  }

  /// Plane points at @p origin's height, moved by its x and y.
  static std::vector<Eigen::Vector3d> lift(const std::vector<Eigen::Vector2d>& points,
                                           const Eigen::Vector3d& origin) {
    std::vector<Eigen::Vector3d> out;
    out.reserve(points.size());
    for (const Eigen::Vector2d& q : points) {
      out.push_back(origin + Eigen::Vector3d(q.x(), q.y(), 0.0));
    }
    return out;
  }
};

}  // namespace

std::vector<SamplerRegion> samplerRegions(const PreparedRequest& request,
                                          const SceneResult& scene) {
  Walker walker{request, scene, {}};
  if (request.sampler != nullptr) {
    walker.visit(*request.sampler, request.reference, request.onTop);
  }
  return walker.regions;
}

}  // namespace placement_samplers
