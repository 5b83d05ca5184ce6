#include "placement_samplers/collision/radius_checker.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "collision/radius_scan.hpp"
#include "collision/radius_test.hpp"

// RadiusChecker answers exactly as robosuite's scan of every entry in order: the same candidates
// collide and the lowest colliding index comes back, from a packed copy of what the test reads. Up
// to scanLimit entries it scans that copy (on the machines of docs/benchmarks.md the scan is
// the faster one below about a hundred entries). Beyond, it looks only near the candidate:
// entries go into uniform grids, one per power-of-two cell size, each into the grid whose
// cells are 4 to 8 times its horizontal radius, listed in every cell within half a cell of
// it, so that a candidate of the entries' size finds all it can touch in its own cell. A
// larger candidate visits every cell within reach, or scans the grid when that would be more
// cells than entries (a table-sized object); a grid of a few entries (a table, some plates)
// is scanned; entries with a non-finite position or a radius of 1e150 m or more are always
// scanned. The grids wrap around (cell (i, j) uses bucket (i mod 32, j mod 32)), so objects
// at negative coordinates, far outside the work area or hidden 20 m away need no bounds:
// the exact test sorts out what shares a bucket.
//
// The scan compares blocks of 8 (AVX-512) or 4 (AVX2) entries at once where the CPU has
// them, with the same operations as the scalar test, so the answers do not depend on the CPU.

namespace placement_samplers {

namespace {

constexpr int kWrapBits = 5;
/// Buckets per axis of a grid: cells further apart share buckets (32 cells of 12.5 cm for
/// 3 cm objects: 4 m before two cells share one).
constexpr std::int64_t kWrap = std::int64_t{1} << kWrapBits;
constexpr std::size_t kBuckets = static_cast<std::size_t>(kWrap * kWrap);
/// In grid mode, a grid with at most this many entries (a table, a few plates) is scanned:
/// cheaper than visiting its cells.
constexpr std::size_t kGridScanLimit = 8;
/// Cells are at least this many horizontal radii wide: half a cell then covers the reach of a
/// candidate as large as the entries (two radii), so it needs only its own cell.
constexpr double kCellPerRadius = 4.0;
/// Smallest cell exponent: 2^-20 m, about 1 um (zero radii need some cell).
constexpr int kMinExponent = -20;
/// Radii from here on go to the always-scanned list: their squared reach would overflow.
constexpr double kHugeRadius = 1e150;
/// Scans of at most this many entries are done inline, not by a vector kernel.
constexpr std::size_t kInlineScan = 4;
/// Cell indices are clamped to +/- 2^52.
constexpr double kCellLimit = 4503599627370496.0;

/// floor(v * inverse) clamped to +/- 2^52, without a branch to mispredict. Monotone in v, so a
/// range of coordinates maps onto a range of cells and clamping never loses a neighbour.
inline std::int64_t cellIndex(double v, double inverse) {
  const double t = std::min(kCellLimit, std::max(-kCellLimit, v * inverse));  // NaN -> -limit
  const auto i = static_cast<std::int64_t>(t);                                // rounds toward zero
  return i - static_cast<std::int64_t>(t < static_cast<double>(i));
}

inline std::size_t bucketOf(std::int64_t ix, std::int64_t iy) {
  return static_cast<std::size_t>(((ix & (kWrap - 1)) << kWrapBits) | (iy & (kWrap - 1)));
}

/// The smallest e >= kMinExponent with 2^e >= kCellPerRadius * r, for finite r >= 0, read off
/// the bits (std::frexp is a library call, and this runs for every placement).
int cellExponent(double r) {
  const double v = kCellPerRadius * r;
  if (!(v >= std::ldexp(1.0, kMinExponent))) {
    return kMinExponent;
  }
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof(bits));
  const int exponent = static_cast<int>((bits >> 52) & 0x7ff) - 1023;  // v = 1.m * 2^exponent
  const bool power = (bits & ((std::uint64_t{1} << 52) - 1)) == 0;
  return power ? exponent : exponent + 1;
}

using detail::RadiusProbe;

inline RadiusProbe probeOf(const Candidate& candidate) {
  return RadiusProbe{candidate.position.x(), candidate.position.y(), candidate.position.z(),
                     candidate.object->horizontalRadius, candidate.object->bottomOffset.z()};
}

}  // namespace

