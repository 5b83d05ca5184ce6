#include "validation/surface_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/text.hpp"
#include "placement_samplers/validation/region_test.hpp"
#include "validation/verdict_text.hpp"

namespace placement_samplers {
namespace detail {

void checkOnSurface(ObjectVerdict& verdict, const UniformRandomSampler& sampler,
                    const ObjectModel& object, const Eigen::Vector3d& base, Candidate& candidate,
                    const SampleContext& context, const RequestSurfaces* surfaces,
                    const ValidationOptions& options) {
  const std::string& s = sampler.name();
  const SurfaceRegion& region = *sampler.params().surface;
  const PlacedEntry* target = context.find(region.of);
  if (target == nullptr) {
    addViolation(verdict, Violation::Kind::ReferenceMissing, s, region.of, 0.0,
                 "object " + quoteText(object.name) + ": region.of " + quoteText(region.of) +
                     " of sampler " + quoteText(s) +
                     " is neither a fixture nor an object placed before it");
    return;
  }
  candidate.support = target - context.entries().data();
  std::vector<SupportSurface> found;
  try {
    found = sampler.surfacesOn(*target, surfaces);
  } catch (const ConfigError& e) {
    addViolation(
        verdict, Violation::Kind::OutsideRegion, s, region.of, 0.0,
        "object " + quoteText(object.name) + ": sampler " + quoteText(s) + ": " + e.what());
    return;
  }
  const double height = object.topOffset.z() - object.bottomOffset.z();
  std::vector<SupportSurface> fitting;
  for (SupportSurface& surface : found) {
    if (height <= surface.clearance) {
      fitting.push_back(std::move(surface));
    }
  }
  if (fitting.empty()) {
    addViolation(verdict, Violation::Kind::OutsideRegion, s, region.of, 0.0,
                 "object " + quoteText(object.name) + " fits on no selected surface of " +
                     quoteText(region.of) + " (sampler " + quoteText(s) + ")");
    return;
  }
  // The surface it is on: the nearest in x-y, and of those as near (all it lies on: shelves
  // stack them) the one at the nearest height.
  const Eigen::Vector3d& p = candidate.position;
  const double lift = sampler.params().zOffset - object.bottomOffset.z();
  std::size_t nearest = 0;
  double outside = std::numeric_limits<double>::infinity();
  double off = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < fitting.size(); ++i) {
    const double d = surfaceShortfall(fitting[i], sampler.surfaceInset(object), p.head<2>());
    const double dz = std::abs(p.z() - (fitting[i].z + lift));
    const double tie = std::max(options.regionTolerance, 1e-12);
    if (d < outside - tie || (std::abs(d - outside) <= tie && dz < off)) {
      nearest = i;
      outside = d;
      off = dz;
    }
  }
  const double margin =
      sampler.params().ensureObjectBoundaryInRange ? object.horizontalRadius : 0.0;
  for (const KeepOutZone& zone : sampler.params().keepOut) {
    const Eigen::Vector2d q =
        zone.world ? Eigen::Vector2d(p.head<2>()) : Eigen::Vector2d((p - base).head<2>());
    outside = std::max(outside, shapeDepth(zone.shape, q) + margin);
  }
  if (outside > options.regionTolerance) {
    addViolation(verdict, Violation::Kind::OutsideRegion, s, "", outside,
                 "object " + quoteText(object.name) + " is outside the surfaces of " +
                     quoteText(region.of) + " that sampler " + quoteText(s) + " draws on by " +
                     metres(outside));
  }
  const double z = fitting[nearest].z + lift;
  if (!(off <= options.heightTolerance)) {
    addViolation(verdict, Violation::Kind::Height, s, "", off,
                 "object " + quoteText(object.name) + " is at z " + metres(p.z()) +
                     ", off the height of the surface of " + quoteText(region.of) + " it is on (" +
                     metres(z) + ") by " + metres(off));
  }
}

}  // namespace detail
}  // namespace placement_samplers
