// Strategy free_space on a surface region: rejection's draws on the surfaces first, then draws
// from cells per surface that may still hold a free position (README, "Strategies").
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "collision/radius_test.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"
#include "sampling/free_cells.hpp"
#include "sampling/free_space_parts.hpp"

namespace placement_samplers {

bool UniformRandomSampler::sampleFreeSpaceOnSurfaces(SampleContext& context,
                                                     const Eigen::Vector3d& base) const {
  const SurfaceRegion& region = *params_.surface;
  const Eigen::Vector2d offset = base.head<2>();
  Engine& engine = engineOf(context);
  const std::uint32_t limit = attemptLimit(context);
  const bool check = params_.ensureValidPlacement;
  const bool orientFirst = check && context.needsOrientation();
  const bool prune = check && context.includesRadiusTest();
  // Per thread and surface, so that their buffers serve every scene.
  thread_local std::vector<detail::FreeCells> cells;
  thread_local std::vector<detail::NearbyEntries> nearby;
  thread_local std::vector<char> usable;
  // Objects of the same size on the same surfaces share the cells: the next one only drops
  // what the objects placed since cover (the cells' splits are kept).
  // (Each object has a draw of its own, made from the same surfaces with its inset and
  // height: equal numbers, equal draws.)
  struct Key {
    std::ptrdiff_t support = -1;
    double radius = -1.0;
    double margin = 0.0;
    double inset = 0.0;
    double height = 0.0;
    double lift = 0.0;
    double bottom = 0.0;
    bool operator==(const Key& o) const {
      return support == o.support && radius == o.radius && margin == o.margin && inset == o.inset &&
             height == o.height && lift == o.lift && bottom == o.bottom;
    }
  };
  Key previous;
  std::size_t applied = 0;

  for (const Entry& entry : entries_) {
    const ObjectModel& object = *entry.object;
    const PlacedEntry* target = context.find(region.of);
    if (target == nullptr) {
      return fail(context, &object, 0,
                  "sampler " + quoteText(name()) + ": region.of " + quoteText(region.of) +
                      " is neither a fixture nor an object placed before this sampler");
    }
    // An index: the entries grow while this sampler places its objects.
    const std::ptrdiff_t support = target - context.entries().data();
    std::string error;
    const SurfaceDraw* draw = surfaceDrawOn(context, entry, *target, error);
    if (draw == nullptr) {
      return fail(context, &object, 0, error);
    }
    // On the heap and tested out of line, as in sampleFreeSpace().
    std::unique_ptr<PlacementRelations> relations;
    if (!entry.relations.empty()) {
      relations = std::make_unique<PlacementRelations>();
      if (!resolveRelations(context, entry, Eigen::Vector2d(1.0, 1.0), Eigen::Vector2d(0.0, 0.0),
                            *relations)) {
        return false;
      }
    }
    const bool related = relations != nullptr;
    const double radius = object.horizontalRadius;
    const double keepOutMargin = params_.ensureObjectBoundaryInRange ? radius : 0.0;
    const double lift = params_.zOffset - object.bottomOffset.z();
    const double bottom = object.bottomOffset.z();
    std::vector<std::uint32_t>* counts = check ? &context.blockerCounts() : nullptr;
    std::uint32_t outside = 0;
    std::uint32_t collided = 0;
    Candidate candidate;
    candidate.object = &object;

    // One attempt at @p p on surface @p surface, as placeOnSurface() tests it: true when placed.
    // @p fromCells: a cell's draw, which may lie off the inset surface (the surface's own draws
    // never do).
    const auto attemptAt = [&](const Eigen::Vector2d& p, std::size_t surface, std::uint32_t attempt,
                               bool fromCells) {
      candidate.position = Eigen::Vector3d(p.x(), p.y(), draw->z(surface) + lift);
      candidate.support = support;
      if (orientFirst && !related) {
        candidate.orientation = sampleOrientation(engine, object);
      }
      const bool blocked = (fromCells && draw->insetDepth(p, surface) < 0.0) ||
                           !draw->accepts(p, surface) ||
                           inKeepOut(p - offset, offset, keepOutMargin);
      outside += blocked ? 1 : 0;
      if (blocked || (related && !relationsAccept(context, engine, *relations, candidate)) ||
          (check && collidesCounted(context, candidate, *counts, collided))) {
        return false;
      }
      if (related && !relations->exact) {
        candidate.orientation = relatedOrientation(engine, object, p, relations.get());
      } else if (!related && !orientFirst) {
        candidate.orientation = sampleOrientation(engine, object);
      }
      context.addPlacement(name(), candidate, attempt, params_.hides);
      return true;
    };
    const auto impossible = [&](std::uint32_t attempt) {
      return related && attempt == kRelationProbeAttempts &&
             !relationsPossible(context, object, *relations);
    };
    const PlacementRelations* refusals = relations.get();

    // Rejection first, on the surfaces as rejection draws: uniform over the free positions
    // when it passes, as the cells' draws are, so the mixture is too.
    const std::uint32_t rejectionAttempts = std::min(limit / 8, detail::kRejectionAttempts);
    bool placed = false;
    std::uint32_t attempt = 1;
    for (; attempt <= rejectionAttempts && !placed; ++attempt) {
      if (impossible(attempt)) {
        return false;
      }
      std::size_t surface = 0;
      const Eigen::Vector2d p = draw->draw(engine, surface);
      placed = attemptAt(p, surface, attempt, false);
    }
    if (placed) {
      continue;
    }
    if (attempt > limit) {
      return failPlacement(context, object, limit, collided > 0 ? counts : nullptr, outside,
                           refusals);
    }

    // The cells of each surface: dropped when wholly off the inset surface, in a keep-out zone
    // or in the exclusion disk of an entry that blocks at that surface's height (never the
    // surface's own object, which the radius test skips). The disks shrink by a hair, so
    // rounding never drops a free position.
    std::size_t tests = 0;
    std::size_t nextClock = detail::kClockPeriod;
    bool outOfTime = false;
    const auto timeOut = [&]() {
      if (++tests >= nextClock) {
        nextClock = tests + detail::kClockPeriod;
        outOfTime = outOfTime || context.expired();
      }
      return outOfTime;
    };
    const std::size_t surfaces = draw->surfaceCount();
    cells.resize(std::max(cells.size(), surfaces));
    nearby.resize(std::max(nearby.size(), surfaces));
    const auto covered = [&](std::size_t surface, const Eigen::Vector2d& c, double h) {
      if (timeOut()) {
        return true;
      }
      if (draw->insetDepth(c, surface) + h * (1.0 + 1e-12) + 1e-12 < 0.0) {
        return true;
      }
      for (const KeepOutZone& zone : params_.keepOut) {
        const Eigen::Vector2d q = zone.world ? c : Eigen::Vector2d(c - offset);
        if (shapeDepth(zone.shape, q) - h > -keepOutMargin) {
          return true;
        }
      }
      return prune && nearby[surface].any(c, [&](std::size_t i) {
        const PlacedEntry& e = context.entries()[i];
        const double reach = radius + e.object->horizontalRadius;
        const double inside = reach * (1.0 - 1e-12) - 1e-12 - h;
        return inside > 0.0 && (c - e.position.head<2>()).squaredNorm() < inside * inside;
      });
    };
    const auto blocksAt = [&](std::size_t s, std::size_t i) {
      const PlacedEntry& e = context.entries()[i];
      return prune && static_cast<std::ptrdiff_t>(i) != support &&
             detail::radiusHeightsOverlap(draw->z(s) + lift, bottom, e.position.z(),
                                          e.object->topOffset.z());
    };
    const Key key{
        support, radius, keepOutMargin, surfaceInset(object), object.topOffset.z() - bottom,
        lift,    bottom};
    if (!(key == previous)) {
      usable.assign(surfaces, 0);
      for (std::size_t s = 0; s < surfaces; ++s) {
        Eigen::Vector2d lo;
        Eigen::Vector2d hi;
        if (!draw->drawnBounds(s, lo, hi)) {
          continue;
        }
        usable[s] = 1;
        const double side = radius > 0.0 ? radius : (hi - lo).maxCoeff() / 32.0;
        cells[s].reset(lo, hi, std::max(side, 1e-6), detail::kMaxCells);
        double reach = 2.0 * radius;
        for (const PlacedEntry& e : context.entries()) {
          reach = std::max(reach, radius + e.object->horizontalRadius);
        }
        nearby[s].reset(lo, hi, std::max(reach, 1e-6));
        for (std::size_t i = 0; i < context.entries().size(); ++i) {
          if (blocksAt(s, i)) {
            nearby[s].add(i, context.entries()[i].position.head<2>());
          }
        }
        cells[s].dropIf([&](const Eigen::Vector2d& c, double h) { return covered(s, c, h); });
      }
      previous = key;
    } else {
      // Only the objects placed since can block more (they are of this size: the key holds it).
      for (std::size_t s = 0; s < surfaces; ++s) {
        for (std::size_t i = applied; usable[s] && i < context.entries().size(); ++i) {
          if (blocksAt(s, i)) {
            nearby[s].add(i, context.entries()[i].position.head<2>());
            cells[s].dropIf([&](const Eigen::Vector2d& c, double h) { return covered(s, c, h); });
          }
        }
      }
    }
    applied = context.entries().size();
    if (outOfTime) {
      return failOutOfTime(context, object, attempt - 1);
    }

    for (; attempt <= limit && !placed; ++attempt) {
      double area = 0.0;
      for (std::size_t s = 0; s < surfaces; ++s) {
        area += usable[s] ? cells[s].area() : 0.0;
      }
      if (!(area > 0.0)) {
        return fail(context, &object, attempt - 1,
                    "could not place object " + quoteText(object.name) + " with sampler " +
                        quoteText(name()) + ": no free position is left on the surfaces of " +
                        quoteText(region.of) + " (strategy free_space, " +
                        countText(attempt - 1, "attempt") + ")");
      }
      if ((attempt & 1023u) == 0 && context.expired()) {
        return failOutOfTime(context, object, attempt - 1);
      }
      if (impossible(attempt)) {
        return false;
      }
      // A surface by its cells' area, then a cell of it by area: a cell by area over all.
      double t = uniform01(engine) * area;
      std::size_t surface = 0;
      for (std::size_t s = 0; s < surfaces; ++s) {
        const double a = usable[s] ? cells[s].area() : 0.0;
        if (!(a > 0.0)) {
          continue;
        }
        surface = s;
        if (t < a) {
          break;
        }
        t -= a;
      }
      int level = 0;
      std::size_t index = 0;
      const Eigen::Vector2d p = cells[surface].draw(engine, level, index);
      placed = attemptAt(p, surface, attempt, true);
      if (!placed) {
        cells[surface].refine(level, index, [&](const Eigen::Vector2d& c, double h) {
          return covered(surface, c, h);
        });
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
