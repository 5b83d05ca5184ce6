#include "geometry/box_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace placement_samplers {
namespace surfaces {
namespace {

/// Cells per axis at most, and cells a box may cover before it is listed apart.
constexpr int kMaxCells = 1024;
constexpr int kMaxCellsPerBox = 64;

bool indexable(const Box2& b) {
  return std::isfinite(b.minX) && std::isfinite(b.minY) && std::isfinite(b.maxX) &&
         std::isfinite(b.maxY) && b.minX <= b.maxX && b.minY <= b.maxY;
}

}  // namespace

BoxGrid::BoxGrid(const std::vector<Box2>& boxes) : stamp_(boxes.size(), 0) {
  std::vector<int> valid;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    if (indexable(boxes[i])) {
      valid.push_back(static_cast<int>(i));
    }
  }
  if (valid.empty()) {
    return;
  }
  bounds_ = boxes[valid.front()];
  for (int i : valid) {
    bounds_.minX = std::min(bounds_.minX, boxes[i].minX);
    bounds_.minY = std::min(bounds_.minY, boxes[i].minY);
    bounds_.maxX = std::max(bounds_.maxX, boxes[i].maxX);
    bounds_.maxY = std::max(bounds_.maxY, boxes[i].maxY);
  }
  const int side = std::clamp(
      static_cast<int>(std::ceil(std::sqrt(static_cast<double>(valid.size())))), 1, kMaxCells);
  const double width = bounds_.maxX - bounds_.minX;
  const double height = bounds_.maxY - bounds_.minY;
  columns_ = width > 0.0 ? side : 1;
  rows_ = height > 0.0 ? side : 1;
  cellWidth_ = width > 0.0 ? width / columns_ : 1.0;
  cellHeight_ = height > 0.0 ? height / rows_ : 1.0;
  // Two passes: count per cell, then fill (a counting sort).
  start_.assign(static_cast<std::size_t>(columns_) * rows_ + 1, 0);
  std::vector<int> small;
  for (int i : valid) {
    const Box2& b = boxes[i];
    const int cells = (column(b.maxX) - column(b.minX) + 1) * (row(b.maxY) - row(b.minY) + 1);
    if (cells > kMaxCellsPerBox) {
      large_.push_back(i);
      continue;
    }
    small.push_back(i);
    for (int y = row(b.minY); y <= row(b.maxY); ++y) {
      for (int x = column(b.minX); x <= column(b.maxX); ++x) {
        ++start_[y * columns_ + x + 1];
      }
    }
  }
  std::partial_sum(start_.begin(), start_.end(), start_.begin());
  items_.resize(start_.back());
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (int i : small) {
    const Box2& b = boxes[i];
    for (int y = row(b.minY); y <= row(b.maxY); ++y) {
      for (int x = column(b.minX); x <= column(b.maxX); ++x) {
        items_[fill[y * columns_ + x]++] = i;
      }
    }
  }
}

int BoxGrid::column(double x) const {
  const double c = std::floor((x - bounds_.minX) / cellWidth_);
  return c <= 0.0 ? 0 : c >= columns_ - 1 ? columns_ - 1 : static_cast<int>(c);
}

int BoxGrid::row(double y) const {
  const double r = std::floor((y - bounds_.minY) / cellHeight_);
  return r <= 0.0 ? 0 : r >= rows_ - 1 ? rows_ - 1 : static_cast<int>(r);
}

void BoxGrid::query(const Box2& box, std::vector<int>& out) {
  out = large_;
  if (columns_ == 0 || !(box.maxX >= bounds_.minX && box.minX <= bounds_.maxX &&
                         box.maxY >= bounds_.minY && box.minY <= bounds_.maxY)) {
    return;
  }
  if (++now_ == 0) {  // wrapped: forget every stamp
    std::fill(stamp_.begin(), stamp_.end(), 0);
    now_ = 1;
  }
  for (int y = row(box.minY); y <= row(box.maxY); ++y) {
    for (int x = column(box.minX); x <= column(box.maxX); ++x) {
      const int cell = y * columns_ + x;
      for (int k = start_[cell]; k < start_[cell + 1]; ++k) {
        if (stamp_[items_[k]] != now_) {
          stamp_[items_[k]] = now_;
          out.push_back(items_[k]);
        }
      }
    }
  }
}

}  // namespace surfaces
}  // namespace placement_samplers
