// The cross-section of a mesh at a height: what of it stands on a surface just below.

#include <algorithm>
#include <cstdint>

#include "geometry/surface_parts.hpp"

namespace placement_samplers {
namespace surfaces {
namespace {

/// A piece of the section in one triangle, the inside on its left; its ends are named by the
/// triangle sides they lie on, which the neighbours share.
struct Segment {
  std::uint64_t from, to;
  Point2 start;
  bool operator<(const Segment& o) const { return from < o.from; }
};

std::uint64_t sideKey(int u, int v) {
  return (static_cast<std::uint64_t>(std::min(u, v)) << 32) |
         static_cast<std::uint32_t>(std::max(u, v));
}

/// Where side (u, v) crosses @p height, computed from the lower index so that both triangles of
/// the side get the same point.
Point2 crossing(const WorldMesh& mesh, int u, int v, double height) {
  const Eigen::Vector3d& a = mesh.vertices[std::min(u, v)];
  const Eigen::Vector3d& b = mesh.vertices[std::max(u, v)];
  const double t = (height - a.z()) / (b.z() - a.z());
  return (a + t * (b - a)).head<2>();
}

}  // namespace

Polygons meshSection(const WorldMesh& mesh, double height) {
  std::vector<Segment> segments;
  for (const std::array<int, 3>& t : mesh.triangles) {
    bool above[3];
    int count = 0;
    for (int k = 0; k < 3; ++k) {
      above[k] = mesh.vertices[t[k]].z() > height;
      count += above[k] ? 1 : 0;
    }
    if (count == 0 || count == 3) {
      continue;
    }
    // Seen from above, an outward-facing triangle's section runs from the side where its
    // boundary goes down through the height to the side where it goes up: inside on the left.
    Segment segment{0, 0, Point2::Zero()};
    for (int k = 0; k < 3; ++k) {
      const int u = t[k];
      const int v = t[(k + 1) % 3];
      if (above[k] && !above[(k + 1) % 3]) {
        segment.from = sideKey(u, v);
        segment.start = crossing(mesh, u, v, height);
      } else if (!above[k] && above[(k + 1) % 3]) {
        segment.to = sideKey(u, v);
      }
    }
    segments.push_back(segment);
  }
  std::sort(segments.begin(), segments.end());
  std::vector<char> used(segments.size(), 0);
  std::vector<Ring> loops;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    if (used[i]) {
      continue;
    }
    Ring ring;
    std::size_t current = i;
    bool closed = false;
    for (std::size_t steps = 0; steps < segments.size(); ++steps) {
      used[current] = 1;
      ring.push_back(segments[current].start);
      if (segments[current].to == segments[i].from) {
        closed = true;
        break;
      }
      auto it = std::lower_bound(segments.begin(), segments.end(),
                                 Segment{segments[current].to, 0, Point2::Zero()});
      while (it != segments.end() && it->from == segments[current].to &&
             used[it - segments.begin()]) {
        ++it;
      }
      if (it == segments.end() || it->from != segments[current].to) {
        break;  // an open mesh: the loop does not close
      }
      current = it - segments.begin();
    }
    if (closed) {
      loops.push_back(std::move(ring));
    }
  }
  bool valid = true;
  std::vector<Ring> copies = loops;
  Polygons section = polygonsFromLoops(std::move(copies), valid);
  if (!valid) {
    section.clear();
    for (Ring& loop : loops) {
      Ring hull = convexHull(std::move(loop));
      if (!hull.empty()) {
        section.push_back(Polygon2{std::move(hull), {}});
      }
    }
  }
  return section;
}

}  // namespace surfaces
}  // namespace placement_samplers
