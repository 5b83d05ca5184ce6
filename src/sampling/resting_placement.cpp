// The uniform sampler under resting: stable: each attempt draws one of the object's resting
// poses first, then its position with that pose's numbers (README, "Resting poses").
#include <algorithm>

#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {

bool UniformRandomSampler::placeOneResting(SampleContext& context, const Entry& entry,
                                           const Eigen::Vector3d& base, bool onTop,
                                           PlacementRelations* relations) const {
  const ObjectModel& object = *entry.object;
  Engine& engine = engineOf(context);
  const std::uint32_t limit = attemptLimit(context);
  const bool check = params_.ensureValidPlacement;
  const bool orientFirst = check && context.needsOrientation();
  std::vector<std::uint32_t>* counts = check ? &context.blockerCounts() : nullptr;
  const Eigen::Vector2d offset = base.head<2>();

  // A surface region's draws of each pose on its target in this scene (nullptr: none fits).
  std::vector<const SurfaceDraw*> surfaces;
  Candidate candidate;
  if (params_.surface) {
    const PlacedEntry* target = context.find(params_.surface->of);
    if (target == nullptr) {
      return fail(context, &object, 0,
                  "sampler " + quoteText(name()) + ": region.of " + quoteText(params_.surface->of) +
                      " is neither a fixture nor an object placed before this sampler");
    }
    candidate.support = target - context.entries().data();
    std::string error;
    std::string first;
    for (const Entry& pose : entry.poses) {
      surfaces.push_back(pose.usable ? surfaceDrawOn(context, pose, *target, error) : nullptr);
      if (surfaces.back() == nullptr && first.empty()) {
        first = pose.usable ? error : pose.problem;
      }
    }
    if (std::all_of(surfaces.begin(), surfaces.end(), [](const SurfaceDraw* d) { return !d; })) {
      return fail(context, &object, 0, first);
    }
  }

  std::uint32_t outside = 0;
  std::uint32_t collided = 0;
  for (std::uint32_t attempt = 1; attempt <= limit; ++attempt) {
    if ((attempt & 1023u) == 0 && context.expired()) {
      return failOutOfTime(context, object, attempt - 1);
    }
    if (relations != nullptr && attempt == kRelationProbeAttempts &&
        !relationsPossible(context, object, *relations)) {
      return false;
    }
    // The pose by probability, then the region's draws with the pose's numbers.
    const double u = uniform01(engine);
    const std::size_t k =
        std::min<std::size_t>(static_cast<std::size_t>(std::upper_bound(entry.cumulative.begin(),
                                                                        entry.cumulative.end(), u) -
                                                       entry.cumulative.begin()),
                              entry.poses.size() - 1);
    const Entry& pose = entry.poses[k];
    const ObjectModel& posed = *pose.object;
    candidate.object = &posed;
    bool blocked = !pose.usable;
    Eigen::Vector2d local = Eigen::Vector2d::Zero();
    if (!blocked && params_.surface) {
      const SurfaceDraw* draw = surfaces[k];
      blocked = draw == nullptr;
      if (!blocked) {
        std::size_t surface = 0;
        const Eigen::Vector2d p = draw->draw(engine, surface);
        candidate.position = Eigen::Vector3d(
            p.x(), p.y(), draw->z(surface) + params_.zOffset - posed.bottomOffset.z());
        local = p - offset;
        blocked = !draw->accepts(p, surface);
      }
    } else if (!blocked && pose.draw) {
      local = pose.draw->draw(engine);
      candidate.position = Eigen::Vector3d(local.x() + offset.x(), local.y() + offset.y(),
                                           height(posed, base, onTop));
      blocked = !pose.draw->accepts(local);
    } else if (!blocked) {
      const double x = uniform(engine, pose.x[0], pose.x[1]);
      const double y = uniform(engine, pose.y[0], pose.y[1]);
      local = Eigen::Vector2d(x, y);
      candidate.position = Eigen::Vector3d(x + base.x(), y + base.y(), height(posed, base, onTop));
    }
    if (!blocked && orientFirst) {
      candidate.orientation = sampleOrientation(engine, posed);
    }
    const double margin = params_.ensureObjectBoundaryInRange ? posed.horizontalRadius : 0.0;
    blocked = blocked || inKeepOut(local, offset, margin);
    if (blocked) {
      ++outside;
      continue;
    }
    // After the region and keep-out tests, with the pose's radius (resting: stable takes
    // position relations only: the orientation stays the sampler's).
    if (relations != nullptr) {
      if (relations->exact && !orientFirst) {
        // The exact gaps need the orientation (drawn already in the fcl modes' attempts).
        candidate.orientation = sampleOrientation(engine, posed);
      }
      if (!relationsHold(context, *relations, candidate)) {
        continue;
      }
    }
    if (check && collidesCounted(context, candidate, *counts, collided)) {
      continue;
    }
    if (!orientFirst && (relations == nullptr || !relations->exact)) {
      candidate.orientation = sampleOrientation(engine, posed);
    }
    context.addPlacement(name(), candidate, attempt, params_.hides, pose.restPose);
    return true;
  }
  return failPlacement(context, object, limit, collided > 0 ? counts : nullptr, outside, relations);
}

}  // namespace placement_samplers
