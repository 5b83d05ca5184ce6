#include "sampling/free_position_check.hpp"

#include <cmath>

#include "collision/radius_test.hpp"

namespace placement_samplers::detail {
namespace {

struct Disk {
  Eigen::Vector2d centre;
  double reach;  // the entry's radius plus the object's [m]
};

class Prover {
 public:
  explicit Prover(std::vector<Disk> disks) : disks_(std::move(disks)) {}

  /// True when every point of the box is within some disk's reach.
  bool covered(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, int depth) {
    if (++cells_ > kMaxCells) {
      exhausted_ = true;
      return false;
    }
    const Eigen::Vector2d centre = 0.5 * (lo + hi);
    const double halfDiagonal = 0.5 * (hi - lo).norm();
    for (const Disk& d : disks_) {
      // A margin of 1e-9 of the reach keeps rounding on the side of "maybe free".
      if ((centre - d.centre).norm() + halfDiagonal <= d.reach * (1.0 - 1e-9)) {
        return true;
      }
    }
    if (depth == 0) {
      return false;
    }
    const Eigen::Vector2d mid = centre;
    return covered(lo, mid, depth - 1) &&
           covered({mid.x(), lo.y()}, {hi.x(), mid.y()}, depth - 1) &&
           covered({lo.x(), mid.y()}, {mid.x(), hi.y()}, depth - 1) && covered(mid, hi, depth - 1);
  }
  bool exhausted() const { return exhausted_; }

 private:
  static constexpr long kMaxCells = 200000;
  std::vector<Disk> disks_;
  long cells_ = 0;
  bool exhausted_ = false;
};

}  // namespace

bool noFreePosition(const std::vector<PlacedEntry>& entries, const ObjectModel& object, double z,
                    const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  std::vector<Disk> disks;
  for (const PlacedEntry& e : entries) {
    // Only entries at an overlapping height block the object.
    if (radiusHeightsOverlap(z, object.bottomOffset.z(), e.position.z(), e.object->topOffset.z())) {
      disks.push_back(
          Disk{e.position.head<2>(), e.object->horizontalRadius + object.horizontalRadius});
    }
  }
  if (disks.empty() || !lo.allFinite() || !hi.allFinite()) {
    return false;
  }
  Prover prover(std::move(disks));
  return prover.covered(lo, hi, 12) && !prover.exhausted();
}

}  // namespace placement_samplers::detail
