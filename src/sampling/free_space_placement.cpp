// Strategy free_space of the uniform sampler: draws from the cells that may still hold a free
// position (free_cells.hpp) instead of the whole region.
#include <algorithm>
#include <cmath>

#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"
#include "collision/radius_test.hpp"
#include "sampling/free_cells.hpp"

namespace placement_samplers {
namespace {

/// Cells per side of the largest level-0 grid: 64 x 64.
constexpr std::size_t kMaxCells = 4096;

/// Rejection attempts over the whole box before the cells are built: an object that needs more
/// has little free room left, where the cells pay for themselves.
constexpr std::uint32_t kRejectionAttempts = 512;
/// Shape and disk tests between two readings of the clock while cells are pruned.
constexpr std::size_t kClockPeriod = std::size_t{1} << 18;

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

/// The entries that may block an object, bucketed by their x-y (sampler frame) in squares of
/// the largest reach, so that testing a cell reads the entries of the 3 x 3 squares around it.
class NearbyEntries {
 public:
  void reset(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double side) {
    const Eigen::Vector2d extent = hi - lo;
    side_ = std::max(side, std::sqrt(extent.x() * extent.y() / 65536.0));
    lo_ = lo;
    nx_ = std::max(1, static_cast<int>(std::ceil(extent.x() / side_)));
    ny_ = std::max(1, static_cast<int>(std::ceil(extent.y() / side_)));
    buckets_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
    for (std::vector<std::size_t>& bucket : buckets_) {
      bucket.clear();  // keeps its buffer for the next scene
    }
  }
  void add(std::size_t index, const Eigen::Vector2d& p) {
    buckets_[static_cast<std::size_t>(row(p.y()) * nx_ + column(p.x()))].push_back(index);
  }
  /// True when @p f is true for an entry of the squares around @p p; entries outside the grid
  /// sit in its border squares, so every entry within one side of @p p is read.
  template <typename F>
  bool any(const Eigen::Vector2d& p, const F& f) const {
    const int i = column(p.x());
    const int j = row(p.y());
    for (int b = std::max(j - 1, 0); b <= std::min(j + 1, ny_ - 1); ++b) {
      for (int a = std::max(i - 1, 0); a <= std::min(i + 1, nx_ - 1); ++a) {
        for (const std::size_t index : buckets_[static_cast<std::size_t>(b * nx_ + a)]) {
          if (f(index)) {
            return true;
          }
        }
      }
    }
    return false;
  }

 private:
  int column(double x) const {
    return std::clamp(static_cast<int>(std::floor((x - lo_.x()) / side_)), 0, nx_ - 1);
  }
  int row(double y) const {
    return std::clamp(static_cast<int>(std::floor((y - lo_.y()) / side_)), 0, ny_ - 1);
  }

  Eigen::Vector2d lo_ = Eigen::Vector2d::Zero();
  double side_ = 1.0;
  int nx_ = 1;
  int ny_ = 1;
  std::vector<std::vector<std::size_t>> buckets_;
};

}  // namespace

bool UniformRandomSampler::sampleFreeSpace(SampleContext& context, const Eigen::Vector3d& base,
                                           bool onTop) const {
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
    const bool related = !entry.relations.empty();
    PlacementRelations relations;
    if (related && !resolveRelations(context, entry, lo + offset, hi + offset, relations)) {
      return false;
    }
    // At kRelationProbeAttempts: false, after fail(), when a relation cannot hold in the box.
    const auto relationsImpossible = [&](std::uint32_t attempt) {
      return related && attempt == kRelationProbeAttempts &&
             !relationsPossible(context, object, relations);
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
        // The fcl modes' exact gaps need the turn (face: towards the target from here).
        if (relations.exact) {
          candidate.orientation =
              relatedOrientation(engine, object, candidate.position.head<2>(), &relations);
        }
        blocked = !relationsHold(context, relations, candidate);
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
      if (related && !relations.exact) {
        candidate.orientation =
            relatedOrientation(engine, object, candidate.position.head<2>(), &relations);
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
    const PlacementRelations* refusals = related ? &relations : nullptr;
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
