#include "placement_samplers/sampling/sampler_regions.hpp"

#include <cmath>
#include <optional>
#include <set>
#include <sstream>

#include "placement_samplers/sampling/region.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "sampling/polygon.hpp"

namespace placement_samplers {
namespace {

struct Walker {
  const PreparedRequest& request;
  const SceneResult& scene;
  std::vector<SamplerRegion> regions;
  std::set<std::pair<std::string, std::size_t>> shown;  ///< surfaces drawn: target, index

  /// The named reference's entry in the scene: a request fixture or an earlier placement.
  std::pair<const Eigen::Vector3d*, const ObjectModel*> find(const std::string& name) const {
    for (const FixtureSpec& f : request.fixtures) {
      if (f.name == name) {
        return {&f.position, f.object.get()};
      }
    }
    for (const ObjectPlacement& p : scene.placements) {
      if (p.name == name) {
        return {&p.position, p.object};
      }
    }
    return {nullptr, nullptr};
  }

  void visit(const UniformRandomSampler& sampler, const Reference& reference, bool onTop) {
    const UniformRandomSampler* uniform = &sampler;
    if (uniform->params().hides) {
      return;
    }
    const auto [position, object] =
        reference.kind == Reference::Kind::Name
            ? find(reference.name)
            : std::pair<const Eigen::Vector3d*, const ObjectModel*>{nullptr, nullptr};
    const std::optional<Eigen::Vector3d> b = uniform->base(reference, onTop, position, object);
    if (!b) {
      return;
    }
    const UniformSamplerParams& p = uniform->params();
    if (p.surface) {
      surfaces(*uniform);
    }
    SamplerRegion region;
    region.sampler = uniform->name();
    region.centre = *b + Eigen::Vector3d(0.5 * (p.xRange[0] + p.xRange[1]),
                                         0.5 * (p.yRange[0] + p.yRange[1]), p.zOffset);
    region.size = Eigen::Vector2d(p.xRange[1] - p.xRange[0], p.yRange[1] - p.yRange[0]);
    if (p.region) {
      region.centre = *b + Eigen::Vector3d(0.0, 0.0, p.zOffset);
      region.triangles = lift(shapeTriangles(*p.region), region.centre);
    }
    if (!p.surface) {
      regions.push_back(region);
    }
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

  /// The support surfaces a surface region draws on in this scene, one region each.
  void surfaces(const UniformRandomSampler& sampler) {
    const std::string& of = sampler.params().surface->of;
    const auto [position, object] = find(of);
    if (position == nullptr) {
      return;
    }
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
    for (const FixtureSpec& f : request.fixtures) {
      orientation = f.name == of ? f.orientation : orientation;
    }
    for (const ObjectPlacement& placed : scene.placements) {
      orientation = placed.name == of ? placed.orientation : orientation;
    }
    std::vector<SupportSurface> found;
    std::vector<std::size_t> indices;
    try {
      found = sampler.surfacesOn(PlacedEntry(of, object, *position, orientation, false),
                                 &request.surfaces, &indices);
    } catch (const std::exception&) {
      return;  // the scene failed there; its message says why
    }
    for (std::size_t k = 0; k < found.size(); ++k) {
      // Each surface once, though several samplers draw on it.
      const std::size_t i = indices[k];
      if (!shown.emplace(of, i).second) {
        continue;
      }
      const SupportSurface& s = found[k];
      SamplerRegion region;
      region.sampler = sampler.name();
      region.surface = true;
      Eigen::Vector2d sum = Eigen::Vector2d::Zero();
      for (const Eigen::Vector2d& v : s.outer) {
        sum += v;
      }
      region.centre = Eigen::Vector3d(0.0, 0.0, s.z);
      region.triangles = lift(detail::trapezoidTriangles(s.outer, s.holes), region.centre);
      region.centre.head<2>() = sum / static_cast<double>(std::max<std::size_t>(1, s.outer.size()));
      std::ostringstream label;
      label << of << ": surface " << i << ", clearance ";
      if (std::isfinite(s.clearance)) {
        label << s.clearance << " m";
      } else {
        label << "unbounded";
      }
      region.label = label.str();
      regions.push_back(std::move(region));
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
  Walker walker{request, scene, {}, {}};
  if (request.sampler != nullptr) {
    request.sampler->forEachUniform(
        request.reference, request.onTop,
        [&](const UniformRandomSampler& sampler, const Reference& reference, bool onTop) {
          walker.visit(sampler, reference, onTop);
        });
  }
  return walker.regions;
}

}  // namespace placement_samplers
