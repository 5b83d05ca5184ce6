// A uniform sampler's relations (README, "Relations"): which apply to each object, their
// targets in a scene, the fast failure of one that cannot hold, the turn of a rotation one.
#include <cmath>
#include <limits>
#include <sstream>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {

void UniformRandomSampler::checkRelations(const std::string& where) const {
  const std::vector<Relation>& relations = params_.relations;
  if (relations.empty()) {
    return;
  }
  if (relations.size() > kMaxRelations) {
    throw ConfigError(where + "relations: at most " + std::to_string(kMaxRelations) +
                      " relations, got " + std::to_string(relations.size()));
  }
  if (params_.strategy == UniformSamplerParams::Strategy::Dense) {
    // dense lays its objects out by its own rule, not by draws that a relation could refuse.
    throw ConfigError(where + "relations take strategy rejection or free_space, not dense");
  }
  for (std::size_t i = 0; i < relations.size(); ++i) {
    const Relation& r = relations[i];
    const std::string at = where + "relations[" + std::to_string(i) + "]";
    const bool finite = std::isfinite(r.minGap) && std::isfinite(r.tolerance) &&
                        std::isfinite(r.period) &&
                        (r.kind == Relation::Kind::AwayFrom || std::isfinite(r.maxGap));
    if (!finite || r.minGap < 0.0 || r.maxGap < 0.0 || r.tolerance < 0.0) {
      throw ConfigError(at + ": distances and tolerance must be finite and >= 0");
    }
    if (r.kind == Relation::Kind::NextTo && r.minGap > r.maxGap) {
      throw ConfigError(at + ".distance: expected [min, max] with min <= max");
    }
    if (r.kind == Relation::Kind::AlignWith && !(r.period > 0.0 && r.period <= 2 * M_PI)) {
      throw ConfigError(at + ".period: expected a period in (0, 2 pi] [rad]");
    }
    if (r.kind == Relation::Kind::AlignWith && !(r.tolerance > 0.0)) {
      throw ConfigError(at + ".tolerance: align_with draws uniformly within it: expected > 0");
    }
    if (!r.isPosition() && params_.rotationAxis != 2) {
      throw ConfigError(at + ": " + relationKindName(r.kind) +
                        " sets the turn about z: rotation_axis must be z");
    }
    if (!r.isPosition() && params_.resting == UniformSamplerParams::Resting::Stable) {
      throw ConfigError(at + ": " + relationKindName(r.kind) +
                        " takes resting: upright only (a resting pose may have no heading)");
    }
  }
}

void UniformRandomSampler::bindRelations(Entry& entry) const {
  const ObjectModel& object = *entry.object;
  int turn = -1;
  for (std::size_t i = 0; i < params_.relations.size(); ++i) {
    const Relation& r = params_.relations[i];
    if (!r.appliesTo(object.name)) {
      continue;
    }
    if (r.target == object.name) {
      throw ConfigError("sampler " + quoteText(name()) + ": " + relationLabel(r, i) +
                        " relates object " + quoteText(object.name) + " to itself");
    }
    if (!r.isPosition()) {
      if (turn >= 0) {
        throw ConfigError("sampler " + quoteText(name()) + ": " + relationLabel(r, i) + " and " +
                          relationLabel(params_.relations[static_cast<std::size_t>(turn)],
                                        static_cast<std::size_t>(turn)) +
                          " both set the yaw of object " + quoteText(object.name) +
                          ": give one align_with or face per object");
      }
      const Eigen::Vector3d x = object.initOrientation * Eigen::Vector3d::UnitX();
      if (std::hypot(x.x(), x.y()) < 1e-6) {
        throw ConfigError("sampler " + quoteText(name()) + ": " + relationLabel(r, i) +
                          ": object " + quoteText(object.name) +
                          " has no heading (its +x axis is vertical in its initial orientation)");
      }
      turn = static_cast<int>(i);
      entry.heading0 = headingOf(object.initOrientation);
    }
    entry.relations.push_back(static_cast<std::uint16_t>(i));
  }
}

