#include "placement_samplers/validation/region_test.hpp"

#include <algorithm>
#include <cmath>

namespace placement_samplers {

double distanceOutsideRegion(const UniformRandomSampler& sampler, const ObjectModel& object,
                             const Eigen::Vector3d& base, const Eigen::Vector3d& position) {
  double squared = 0.0;
  for (int axis = 0; axis < 2; ++axis) {
    const Eigen::Vector2d range = sampler.effectiveRange(object, axis);
    const double v = position[axis] - base[axis];
    const double outside = std::max({range[0] - v, v - range[1], 0.0});
    squared += outside * outside;
  }
  return std::sqrt(squared);
}

}  // namespace placement_samplers
