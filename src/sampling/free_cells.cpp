#include "sampling/free_cells.hpp"

#include <algorithm>
#include <cmath>

namespace placement_samplers::detail {

void FreeCells::reset(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double side,
                      std::size_t maxCells) {
  for (auto& list : corners_) {
    list.clear();
  }
  const Eigen::Vector2d extent = hi - lo;
  side_ = std::max(side, std::sqrt(extent.x() * extent.y() / static_cast<double>(maxCells)));
  const int nx = std::max(1, static_cast<int>(std::ceil(extent.x() / side_)));
  const int ny = std::max(1, static_cast<int>(std::ceil(extent.y() / side_)));
  corners_[0].reserve(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      corners_[0].push_back(lo + Eigen::Vector2d(i * side_, j * side_));
    }
  }
}

Eigen::Vector2d FreeCells::draw(Engine& engine, int& level, std::size_t& index) const {
  double t = uniform01(engine) * area();
  int last = 0;
  for (level = 0; level < kLevels; ++level) {
    const std::vector<Eigen::Vector2d>& list = corners_[static_cast<std::size_t>(level)];
    if (list.empty()) {
      continue;
    }
    last = level;
    const double cell = side(level) * side(level);
    const double levelArea = cell * static_cast<double>(list.size());
    if (t < levelArea) {
      index = std::min(list.size() - 1, static_cast<std::size_t>(t / cell));
      break;
    }
    t -= levelArea;
  }
  if (level == kLevels) {  // rounding past the end: the last cell
    level = last;
    index = corners_[static_cast<std::size_t>(last)].size() - 1;
  }
  const double s = side(level);
  const Eigen::Vector2d& corner = corners_[static_cast<std::size_t>(level)][index];
  const double x = corner.x() + s * uniform01(engine);
  return Eigen::Vector2d(x, corner.y() + s * uniform01(engine));
}

double FreeCells::area() const {
  double sum = 0.0;
  for (int level = 0; level < kLevels; ++level) {
    sum += side(level) * side(level) *
           static_cast<double>(corners_[static_cast<std::size_t>(level)].size());
  }
  return sum;
}

std::size_t FreeCells::count() const {
  std::size_t n = 0;
  for (const auto& list : corners_) {
    n += list.size();
  }
  return n;
}

}  // namespace placement_samplers::detail
