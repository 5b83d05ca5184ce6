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
  if (!entry.poses.empty()) {
    return placeOneResting(context, entry, base, onTop);
  }
  if (params_.surface) {
    return placeOnSurface(context, entry, base);
  }
  if (entry.draw) {
    return placeOneShaped(context, entry, base, onTop);
  }
  if (UniformSource* source = context.uniformSource()) {
    SourceDraws draws{*source};
    return placeInRectangle(context, entry, base, onTop, draws);
  }
  EngineDraws draws{engineOf(context)};
  return placeInRectangle(context, entry, base, onTop, draws);
}

template <class Draws>
bool UniformRandomSampler::placeInRectangle(SampleContext& context, const Entry& entry,
                                            const Eigen::Vector3d& base, bool onTop,
                                            Draws& draws) const {
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
    if (orientFirst) {
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
    if (!orientFirst) {
      angle = drawAngle(draws);
      if (params_.orientations) {
        candidate.orientation = orientationOf(angle, object);
      }
    }
    draws.rotation(angle);
    context.addPlacement(name(), candidate, attempt, params_.hides);
    return true;
  }

  return failPlacement(context, object, limit, counts, 0);
}

}  // namespace placement_samplers