bool radiusOverlap(const PlacedEntry& other, const Candidate& candidate) {
  return detail::radiusOverlap(probeOf(candidate), other.position.x(), other.position.y(),
                               other.position.z(), other.object->horizontalRadius,
                               other.object->topOffset.z());
}

/// What the test reads of an entry, packed: position [m], horizontal radius [m] and top
/// offset z [m].
struct RadiusChecker::Item {
  double x;
  double y;
  double z;
  double radius;
  double top;

  /// robosuite's test (detail::radiusOverlap) on this entry.
  bool overlaps(const RadiusProbe& p) const {
    return detail::radiusOverlap(p, x, y, z, radius, top);
  }
};

/// One uniform grid: cells of 2^exponent m, wrapped onto kWrap x kWrap buckets. An entry is
/// listed in every cell its square of side one cell, centred on it, touches (2 x 2 cells
/// mostly), so a candidate within half a cell of it finds it in the candidate's own cell: one
/// list to walk, where the candidate's 2 x 2 neighbours would be four, with four ends to
/// mispredict. Lists keep ascending entry order, so their first hit is the lowest index.
struct RadiusChecker::Grid {
  /// An entry's copy in one bucket list.
  struct Node {
    Item item;
    std::int32_t index;  ///< entry index
    std::int32_t next;   ///< next node of the same bucket, -1 = none
    std::uint32_t bucket;
  };

  explicit Grid(int e)
      : exponent(e),
        half(std::ldexp(0.5, e)),
        inverse(std::ldexp(1.0, -e)),
        ownCellLimit(std::ldexp(0.5, e) * (1.0 - 1e-6)),
        coordinateLimit(std::ldexp(1e6, e)) {}

  int exponent;
  double half;     ///< half a cell [m]: how far an entry is listed around itself
  double inverse;  ///< 1 / cell size [1/m]
  /// Queries reaching at most this far [m] need only the candidate's cell. Slightly below
  /// half a cell, and only within coordinateLimit [m] of the origin, so that rounding in
  /// entry +/- half cannot lose a neighbour.
  double ownCellLimit;
  double coordinateLimit;
  double maxRadius = 0.0;             ///< largest |horizontal radius| of the members [m]
  std::vector<std::int32_t> members;  ///< entry indices, ascending
  bool bucketed = false;              ///< members are in the buckets
  std::vector<Node> nodes;            ///< the bucket lists' nodes
  std::vector<std::int32_t> head;     ///< first node of each bucket, -1 = empty
  std::vector<std::int32_t> tail;     ///< last node of each bucket, -1 = empty

  /// Lowest colliding index among the members below @p best, or @p best.
  std::int32_t scan(const std::vector<Item>& items, const RadiusProbe& p, std::int32_t best) const {
    for (const std::int32_t i : members) {
      if (i >= best) {
        break;
      }
      if (items[static_cast<std::size_t>(i)].overlaps(p)) {
        return i;
      }
    }
    return best;
  }

  void insert(const std::vector<Item>& items, std::int32_t index) {
    const Item& item = items[static_cast<std::size_t>(index)];
    const std::int64_t x0 = cellIndex(item.x - half, inverse);
    const std::int64_t x1 = cellIndex(item.x + half, inverse);
    const std::int64_t y0 = cellIndex(item.y - half, inverse);
    const std::int64_t y1 = cellIndex(item.y + half, inverse);
    // 2 x 2 cells, 3 when rounding straddles a boundary, and at most the kWrap buckets.
    for (std::int64_t ix = x0; ix <= x1 && ix < x0 + kWrap; ++ix) {
      for (std::int64_t iy = y0; iy <= y1 && iy < y0 + kWrap; ++iy) {
        const std::size_t b = bucketOf(ix, iy);
        const auto node = static_cast<std::int32_t>(nodes.size());
        nodes.push_back(Node{item, index, -1, static_cast<std::uint32_t>(b)});
        if (tail[b] < 0) {
          head[b] = node;
        } else {
          nodes[static_cast<std::size_t>(tail[b])].next = node;
        }
        tail[b] = node;
      }
    }
  }

