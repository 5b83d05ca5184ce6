#include "placement_samplers/validation/region_test.hpp"

#include <algorithm>
#include <cmath>

namespace placement_samplers {

double distanceOutsideRegion(const UniformRandomSampler& sampler, const ObjectModel& object,
                             const Eigen::Vector3d& base, const Eigen::Vector3d& position) {
  const UniformSamplerParams& p = sampler.params();
  const double margin = p.ensureObjectBoundaryInRange ? object.horizontalRadius : 0.0;
  const Eigen::Vector2d local = (position - base).head<2>();
  double outside = 0.0;
  if (p.region) {
    // Another shape: how far short of the inset the signed depth falls (the distance for disks,
    // annuli and straight edges, an upper bound near corners).
    outside = std::max(0.0, margin - shapeDepth(*p.region, local));
  } else {
    double squared = 0.0;
    for (int axis = 0; axis < 2; ++axis) {
      const Eigen::Vector2d range = sampler.effectiveRange(object, axis);
      const double v = position[axis] - base[axis];
      const double out = std::max({range[0] - v, v - range[1], 0.0});
      squared += out * out;
    }
    outside = std::sqrt(squared);
  }
  // A keep-out zone counts as outside: how far the object's disk (or centre) reaches into it.
  for (const KeepOutZone& zone : p.keepOut) {
    const Eigen::Vector2d q = zone.world ? Eigen::Vector2d(position.head<2>()) : local;
    outside = std::max(outside, shapeDepth(zone.shape, q) + margin);
  }
  return outside;
}

}  // namespace placement_samplers
