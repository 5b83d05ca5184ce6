// The uniform sampler's region shapes and keep-out zones, apart from robosuite's rectangle
// (rectangle_placement.cpp), whose loop stays as it was.
#include <cmath>
#include <sstream>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {

void UniformRandomSampler::checkShapes(const std::string& where) {
  if (params_.region) {
    if (params_.xRange != Eigen::Vector2d::Zero() || params_.yRange != Eigen::Vector2d::Zero()) {
      throw ConfigError(where + "region replaces x_range and y_range: give one or the other");
    }
    if (const auto problem = findShapeProblem(*params_.region)) {
      throw ConfigError(where + "region." + problem->key + ": " + problem->message);
    }
    if (params_.region->kind == RegionShape::Kind::Rectangle) {
      // robosuite's own rectangle: the same draws as x_range and y_range.
      params_.xRange = params_.region->xRange;
      params_.yRange = params_.region->yRange;
      params_.region.reset();
    }
  }
  if (params_.surface) {
    if (params_.region || params_.xRange != Eigen::Vector2d::Zero() ||
        params_.yRange != Eigen::Vector2d::Zero()) {
      throw ConfigError(where +
                        "region (surface) replaces x_range and y_range: give one or the other");
    }
    if (params_.strategy == UniformSamplerParams::Strategy::Dense) {
      throw ConfigError(where + "region (surface) takes strategy rejection or free_space");
    }
    const SurfaceRegion& s = *params_.surface;
    if (s.of.empty()) {
      throw ConfigError(where + "region.of must name a fixture or an object placed earlier");
    }
    const auto bad = [](double v) { return !std::isfinite(v) || v < 0.0; };
    if (bad(s.minArea) || bad(s.margin) || bad(s.normalTolerance) || s.normalTolerance >= M_PI_2) {
      throw ConfigError(where +
                        "region: min_area [m^2] and margin [m] must be finite and >= 0, "
                        "normal_tolerance in [0, pi/2) [rad]");
    }
  }
  for (std::size_t i = 0; i < params_.keepOut.size(); ++i) {
    if (const auto problem = findShapeProblem(params_.keepOut[i].shape)) {
      throw ConfigError(where + "keep_out[" + std::to_string(i) + "]." + problem->key + ": " +
                        problem->message);
    }
  }
}

std::shared_ptr<const RegionDraw> UniformRandomSampler::regionDraw(const ObjectModel& object) {
  const double margin = params_.ensureObjectBoundaryInRange ? object.horizontalRadius : 0.0;
  for (const Entry& e : entries_) {
    const double other = params_.ensureObjectBoundaryInRange ? e.object->horizontalRadius : 0.0;
    if (e.draw && other == margin) {
      return e.draw;
    }
  }
  const RegionShape shape =
      params_.region ? *params_.region : RegionShape::rectangle(params_.xRange, params_.yRange);
  std::optional<RegionDraw> draw = RegionDraw::make(shape, margin);
  if (!draw) {
    std::ostringstream out;
    out << "sampler " << quoteText(name()) << ": region (" << shapeKindName(shape.kind)
        << ") leaves no room for object " << quoteText(object.name) << " (horizontal radius "
        << object.horizontalRadius
        << " m) with ensure_object_boundary_in_range on: no point of it is that far from its edge";
    throw ConfigError(out.str());
  }
  return std::make_shared<const RegionDraw>(std::move(*draw));
}

bool UniformRandomSampler::placeOneShaped(SampleContext& context, const Entry& entry,
                                          const Eigen::Vector3d& base, bool onTop,
                                          PlacementRelations* relations) const {
  const ObjectModel& object = *entry.object;
  // Per attempt: the region's draws (README, "Region shapes"), the rotation in the fcl modes,
  // then the inset test of a non-convex polygon, the keep-out zones and the collision test;
  // the rotation after the accepted attempt otherwise, as robosuite.
  Engine& engine = engineOf(context);
  const std::uint32_t limit = attemptLimit(context);
  const bool check = params_.ensureValidPlacement;
  const bool orientFirst = check && context.needsOrientation();
  std::vector<std::uint32_t>* counts = check ? &context.blockerCounts() : nullptr;
  const double margin = params_.ensureObjectBoundaryInRange ? object.horizontalRadius : 0.0;
  const Eigen::Vector2d offset = base.head<2>();
  std::uint32_t outside = 0;
  std::uint32_t collided = 0;

  Candidate candidate;
  candidate.object = &object;
  candidate.position.z() = height(object, base, onTop);
  for (std::uint32_t attempt = 1; attempt <= limit; ++attempt) {
    if ((attempt & 1023u) == 0 && context.expired()) {
      return failOutOfTime(context, object, attempt - 1);
    }
    if (relations != nullptr && attempt == kRelationProbeAttempts &&
        !relationsPossible(context, object, *relations)) {
      return false;
    }
    const Eigen::Vector2d local = entry.draw->draw(engine);
    candidate.position.head<2>() = local + offset;
    if (orientFirst && relations == nullptr) {
      candidate.orientation = sampleOrientation(engine, object);
    }
    const bool blocked = !entry.draw->accepts(local) || inKeepOut(local, offset, margin);
    if (blocked) {
      ++outside;
      continue;
    }
    if (relations != nullptr) {
      // After the region and keep-out tests; the turn before them in the fcl modes, whose
      // exact gaps need it.
      if (relations->exact) {
        candidate.orientation =
            relatedOrientation(engine, object, candidate.position.head<2>(), relations);
      }
      if (!relationsHold(context, *relations, candidate)) {
        continue;
      }
    }
    if (check && collidesCounted(context, candidate, *counts, collided)) {
      continue;
    }
    if (!orientFirst && (relations == nullptr || !relations->exact)) {
      candidate.orientation =
          relatedOrientation(engine, object, candidate.position.head<2>(), relations);
    }
    context.addPlacement(name(), candidate, attempt, params_.hides);
    return true;
  }
  return failPlacement(context, object, limit, collided > 0 ? counts : nullptr, outside, relations);
}

}  // namespace placement_samplers