  void add(const std::vector<Item>& items, std::int32_t index, double radius) {
    maxRadius = std::max(maxRadius, radius);
    members.push_back(index);
    if (bucketed) {
      insert(items, index);
    } else if (members.size() > kGridScanLimit) {
      if (head.empty()) {
        head.assign(kBuckets, -1);
        tail.assign(kBuckets, -1);
      }
      for (const std::int32_t m : members) {
        insert(items, m);
      }
      bucketed = true;
    }
  }

  /// Forgets the members, resetting only the buckets they used.
  void clear() {
    for (const Node& node : nodes) {
      head[node.bucket] = -1;
      tail[node.bucket] = -1;
    }
    nodes.clear();
    bucketed = false;
    members.clear();
    maxRadius = 0.0;
  }

  /// Lowest colliding index below @p best, or @p best.
  std::int32_t query(const std::vector<Item>& items, const RadiusProbe& p,
                     std::int32_t best) const {
    if (!bucketed) {
      return scan(items, p, best);
    }
    const double reach = std::abs(p.radius) + maxRadius;
    // The test accepts up to a distance of reach plus rounding; the margin covers that and the
    // rounding of x +/- far with room to spare (1e-12 relative, 1e-100 m where dx * dx would
    // underflow to zero).
    const double far = reach * (1.0 + 1e-12) + 1e-12 * (std::abs(p.x) + std::abs(p.y)) + 1e-100;
    if (far <= ownCellLimit && std::abs(p.x) <= coordinateLimit &&
        std::abs(p.y) <= coordinateLimit) {
      // The usual case: everything within reach is listed in the candidate's own cell.
      const std::size_t b = bucketOf(cellIndex(p.x, inverse), cellIndex(p.y, inverse));
      for (std::int32_t n = head[b]; n >= 0;) {
        const Node& node = nodes[static_cast<std::size_t>(n)];
        if (node.index >= best) {
          break;
        }
        if (node.item.overlaps(p)) {
          return node.index;
        }
        n = node.next;
      }
      return best;
    }
    // A larger candidate: every cell within reach. Each entry is listed in its own cell (and
    // maybe a few more: seeing it twice does no harm).
    const std::int64_t x0 = cellIndex(p.x - far, inverse);
    const std::int64_t x1 = cellIndex(p.x + far, inverse);
    const std::int64_t y0 = cellIndex(p.y - far, inverse);
    const std::int64_t y1 = cellIndex(p.y + far, inverse);
    const double cells =
        (static_cast<double>(x1 - x0) + 1.0) * (static_cast<double>(y1 - y0) + 1.0);
    if (cells > static_cast<double>(members.size())) {
      return scan(items, p, best);  // a candidate much larger than the members (a table)
    }
    const std::int64_t nx = std::min(x1 - x0 + 1, kWrap);
    const std::int64_t ny = std::min(y1 - y0 + 1, kWrap);
    for (std::int64_t ix = x0; ix < x0 + nx; ++ix) {
      for (std::int64_t iy = y0; iy < y0 + ny; ++iy) {
        for (std::int32_t n = head[bucketOf(ix, iy)]; n >= 0;) {
          const Node& node = nodes[static_cast<std::size_t>(n)];
          if (node.index >= best) {
            break;
          }
          if (node.item.overlaps(p)) {
            best = node.index;
            break;
          }
          n = node.next;
        }
      }
    }
    return best;
  }
};

RadiusChecker::RadiusChecker(std::size_t scanLimit)
    : scanLimit_(scanLimit),
      columns_(std::make_unique<detail::RadiusColumns>()),
      firstOverlap_(detail::scanKernel(detail::bestScanKernel())) {}
RadiusChecker::~RadiusChecker() = default;

void RadiusChecker::clear() {
  for (Grid* grid : active_) {
    grid->clear();
  }
  active_.clear();
  lastGrid_ = nullptr;
  unbounded_.clear();
  items_.clear();
  columns_->clear();
  gridMode_ = false;
}

