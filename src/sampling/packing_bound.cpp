#include "placement_samplers/sampling/packing_bound.hpp"

#include <cmath>
#include <sstream>
#include <vector>

#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"
#include "collision/radius_test.hpp"
#include "sampling/polygon.hpp"

namespace placement_samplers {

double regionArea(const RegionShape& s) {
  switch (s.kind) {
    case RegionShape::Kind::Rectangle:
      return (s.xRange[1] - s.xRange[0]) * (s.yRange[1] - s.yRange[0]);
    case RegionShape::Kind::RotatedRectangle:
      return s.size.x() * s.size.y();
    case RegionShape::Kind::Disk:
      return M_PI * s.radius * s.radius;
    case RegionShape::Kind::Annulus:
      return M_PI * (s.radius * s.radius - s.innerRadius * s.innerRadius);
    case RegionShape::Kind::Polygon:
      return 0.5 * std::abs(detail::signedArea2(s.vertices));
  }
  return 0.0;
}

namespace {

/// Objects of @p sampler that all test against each other (in sampling order: each later one
/// against every earlier one), greedily from the first.
std::vector<ObjectPtr> mutuallyTested(const UniformRandomSampler& sampler, bool onTop) {
  const Eigen::Vector3d base = Eigen::Vector3d::Zero();  // heights differ by offsets only
  std::vector<ObjectPtr> clique;
  for (const ObjectPtr& candidate : sampler.objects()) {
    const double zc = sampler.height(*candidate, base, onTop);
    bool testsAll = true;
    for (const ObjectPtr& earlier : clique) {
      const double ze = sampler.height(*earlier, base, onTop);
      testsAll = testsAll && detail::radiusHeightsOverlap(zc, candidate->bottomOffset.z(), ze,
                                                          earlier->topOffset.z());
    }
    if (testsAll) {
      clique.push_back(candidate);
    }
  }
  return clique;
}

}  // namespace

std::optional<std::string> findOverfullSampler(const PlacementSampler& root,
                                               const Reference& reference, bool onTop,
                                               CollisionMode mode) {
  if (mode == CollisionMode::Fcl) {
    return std::nullopt;
  }
  std::optional<std::string> found;
  root.forEachUniform(
      reference, onTop, [&](const UniformRandomSampler& s, const Reference&, bool samplerOnTop) {
        const UniformSamplerParams& p = s.params();
        // A surface region's area is known per scene only (its target may move).
        if (found || p.hides || !p.ensureValidPlacement || !p.ensureObjectBoundaryInRange ||
            p.surface) {
          return;
        }
        const std::vector<ObjectPtr> objects = mutuallyTested(s, samplerOnTop);
        double disks = 0.0;
        for (const ObjectPtr& o : objects) {
          disks += M_PI * o->horizontalRadius * o->horizontalRadius;
        }
        const RegionShape region =
            p.region ? *p.region : RegionShape::rectangle(p.xRange, p.yRange);
        const double area = regionArea(region);
        if (objects.size() < 2 || disks <= area) {
          return;
        }
        std::ostringstream out;
        out << "sampler " << quoteText(s.name()) << " cannot place its objects: the disks of "
            << objects.size() << " objects that must not overlap (" << quoteText(objects[0]->name)
            << ", " << quoteText(objects[1]->name) << (objects.size() > 2 ? ", ..." : "")
            << ") cover " << disks << " m^2, more than its region's " << area
            << " m^2 that they must lie in (ensure_object_boundary_in_range): no packing fits them";
        found = out.str();
      });
  return found;
}

}  // namespace placement_samplers
