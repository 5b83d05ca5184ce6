#pragma once
// What strategy free_space shares between its region and its surface loops
// (free_space_placement.cpp, surface_free_space.cpp). Private to the core.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace placement_samplers::detail {

/// Cells per side of the largest level-0 grid: 64 x 64.
constexpr std::size_t kMaxCells = 4096;

/// Rejection attempts over the whole box before the cells are built: an object that needs more
/// has little free room left, where the cells pay for themselves.
constexpr std::uint32_t kRejectionAttempts = 512;
/// Shape and disk tests between two readings of the clock while cells are pruned.
constexpr std::size_t kClockPeriod = std::size_t{1} << 18;

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

}  // namespace placement_samplers::detail
