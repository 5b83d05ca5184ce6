// robosuite's rectangle: the rejection loop of a uniform sampler without a region shape or
// keep-out zones, drawing from the scene's engine or from a caller's UniformSource.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"
#include "sampling/free_position_check.hpp"

namespace placement_samplers {
namespace {

/// Draws from the scene's engine (the library's own sampling).
struct EngineDraws {
  Engine& engine;
  double operator()(double low, double high, UniformSource::Draw) {
    return uniform(engine, low, high);
  }
  void rotation(double) {}
};

/// Draws from a caller's source (SampleContext::setUniformSource).
struct SourceDraws {
  UniformSource& source;
  double operator()(double low, double high, UniformSource::Draw what) {
    return source.uniform(low, high, what);
  }
  void rotation(double angle) { source.rotation(angle); }
};

}  // namespace

template <class Draws>
double UniformRandomSampler::drawAngle(Draws& draws) const {
  if (params_.rotation.kind == RotationSpec::Kind::Full) {
    return draws(0.0, 2.0 * M_PI, UniformSource::Draw::Rotation);
  }
  if (params_.rotation.kind == RotationSpec::Kind::Range) {  // draws when low == high
    return draws(params_.rotation.low, params_.rotation.high, UniformSource::Draw::Rotation);
  }
  return params_.rotation.low;
}

Eigen::Quaterniond UniformRandomSampler::sampleOrientation(Engine& engine,
                                                           const ObjectModel& object) const {
  EngineDraws draws{engine};
  return orientationOf(drawAngle(draws), object);
}

bool UniformRandomSampler::placeOne(SampleContext& context, const Entry& entry,
                                    const Eigen::Vector3d& base, bool onTop) const {
  if (!entry.relations.empty()) {
    // The box the centres are drawn from, for the fast failure of a relation that cannot
    // hold: the inset rectangle, a shape's bounds, none on surfaces (lo > hi).
    const bool rectangle = entry.poses.empty() && !params_.surface && !entry.draw;
    const Eigen::Vector2d lo = params_.surface ? Eigen::Vector2d(1.0, 1.0)
                               : rectangle     ? Eigen::Vector2d(entry.x[0], entry.y[0])
                                               : boundsLo_;
    const Eigen::Vector2d hi = params_.surface ? Eigen::Vector2d(0.0, 0.0)
                               : rectangle     ? Eigen::Vector2d(entry.x[1], entry.y[1])
                                               : boundsHi_;
    const Eigen::Vector2d shift =
        params_.surface ? Eigen::Vector2d::Zero() : Eigen::Vector2d(base.head<2>());
    PlacementRelations relations;
    if (!resolveRelations(context, entry, lo + shift, hi + shift, relations)) {
      return false;
    }
    if (!entry.poses.empty()) {
      return placeOneResting(context, entry, base, onTop, &relations);
    }
    if (params_.surface) {
      return placeOnSurface(context, entry, base, &relations);
    }
    if (entry.draw) {
      return placeOneShaped(context, entry, base, onTop, &relations);
    }
    EngineDraws draws{engineOf(context)};
    return placeInRectangle<true>(context, entry, base, onTop, draws, &relations);
  }
  if (!entry.poses.empty()) {
    return placeOneResting(context, entry, base, onTop, nullptr);
  }
  if (params_.surface) {
    return placeOnSurface(context, entry, base, nullptr);
  }
  if (entry.draw) {
    return placeOneShaped(context, entry, base, onTop, nullptr);
  }
  if (UniformSource* source = context.uniformSource()) {
    SourceDraws draws{*source};
    return placeInRectangle<false>(context, entry, base, onTop, draws, nullptr);
  }
  EngineDraws draws{engineOf(context)};
  return placeInRectangle<false>(context, entry, base, onTop, draws, nullptr);
}

template <bool kRelated, class Draws>
bool UniformRandomSampler::placeInRectangle(SampleContext& context, const Entry& entry,
                                            const Eigen::Vector3d& base, bool onTop, Draws& draws,
                                            PlacementRelations* relations) const {
  const ObjectModel& object = *entry.object;
  // robosuite's draws: per attempt x then y, one rotation draw after the accepted attempt
  // (the fcl modes draw it per attempt, before their test, which needs it).
  const std::uint32_t limit = attemptLimit(context);
  const bool check = params_.ensureValidPlacement;
  const bool orientFirst = check && context.needsOrientation();
  // Rejections per entry, for the failure message; zeroed at the first rejection, since most
  // objects are placed at their first attempt.
  std::vector<std::uint32_t>* counts = nullptr;

  Candidate candidate;
  candidate.object = &object;
  candidate.position.z() = height(object, base, onTop);
  double angle = 0.0;  // of the accepted attempt
  for (std::uint32_t attempt = 1; attempt <= limit; ++attempt) {
    if ((attempt & 1023u) == 0 && context.expired()) {
      return failOutOfTime(context, object, attempt - 1);
    }
    if (attempt == detail::kNoRoomProbeAttempts && check && context.includesRadiusTest() &&
        detail::noFreePosition(context.entries(), object, candidate.position.z(),
                               base.head<2>() + Eigen::Vector2d(entry.x[0], entry.y[0]),
                               base.head<2>() + Eigen::Vector2d(entry.x[1], entry.y[1]))) {
      return fail(context, &object, attempt - 1,
                  "could not place object " + quoteText(object.name) + " with sampler " +
                      quoteText(name()) + ": after " + std::to_string(attempt - 1) +
                      " attempts, no position is left (every position of its range overlaps a "
                      "fixture or an object placed before it)");
    }
    // x before y, as robosuite draws them; stored as one pair, since the checker loads the
    // pair at once and a load that spans two separate stores waits for both to retire.
    const double x = draws(entry.x[0], entry.x[1], UniformSource::Draw::X) + base.x();
    const double y = draws(entry.y[0], entry.y[1], UniformSource::Draw::Y) + base.y();
    candidate.position.head<2>() = Eigen::Vector2d(x, y);
    if constexpr (kRelated) {
      // The relations after the region's draws; after the accepted attempt the turn (face
      // needs the position), but before the test in the fcl modes, whose exact gaps need it.
      if (attempt == kRelationProbeAttempts && !relationsPossible(context, object, *relations)) {
        return false;
      }
      if (relations->exact) {
        // The exact gaps need the orientation: drawn first (face: towards the target from here).
        candidate.orientation =
            relatedOrientation(draws.engine, object, candidate.position.head<2>(), relations);
        if (!relationsHold(context, *relations, candidate)) {
          continue;
        }
      } else if (!relations->holds(candidate.position.head<2>(), object.horizontalRadius)) {
        continue;
      }
    } else if (orientFirst) {
      angle = drawAngle(draws);
      candidate.orientation = orientationOf(angle, object);
    }
    if (check) {
      const std::ptrdiff_t blocker = context.firstCollision(candidate);
      if (blocker != CollisionChecker::kNone) {
        if (counts == nullptr) {
          counts = &context.blockerCounts();
        }
        ++(*counts)[static_cast<std::size_t>(blocker)];
        continue;
      }
    }
    if constexpr (kRelated) {
      if (!relations->exact) {
        candidate.orientation =
            relatedOrientation(draws.engine, object, candidate.position.head<2>(), relations);
      }
    } else {
      if (!orientFirst) {
        angle = drawAngle(draws);
        if (params_.orientations) {
          candidate.orientation = orientationOf(angle, object);
        }
      }
      draws.rotation(angle);
    }
    context.addPlacement(name(), candidate, attempt, params_.hides);
    return true;
  }

  return failPlacement(context, object, limit, counts, 0, relations);
}

}  // namespace placement_samplers
