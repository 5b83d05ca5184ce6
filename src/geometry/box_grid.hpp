#pragma once

// Axis-aligned boxes in x-y indexed by a uniform grid (private to the core): which may overlap
// a query box, without a scan of all of them.

#include <vector>

#include "geometry/surface_polygons.hpp"

namespace placement_samplers {
namespace surfaces {

class BoxGrid {
 public:
  /// Indexes @p boxes; empty or non-finite ones are never found.
  explicit BoxGrid(const std::vector<Box2>& boxes);

  /// Sets @p out to the indices of the boxes that may overlap or touch @p box (each once; a
  /// superset: callers test each).
  void query(const Box2& box, std::vector<int>& out);

 private:
  int column(double x) const;
  int row(double y) const;

  Box2 bounds_;
  int columns_ = 0, rows_ = 0;
  double cellWidth_ = 1.0, cellHeight_ = 1.0;
  std::vector<int> start_;  ///< items_ of cell c: [start_[c], start_[c + 1])
  std::vector<int> items_;
  std::vector<int> large_;  ///< boxes covering many cells: returned by every query
  std::vector<unsigned> stamp_;
  unsigned now_ = 0;
};

}  // namespace surfaces
}  // namespace placement_samplers
