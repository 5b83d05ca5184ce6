#pragma once
// The cells of strategy free_space (free_space_placement.cpp). Private to the core.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

#include "placement_samplers/sampling/random.hpp"

namespace placement_samplers::detail {

/// Square cells that may still hold a free position, on levels: level 0 is a grid, a cell of
/// level k + 1 a quarter of one of level k. Draws pick a cell with probability proportional to
/// its area and a uniform point in it, so a point drawn is uniform over the cells' union; cells
/// are only ever dropped when no point of them is free, so a draw that passes the test is
/// uniform over the free positions, as robosuite's rejection with unlimited attempts.
class FreeCells {
 public:
  static constexpr int kLevels = 10;  ///< a level-0 cell splits down to 1/512 of its side

  /// A grid over [lo, hi] of cells of side about @p side (at most @p maxCells of them) [m].
  void reset(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double side,
             std::size_t maxCells);

  /// Drops every cell for which @p covered(centre, halfDiagonal) is true.
  template <typename Covered>
  void dropIf(const Covered& covered) {
    for (int level = 0; level < kLevels; ++level) {
      std::vector<Eigen::Vector2d>& list = corners_[static_cast<std::size_t>(level)];
      const double h = halfDiagonal(level);
      const Eigen::Vector2d half = Eigen::Vector2d::Constant(0.5 * side(level));
      std::size_t kept = 0;
      for (std::size_t i = 0; i < list.size(); ++i) {
        if (!covered(Eigen::Vector2d(list[i] + half), h)) {
          list[kept++] = list[i];
        }
      }
      list.resize(kept);
    }
  }

  bool empty() const { return area() <= 0.0; }

  /// One draw: U(0, 1) picks a cell by area (levels from the coarsest, cells in their order),
  /// then U(0, side) for x and for y in it. @return the point [m]; @p level, @p index name the
  /// cell for refine()
  Eigen::Vector2d draw(Engine& engine, int& level, std::size_t& index) const;

  /// After a draw in cell (@p level, @p index) failed: drops the cell when @p covered says all
  /// of it is blocked, else splits it into its four quarters (those not covered) unless it is
  /// on the finest level.
  template <typename Covered>
  void refine(int level, std::size_t index, const Covered& covered) {
    std::vector<Eigen::Vector2d>& list = corners_[static_cast<std::size_t>(level)];
    const Eigen::Vector2d corner = list[index];
    const double s = side(level);
    if (!covered(Eigen::Vector2d(corner + Eigen::Vector2d::Constant(0.5 * s)),
                 halfDiagonal(level))) {
      if (level + 1 == kLevels) {
        return;
      }
      const double q = 0.5 * s;
      std::vector<Eigen::Vector2d>& finer = corners_[static_cast<std::size_t>(level + 1)];
      for (const auto& [i, j] :
           std::array<std::pair<int, int>, 4>{{{0, 0}, {1, 0}, {0, 1}, {1, 1}}}) {
        const Eigen::Vector2d c = corner + Eigen::Vector2d(i * q, j * q);
        if (!covered(Eigen::Vector2d(c + Eigen::Vector2d::Constant(0.5 * q)),
                     halfDiagonal(level + 1))) {
          finer.push_back(c);
        }
      }
    }
    list[index] = list.back();  // the order changes, deterministically
    list.pop_back();
  }

  /// The cells' total area [m^2].
  double area() const;
  std::size_t count() const;

 private:
  double side(int level) const { return side_ / static_cast<double>(1 << level); }
  double halfDiagonal(int level) const { return 0.5 * M_SQRT2 * side(level); }

  double side_ = 0.0;
  std::array<std::vector<Eigen::Vector2d>, kLevels> corners_;  // lower-left corners per level
};

}  // namespace placement_samplers::detail