bool UniformRandomSampler::resolveRelations(SampleContext& context, const Entry& entry,
                                            const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                            PlacementRelations& out) const {
  const ObjectModel& object = *entry.object;
  out.exact = context.needsOrientation();
  out.boxLo = lo;
  out.boxHi = hi;
  // Under resting: stable the poses' radii differ: the test must fail for all of them.
  out.leastRadius = object.horizontalRadius;
  out.mostRadius = object.horizontalRadius;
  for (const Entry& pose : entry.poses) {
    out.leastRadius = std::min(out.leastRadius, pose.object->horizontalRadius);
    out.mostRadius = std::max(out.mostRadius, pose.object->horizontalRadius);
  }
  const auto failWith = [&](std::size_t i, const std::string& why) {
    return fail(context, &object, 0,
                "could not place object " + quoteText(object.name) + " with sampler " +
                    quoteText(name()) + ": " + relationLabel(params_.relations[i], i) + " " + why);
  };
  for (const std::uint16_t i : entry.relations) {
    const Relation& r = params_.relations[i];
    const PlacedEntry* target = context.find(r.target);
    if (target == nullptr) {
      return failWith(i,
                      "cannot hold: its target is neither a fixture nor an object placed "
                      "before it");
    }
    // The target's heading (an atan2) only for align_with.
    const RelationTarget t = relationTarget(*target, r.kind == Relation::Kind::AlignWith);
    if (r.isPosition()) {
      PositionTest& test = out.position[out.count++];
      test = PositionTest(r, i, t);
      test.entry = target - context.entries().data();
      continue;
    }
    out.turns = true;
    RotationTest& turn = out.turn;
    turn.kind = r.kind;
    turn.index = i;
    turn.tolerance = r.tolerance;
    turn.period = r.period;
    turn.target = t.centre;
    turn.h0 = entry.heading0;
    turn.centre = t.heading - turn.h0;
    if (r.kind != Relation::Kind::AlignWith) {
      continue;
    }
    const RotationSpec& spec = params_.rotation;
    if (spec.kind == RotationSpec::Kind::Fixed) {
      if (angleApart(spec.low + turn.h0, t.heading, r.period) > r.tolerance) {
        std::ostringstream why;
        why << "cannot hold: the fixed rotation " << spec.low << " rad gives object "
            << quoteText(object.name) << " a yaw "
            << angleApart(spec.low + turn.h0, t.heading, r.period)
            << " rad from the target's (modulo the period)";
        return failWith(i, why.str());
      }
      continue;
    }
    const double low = spec.kind == RotationSpec::Kind::Full ? 0.0 : spec.low;
    const double high = spec.kind == RotationSpec::Kind::Full ? 2 * M_PI : spec.high;
    out.alignedLength = alignedLength(turn, low, high);
    if (!(out.alignedLength > 0.0)) {
      std::ostringstream why;
      why << "cannot hold: no turn of rotation [" << low << ", " << high
          << "] rad gives the target's yaw " << t.heading << " rad within the tolerance";
      return failWith(i, why.str());
    }
  }
  return true;
}

bool UniformRandomSampler::relationsPossible(SampleContext& context, const ObjectModel& object,
                                             const PlacementRelations& relations) const {
  if (relations.boxLo.x() > relations.boxHi.x()) {
    return true;
  }
  // The exact gaps of the fcl modes have no bound from the disks: the sides only.
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < relations.count; ++k) {
    const PositionTest& test = relations.position[k];
    const std::string why = infeasibleReason(test, relations.exact ? -inf : relations.leastRadius,
                                             relations.exact ? inf : relations.mostRadius,
                                             relations.boxLo, relations.boxHi);
    if (!why.empty()) {
      return fail(context, &object, kRelationProbeAttempts - 1,
                  "could not place object " + quoteText(object.name) + " with sampler " +
                      quoteText(name()) + ": " +
                      relationLabel(params_.relations[test.index], test.index) +
                      " cannot hold anywhere: " + why);
    }
  }
  return true;
}

bool UniformRandomSampler::relationsAccept(SampleContext& context, Engine& engine,
                                           PlacementRelations& relations,
                                           Candidate& candidate) const {
  if (relations.exact) {
    // Face: towards the target from here.
    candidate.orientation =
        relatedOrientation(engine, *candidate.object, candidate.position.head<2>(), &relations);
  }
  return relationsHold(context, relations, candidate);
}

bool UniformRandomSampler::relationsHold(SampleContext& context, PlacementRelations& relations,
                                         const Candidate& candidate) const {
  const Eigen::Vector2d p = candidate.position.head<2>();
  const double radius = candidate.object->horizontalRadius;
  if (!relations.exact) {
    return relations.holds(p, radius);
  }
  for (std::size_t k = 0; k < relations.count; ++k) {
    const PositionTest& test = relations.position[k];
    double gap = 0.0;
    const bool holds = test.entry >= 0 && context.exactDistance(
                                              static_cast<std::size_t>(test.entry), candidate, gap)
                           ? test.holdsGap(p, gap)
                           : test.holds(p, radius);
    if (!holds) {
      ++relations.refused[k];
      return false;
    }
  }
  return true;
}

Eigen::Quaterniond UniformRandomSampler::relatedOrientation(
    Engine& engine, const ObjectModel& object, const Eigen::Vector2d& p,
    const PlacementRelations* relations) const {
  if (relations == nullptr || !relations->turns) {
    return sampleOrientation(engine, object);
  }
  const RotationTest& t = relations->turn;
  const RotationSpec& spec = params_.rotation;
  double angle = spec.low;
  if (t.kind == Relation::Kind::Face) {
    // Towards the target's centre, then one draw within the tolerance.
    const Eigen::Vector2d d = t.target - p;
    angle = std::atan2(d.y(), d.x()) - t.h0 + uniform(engine, -t.tolerance, t.tolerance);
  } else if (spec.kind != RotationSpec::Kind::Fixed) {
    // One draw along the allowed turns of the rotation's interval, in increasing order.
    const double low = spec.kind == RotationSpec::Kind::Full ? 0.0 : spec.low;
    const double high = spec.kind == RotationSpec::Kind::Full ? 2 * M_PI : spec.high;
    angle = alignedTurn(t, low, high, uniform(engine, 0.0, relations->alignedLength));
  }
  return orientationOf(angle, object);
}

}  // namespace placement_samplers
