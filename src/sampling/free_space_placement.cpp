// Strategy free_space of the uniform sampler: draws from the cells that may still hold a free
// position (free_cells.hpp) instead of the whole region.
#include <algorithm>
#include <cmath>
#include <memory>

#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"
#include "collision/radius_test.hpp"
#include "sampling/free_cells.hpp"
#include "sampling/free_space_parts.hpp"

namespace placement_samplers {
namespace {

using detail::kClockPeriod;
using detail::kMaxCells;
using detail::kRejectionAttempts;
using detail::NearbyEntries;

/// What decides the blocked set of one object: objects that share it share the cells.
struct CellKey {
  double radius = -1.0;
  double margin = 0.0;
  double z = 0.0;
  double bottom = 0.0;
  bool operator==(const CellKey& o) const {
    return radius == o.radius && margin == o.margin && z == o.z && bottom == o.bottom;
  }
};

}  // namespace

bool UniformRandomSampler::sampleFreeSpace(SampleContext& context, const Eigen::Vector3d& base,
                                           bool onTop) const {
  if (params_.surface) {
    return sampleFreeSpaceOnSurfaces(context, base);
  }
  const RegionShape plain = RegionShape::rectangle(params_.xRange, params_.yRange);
  const RegionShape& region = params_.region ? *params_.region : plain;
  const Eigen::Vector2d offset = base.head<2>();
  Engine& engine = engineOf(context);
  const std::uint32_t limit = attemptLimit(context);
  const bool check = params_.ensureValidPlacement;
  const bool orientFirst = check && context.needsOrientation();
  // robosuite's radius test prunes cells only when the check includes it (radius,
  // radius_and_fcl): fcl alone may accept what it refuses, so there only the region and the
  // keep-out zones prune.
  const bool prune = check && context.includesRadiusTest();
  // Per thread, so that their buffers serve every scene (nothing here calls another sampler).
  thread_local detail::FreeCells cells;
  thread_local NearbyEntries nearby;
  CellKey previous;
  std::size_t applied = 0;
  // Pruning cells tests each against every keep-out zone and nearby entry: many zones and
  // objects of many sizes make it long, so it reads the clock every kClockPeriod tests. Once
  // the time is out every cell counts as covered (they all go at once), and the scene fails.
  std::size_t tests = 0;
  std::size_t nextClock = kClockPeriod;
  bool outOfTime = false;
  const auto timeOut = [&](std::size_t cost) {
    tests += cost;
    if (tests >= nextClock) {
      nextClock = tests + kClockPeriod;
      outOfTime = outOfTime || context.expired();
    }
    return outOfTime;
  };

  for (const Entry& entry : entries_) {
    const ObjectModel& object = *entry.object;
    const double radius = object.horizontalRadius;
    const double margin = params_.ensureObjectBoundaryInRange ? radius : 0.0;
    const double bottom = object.bottomOffset.z();
    const double z = height(object, base, onTop);
    // Whole cells (centre c, half diagonal h, in the sampler's frame) known to be blocked: the
    // distances change by at most h over the cell. The disks shrink by a hair, so rounding
    // never drops a free position.
    const auto blocks = [&](const PlacedEntry& e) {
      return detail::radiusHeightsOverlap(z, bottom, e.position.z(), e.object->topOffset.z());
    };
    const auto disk = [&](const PlacedEntry& e, const Eigen::Vector2d& c, double h) {
      const double reach = radius + e.object->horizontalRadius;
      const double inside = reach * (1.0 - 1e-12) - 1e-12 - h;
      return inside > 0.0 && (c + offset - e.position.head<2>()).squaredNorm() < inside * inside;
    };
    const auto covered = [&](const Eigen::Vector2d& c, double h) {
      if (timeOut(1 + params_.keepOut.size())) {
        return true;
      }
      if (shapeDepth(region, c) + h < margin) {
        return true;
      }
      for (const KeepOutZone& zone : params_.keepOut) {
        if (shapeDepth(zone.shape, zone.world ? Eigen::Vector2d(c + offset) : c) - h > -margin) {
          return true;
        }
      }
      return prune &&
             nearby.any(c, [&](std::size_t i) { return disk(context.entries()[i], c, h); });
    };

    const Eigen::Vector2d lo = boundsLo_ + Eigen::Vector2d::Constant(margin);
    const Eigen::Vector2d hi = boundsHi_ - Eigen::Vector2d::Constant(margin);
    if (!(hi.x() > lo.x() && hi.y() > lo.y())) {
      // A region of no area (a range the shrink leaves zero wide): robosuite's draws.
      if (!placeOne(context, entry, base, onTop)) {
        return false;
      }
      previous = CellKey();
      continue;
    }

    // Relations are tests of each attempt, as under rejection: the draws from the cells then stay
    // uniform over the free positions where every relation holds.
    // On the heap, and tested out of line: an object without relations keeps the loop it had
    // (1.7 kB more in its frame and the tests inline made it 5-15 % slower).
    std::unique_ptr<PlacementRelations> relations;
    if (!entry.relations.empty()) {
      relations = std::make_unique<PlacementRelations>();
      if (!resolveRelations(context, entry, lo + offset, hi + offset, *relations)) {
        return false;
      }
    }
    const bool related = relations != nullptr;
    // At kRelationProbeAttempts: false, after fail(), when a relation cannot hold in the box.
    const auto relationsImpossible = [&](std::uint32_t attempt) {
      return related && attempt == kRelationProbeAttempts &&
             !relationsPossible(context, object, *relations);
    };

    // Rejections per entry for the failure message, zeroed at the first collision: most objects
    // are placed at their first attempt.
    std::vector<std::uint32_t>* counts = nullptr;
    std::uint32_t outside = 0;
    std::uint32_t collided = 0;
    Candidate candidate;
    candidate.object = &object;
    candidate.position.z() = z;
    // One attempt at @p local (sampler frame): true when it is placed.
    // @p inBox: @p local is a draw of the box of a plain x/y-range region, which is robosuite's
    // shrunk range itself.
    const auto attemptAt = [&](const Eigen::Vector2d& local, std::uint32_t attempt, bool inBox) {
      candidate.position.head<2>() = local + offset;
      if (orientFirst && !related) {
        candidate.orientation = sampleOrientation(engine, object);
      }
      bool blocked = !inBox && shapeDepth(region, local) < margin;
      for (std::size_t i = 0; i < params_.keepOut.size() && !blocked; ++i) {
        const KeepOutZone& zone = params_.keepOut[i];
        blocked = keepOutBlocks(zone, zone.world ? Eigen::Vector2d(local + offset) : local, margin);
      }
      outside += blocked ? 1 : 0;
      if (!blocked && related) {
        blocked = !relationsAccept(context, engine, *relations, candidate);
      }
      if (!blocked && check) {
        const std::ptrdiff_t blocker = context.firstCollision(candidate);
        if (blocker != CollisionChecker::kNone) {
          if (counts == nullptr) {
            counts = &context.blockerCounts();
          }
          ++(*counts)[static_cast<std::size_t>(blocker)];
          ++collided;
          blocked = true;
        }
      }
      if (blocked) {
        return false;
      }
      if (related && !relations->exact) {
        candidate.orientation =
            relatedOrientation(engine, object, candidate.position.head<2>(), relations.get());
      } else if (!related && !orientFirst) {
        candidate.orientation = sampleOrientation(engine, object);
      }
      context.addPlacement(name(), candidate, attempt, params_.hides);
      return true;
    };

    // Rejection first, over the box the cells would cover: a draw that passes is uniform over
    // the free positions, as a draw from the cells is, so the mixture of the two is uniform too.
    // Most objects are placed here and never pay for the cells.
    // An eighth of a small attempt limit, so that the cells still get most of it.
    const std::uint32_t rejectionAttempts = std::min(limit / 8, kRejectionAttempts);
    const bool plainRange = !params_.region;
    bool placed = false;
    std::uint32_t attempt = 1;
    for (; attempt <= rejectionAttempts && !placed; ++attempt) {
      if (relationsImpossible(attempt)) {
        return false;
      }
      const double x = uniform(engine, lo.x(), hi.x());
      const double y = uniform(engine, lo.y(), hi.y());
      placed = attemptAt(Eigen::Vector2d(x, y), attempt, plainRange);
    }
    if (placed) {
      continue;
    }
    const PlacementRelations* refusals = relations.get();
    if (attempt > limit) {
      return failPlacement(context, object, limit, collided > 0 ? counts : nullptr, outside,
                           refusals);
    }

    const CellKey key{radius, margin, z, bottom};
    if (!(key == previous)) {
      const double side = radius > 0.0 ? radius : (hi - lo).maxCoeff() / 32.0;
      cells.reset(lo, hi, side, kMaxCells);
      double reach = 2.0 * radius;
      for (const PlacedEntry& e : context.entries()) {
        reach = std::max(reach, radius + e.object->horizontalRadius);
      }
      nearby.reset(lo, hi, std::max(reach, 1e-6));
      for (std::size_t i = 0; prune && i < context.entries().size(); ++i) {
        if (blocks(context.entries()[i])) {
          nearby.add(i, context.entries()[i].position.head<2>() - offset);
        }
      }
      cells.dropIf(covered);
      previous = key;
    } else if (prune) {
      // Same object size and height: only the objects placed since can block more.
      for (std::size_t i = applied; i < context.entries().size(); ++i) {
        const PlacedEntry& e = context.entries()[i];
        if (blocks(e)) {
          nearby.add(i, e.position.head<2>() - offset);
          cells.dropIf(
              [&](const Eigen::Vector2d& c, double h) { return timeOut(1) || disk(e, c, h); });
        }
      }
    }
    applied = context.entries().size();
    if (outOfTime) {
      return failOutOfTime(context, object, 0);
    }

    for (; attempt <= limit && !placed; ++attempt) {
      if (cells.empty()) {
        return fail(context, &object, attempt - 1,
                    // "1 attempts" stays: shipped outputs (scripts/same_output) hold this text.
                    "could not place object " + quoteText(object.name) + " with sampler " +
                        quoteText(name()) + ": no free position is left (strategy free_space, " +
                        std::to_string(attempt - 1) + " attempts)");
      }
      if ((attempt & 1023u) == 0 && context.expired()) {
        return failOutOfTime(context, object, attempt - 1);
      }
      if (relationsImpossible(attempt)) {
        return false;
      }
      int level = 0;
      std::size_t index = 0;
      const Eigen::Vector2d local = cells.draw(engine, level, index);
      placed = attemptAt(local, attempt, false);
      if (!placed) {
        cells.refine(level, index, covered);
        if (outOfTime) {
          return failOutOfTime(context, object, attempt);
        }
      }
    }
    if (!placed) {
      return failPlacement(context, object, limit, collided > 0 ? counts : nullptr, outside,
                           refusals);
    }
  }
  return true;
}

}  // namespace placement_samplers