void RadiusChecker::added(const std::vector<PlacedEntry>& entries, std::size_t index) {
  if (index != columns_->size()) {
    // Not announced in order (a caller other than SampleContext): index everything again.
    clear();
    for (std::size_t i = 0; i < index; ++i) {
      added(entries, i);
    }
  }
  const PlacedEntry& entry = entries[index];
  columns_->push(entry.position.x(), entry.position.y(), entry.position.z(),
                 entry.object->horizontalRadius, entry.object->topOffset.z());
  if (gridMode_) {
    items_.push_back(itemOf(index));
    indexEntry(index);
  } else if (columns_->size() > scanLimit_) {
    // The grids read items: made from the columns when the scene first needs them.
    gridMode_ = true;
    for (std::size_t i = 0; i < columns_->size(); ++i) {
      items_.push_back(itemOf(i));
      indexEntry(i);
    }
  }
}

RadiusChecker::Item RadiusChecker::itemOf(std::size_t index) const {
  const detail::RadiusColumns& c = *columns_;
  return Item{c.x()[index], c.y()[index], c.z()[index], c.radius()[index], c.top()[index]};
}

void RadiusChecker::indexEntry(std::size_t index) {
  const Item& item = items_[index];
  const auto i = static_cast<std::int32_t>(index);
  const double r = std::abs(item.radius);
  if (!std::isfinite(item.x) || !std::isfinite(item.y) || !(r < kHugeRadius)) {
    unbounded_.push_back(i);
    return;
  }
  const int exponent = cellExponent(r);
  Grid* grid = lastGrid_;  // placements mostly come in runs of one size
  if (grid == nullptr || grid->exponent != exponent) {
    grid = nullptr;
    for (Grid* g : active_) {
      if (g->exponent == exponent) {
        grid = g;
        break;
      }
    }
    if (grid == nullptr) {
      for (const std::unique_ptr<Grid>& g : grids_) {
        if (g->exponent == exponent) {
          grid = g.get();
          break;
        }
      }
      if (grid == nullptr) {
        grids_.push_back(std::make_unique<Grid>(exponent));
        grid = grids_.back().get();
      }
      active_.push_back(grid);
    }
    lastGrid_ = grid;
  }
  grid->add(items_, i, r);
}

std::ptrdiff_t RadiusChecker::firstCollision(const std::vector<PlacedEntry>& entries,
                                             const Candidate& candidate) {
  const std::size_t n = columns_->size();
  if (candidate.support >= 0) {
    // Standing on a surface of its support: robosuite's scan over the others.
    for (std::size_t i = 0; i < entries.size(); ++i) {
      if (static_cast<std::ptrdiff_t>(i) != candidate.support &&
          radiusOverlap(entries[i], candidate)) {
        return static_cast<std::ptrdiff_t>(i);
      }
    }
    return kNone;
  }
  if (entries.size() != n) {
    // Entries the checker was not told about: robosuite's scan over them.
    for (std::size_t i = 0; i < entries.size(); ++i) {
      if (radiusOverlap(entries[i], candidate)) {
        return static_cast<std::ptrdiff_t>(i);
      }
    }
    return kNone;
  }
  const RadiusProbe p = probeOf(candidate);
  if (!gridMode_ || !std::isfinite(p.x) || !std::isfinite(p.y) ||
      !(std::abs(p.radius) < kHugeRadius)) {
    // Few entries, or a candidate no range of cells can bound: the scan, in index order.
    // A handful is cheaper here than setting up a vector kernel (Stack: one entry).
    const std::size_t i =
        n <= kInlineScan ? detail::firstOverlapInline(*columns_, p) : firstOverlap_(*columns_, p);
    return i < n ? static_cast<std::ptrdiff_t>(i) : kNone;
  }
  const auto none = static_cast<std::int32_t>(n);
  std::int32_t best = none;
  for (const std::int32_t i : unbounded_) {
    if (items_[static_cast<std::size_t>(i)].overlaps(p)) {
      best = i;
      break;
    }
  }
  for (const Grid* grid : active_) {
    best = grid->query(items_, p, best);
  }
  return best < none ? static_cast<std::ptrdiff_t>(best) : kNone;
}

}  // namespace placement_samplers
