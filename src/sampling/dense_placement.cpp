// Strategy dense of the uniform sampler: the objects on a randomly shifted and turned
// hexagonal lattice, past the random-packing (jamming) limit of rejection and free_space.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"
#include "sampling/sin_cos.hpp"

namespace placement_samplers {
namespace {

/// Most edge tests of the lattice sites of one scene (about a second): sites in the region's
/// bounding box times the cost of testing one against the region and the keep-out zones.
constexpr double kMaxSiteWork = 2.5e8;
/// Edge tests between two readings of the clock (milliseconds).
constexpr double kClockPeriod = 1 << 20;

/// What testing a point against @p shape costs, in edges.
double shapeCost(const RegionShape& shape) {
  return shape.kind == RegionShape::Kind::Polygon ? static_cast<double>(shape.vertices.size())
                                                  : 1.0;
}

/// The indices j in [-k, k] of the row c + j b whose points may lie within [lo, hi] (widened
/// by @p pad, which covers rounding): the others are outside the region, so they are not
/// tested. @return false when there is none
bool rowRange(const Eigen::Vector2d& c, const Eigen::Vector2d& b, const Eigen::Vector2d& lo,
              const Eigen::Vector2d& hi, double pad, int k, int& first, int& last) {
  double from = -k;
  double to = k;
  for (int d = 0; d < 2; ++d) {
    const double l = lo[d] - pad - c[d];
    const double h = hi[d] + pad - c[d];
    if (b[d] == 0.0) {
      if (l > 0.0 || h < 0.0) {
        return false;
      }
      continue;
    }
    const double t0 = std::min(l / b[d], h / b[d]);
    const double t1 = std::max(l / b[d], h / b[d]);
    from = std::max(from, std::floor(t0));
    to = std::min(to, std::ceil(t1));
  }
  if (!(from <= to)) {
    return false;
  }
  first = static_cast<int>(from);
  last = static_cast<int>(to);
  return true;
}

}  // namespace

bool UniformRandomSampler::sampleDense(SampleContext& context, const Eigen::Vector3d& base,
                                       bool onTop) const {
  if (entries_.empty()) {
    return true;
  }
  const RegionShape region =
      params_.region ? *params_.region : RegionShape::rectangle(params_.xRange, params_.yRange);
  const Eigen::Vector2d offset = base.head<2>();
  Engine& engine = engineOf(context);
  double largest = 0.0;
  for (const Entry& e : entries_) {
    largest = std::max(largest, e.object->horizontalRadius);
  }
  const double margin = params_.ensureObjectBoundaryInRange ? largest : 0.0;
  // Neighbours a hair more than two radii apart: robosuite's test counts touching.
  const double spacing = std::max(2.0 * largest * (1.0 + 1e-9) + 1e-9, 1e-6);

  Eigen::Vector2d lo;
  Eigen::Vector2d hi;
  shapeBounds(region, lo, hi);
  // The work is bounded before any draw, so that a configuration fails every scene or none:
  // the sites in the bounding box (a hexagonal cell per site) times the edges of a test.
  double cost = shapeCost(region);
  for (const KeepOutZone& zone : params_.keepOut) {
    cost += shapeCost(zone.shape);
  }
  const Eigen::Vector2d box = hi - lo + Eigen::Vector2d::Constant(2.0 * spacing);
  const double boxSites = box.x() * box.y() / (0.8660254037844386 * spacing * spacing);
  if (boxSites * cost > kMaxSiteWork) {
    std::ostringstream out;
    out << "sampler " << quoteText(name()) << ": strategy dense: about " << std::llround(boxSites)
        << " lattice sites in the region's bounding box, each tested against " << cost
        << " region and keep-out edges, exceed the limit of "
        << static_cast<long long>(kMaxSiteWork)
        << " tests a scene (larger objects, a smaller region or fewer vertices)";
    return fail(context, entries_.front().object.get(), 0, out.str());
  }

  // The lattice: a shift along each basis vector, then a turn in [0, pi/3) (its symmetry).
  const double u = uniform01(engine);
  const double v = uniform01(engine);
  double s = 0.0;
  double c = 0.0;
  sinCos(uniform(engine, 0.0, M_PI / 3.0), s, c);
  const Eigen::Vector2d a = spacing * Eigen::Vector2d(c, s);
  const Eigen::Vector2d b =
      spacing * Eigen::Vector2d(0.5 * c - 0.8660254037844386 * s, 0.5 * s + 0.8660254037844386 * c);
  const Eigen::Vector2d middle = 0.5 * (lo + hi);
  const double reach = 0.5 * (hi - lo).norm();
  const int k = static_cast<int>(std::ceil(2.0 * reach / spacing)) + 2;
  if (k > 2000) {
    return fail(context, entries_.front().object.get(), 0,
                "sampler " + quoteText(name()) +
                    ": strategy dense: the region is too large for a lattice of its objects");
  }
  std::vector<Eigen::Vector2d> sites;
  double work = 0.0;
  double nextClock = kClockPeriod;
  for (int i = -k; i <= k; ++i) {
    int first = 0;
    int last = -1;
    if (!rowRange(middle + (i + u) * a + v * b, b, lo, hi, spacing, k, first, last)) {
      continue;
    }
    work += cost * (last - first + 1);
    if (work >= nextClock) {
      nextClock = work + kClockPeriod;
      if (context.expired()) {
        return fail(context, entries_.front().object.get(), 0,
                    "sampler " + quoteText(name()) +
                        ": strategy dense: stopped laying out the lattice sites: " +
                        context.outOfTimeReason());
      }
    }
    for (int j = first; j <= last; ++j) {
      const Eigen::Vector2d p = middle + (i + u) * a + (j + v) * b;
      if (shapeDepth(region, p) < margin) {
        continue;
      }
      bool blocked = false;
      for (const KeepOutZone& zone : params_.keepOut) {
        blocked =
            blocked || keepOutBlocks(zone, zone.world ? Eigen::Vector2d(p + offset) : p, margin);
      }
      if (!blocked) {
        sites.push_back(p);
      }
    }
  }
  // A random order of the sites (Fisher-Yates, one draw per swap, from the last site down).
  for (std::size_t i = sites.size(); i > 1; --i) {
    const std::size_t j =
        std::min(i - 1, static_cast<std::size_t>(uniform01(engine) * static_cast<double>(i)));
    std::swap(sites[i - 1], sites[j]);
  }

  // Each object takes the next site that the configured check accepts.
  const bool check = params_.ensureValidPlacement;
  std::size_t next = 0;
  for (const Entry& entry : entries_) {
    const ObjectModel& object = *entry.object;
    Candidate candidate;
    candidate.object = &object;
    candidate.position.z() = height(object, base, onTop);
    const std::size_t first = next;
    bool placed = false;
    while (!placed && next < sites.size()) {
      if (((next - first) & 1023u) == 1023u && context.expired()) {
        return failOutOfTime(context, object, static_cast<std::uint32_t>(next - first));
      }
      candidate.position.head<2>() = sites[next++] + offset;
      candidate.orientation = sampleOrientation(engine, object);
      placed = !check || context.firstCollision(candidate) == CollisionChecker::kNone;
    }
    if (!placed) {
      return fail(context, &object, static_cast<std::uint32_t>(next - first),
                  "could not place object " + quoteText(object.name) + " with sampler " +
                      quoteText(name()) + ": strategy dense ran out of lattice sites (" +
                      std::to_string(sites.size()) + " in the region)");
    }
    context.addPlacement(name(), candidate, static_cast<std::uint32_t>(next - first),
                         params_.hides);
  }
  return true;
}

}  // namespace placement_samplers
