// Strategy dense of the uniform sampler: the objects on a randomly shifted and turned
// hexagonal lattice, past the random-packing (jamming) limit of rejection and free_space.
#include <algorithm>
#include <cmath>

#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"
#include "sampling/sin_cos.hpp"

namespace placement_samplers {

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

  // The lattice: a shift along each basis vector, then a turn in [0, pi/3) (its symmetry).
  const double u = uniform01(engine);
  const double v = uniform01(engine);
  double s = 0.0;
  double c = 0.0;
  sinCos(uniform(engine, 0.0, M_PI / 3.0), s, c);
  const Eigen::Vector2d a = spacing * Eigen::Vector2d(c, s);
  const Eigen::Vector2d b =
      spacing * Eigen::Vector2d(0.5 * c - 0.8660254037844386 * s, 0.5 * s + 0.8660254037844386 * c);
  Eigen::Vector2d lo;
  Eigen::Vector2d hi;
  shapeBounds(region, lo, hi);
  const Eigen::Vector2d middle = 0.5 * (lo + hi);
  const double reach = 0.5 * (hi - lo).norm();
  const int k = static_cast<int>(std::ceil(2.0 * reach / spacing)) + 2;
  if (k > 2000) {
    return fail(context, entries_.front().object.get(), 0,
                "sampler " + quoteText(name()) +
                    ": strategy dense: the region is too large for a lattice of its objects");
  }
  std::vector<Eigen::Vector2d> sites;
  for (int i = -k; i <= k; ++i) {
    for (int j = -k; j <= k; ++j) {
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
