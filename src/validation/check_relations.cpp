// The validator's RELATION violations (README, "Relations").
#include "placement_samplers/validation/check_relations.hpp"

#include <cmath>
#include <sstream>

#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace {

/// The side of the target's frame that @p p is on (the sector's edges go to left and right).
Relation::Side sideOf(const PositionTest& test, const Eigen::Vector2d& p) {
  const Eigen::Vector2d d = p - test.centre;
  const double x = d.x() * test.cosHeading + d.y() * test.sinHeading;
  const double y = d.y() * test.cosHeading - d.x() * test.sinHeading;
  for (const Relation::Side side :
       {Relation::Side::Left, Relation::Side::Right, Relation::Side::Front, Relation::Side::Back}) {
    if (inSide(side, x, y)) {
      return side;
    }
  }
  return Relation::Side::Any;
}

}  // namespace

std::vector<RelationMiss> checkRelations(const UniformRandomSampler& sampler,
                                         const ObjectModel& object, const Candidate& candidate,
                                         SampleContext& context) {
  std::vector<RelationMiss> misses;
  const std::vector<Relation>& relations = sampler.params().relations;
  const Eigen::Vector2d p = candidate.position.head<2>();
  for (std::size_t i = 0; i < relations.size(); ++i) {
    const Relation& r = relations[i];
    if (!r.appliesTo(object.name)) {
      continue;
    }
    RelationMiss miss;
    miss.index = i;
    miss.target = r.target;
    std::ostringstream out;
    out << "object " << quoteText(object.name) << ": " << relationLabel(r, i) << " of sampler "
        << quoteText(sampler.name()) << " does not hold: ";
    const PlacedEntry* target = context.find(r.target);
    if (target == nullptr) {
      out << "its target is neither a fixture nor an object placed before it";
      miss.message = out.str();
      misses.push_back(std::move(miss));
      continue;
    }
    const RelationTarget t = relationTarget(*target);
    if (r.isPosition()) {
      const PositionTest test(r, i, t);
      const double radius = candidate.object->horizontalRadius;
      // The fcl modes: the shapes' exact distance, as sampling measured it.
      double exact = 0.0;
      const bool isExact =
          context.needsOrientation() &&
          context.exactDistance(static_cast<std::size_t>(target - context.entries().data()),
                                candidate, exact);
      if (isExact ? test.holdsGap(p, exact) : test.holds(p, radius)) {
        continue;
      }
      miss.value = isExact ? exact : test.gap(p, radius);
      const bool near =
          r.minGap <= miss.value && (r.kind == Relation::Kind::AwayFrom || miss.value <= r.maxGap);
      if (near) {
        // The distance holds: the side does not.
        out << "it is on the " << relationSideName(sideOf(test, p)) << " of " << quoteText(r.target)
            << ", not on its " << relationSideName(r.side);
      } else {
        out << "the gap is " << miss.value << " m";
      }
    } else {
      miss.value = relationAngleError(r, t, p, candidate.orientation);
      if (miss.value <= r.tolerance + kRelationAngleSlack) {
        continue;
      }
      out << "its yaw is " << miss.value << " rad off "
          << (r.kind == Relation::Kind::Face ? "the direction to " : "the yaw of ")
          << quoteText(r.target);
    }
    miss.message = out.str();
    misses.push_back(std::move(miss));
  }
  return misses;
}

}  // namespace placement_samplers
