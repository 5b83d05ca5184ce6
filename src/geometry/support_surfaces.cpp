#include "placement_samplers/geometry/support_surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "geometry/surface_parts.hpp"

namespace placement_samplers {
namespace {

using namespace surfaces;

/// Footprints overlapping a surface by less than this only touch it [m^2].
constexpr double kOverlapArea = 1e-12;

/// Coplanar facets: merged into the same surfaces.
struct Cluster {
  std::vector<int> facets;
  Plane plane;  ///< its first facet's
  bool horizontal = true;
  double zFirst = 0.0;  ///< its first facet's highest point (horizontal clusters)
  double z = 0.0;       ///< its highest point
  Box2 box;
};

Box2 merged(const Box2& a, const Box2& b) {
  return Box2{std::min(a.minX, b.minX), std::min(a.minY, b.minY), std::max(a.maxX, b.maxX),
              std::max(a.maxY, b.maxY)};
}

/// Whether two planes are within kHeightTolerance of each other over @p box.
bool coplanar(const Plane& p, const Plane& q, const Box2& box) {
  for (double x : {box.minX, box.maxX}) {
    for (double y : {box.minY, box.maxY}) {
      if (!(std::abs(p.at(x, y) - q.at(x, y)) <= kHeightTolerance)) {
        return false;
      }
    }
  }
  return true;
}

std::vector<Cluster> clusterFacets(const std::vector<Facet>& facets) {
  std::vector<int> flat;
  std::vector<int> tilted;
  for (std::size_t i = 0; i < facets.size(); ++i) {
    (facets[i].horizontal ? flat : tilted).push_back(static_cast<int>(i));
  }
  std::stable_sort(flat.begin(), flat.end(),
                   [&](int a, int b) { return facets[a].zMax < facets[b].zMax; });
  std::vector<Cluster> clusters;
  const auto start = [&](int i) {
    Cluster c;
    c.facets.push_back(i);
    c.plane = facets[i].plane;
    c.horizontal = facets[i].horizontal;
    c.zFirst = c.z = facets[i].zMax;
    c.box = facets[i].box;
    clusters.push_back(std::move(c));
  };
  const auto join = [&](Cluster& c, int i) {
    c.facets.push_back(i);
    c.z = std::max(c.z, facets[i].zMax);
    c.box = merged(c.box, facets[i].box);
  };
  for (int i : flat) {
    if (!clusters.empty() && facets[i].zMax - clusters.back().zFirst <= kHeightTolerance) {
      join(clusters.back(), i);
    } else {
      start(i);
    }
  }
  const std::size_t firstTilted = clusters.size();
  for (int i : tilted) {
    std::size_t c = firstTilted;
    while (c < clusters.size() &&
           !coplanar(clusters[c].plane, facets[i].plane, merged(clusters[c].box, facets[i].box))) {
      ++c;
    }
    if (c < clusters.size()) {
      join(clusters[c], i);
    } else {
      start(i);
    }
  }
  return clusters;
}

const Eigen::Vector2d& lowestXVertex(const std::vector<Eigen::Vector2d>& ring) {
  return *std::min_element(ring.begin(), ring.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
}

class Extraction {
 public:
  Extraction(const SurfaceParts& parts, const SurfaceOptions& options)
      : parts_(parts),
        minArea_(options.minArea >= 0.0 ? options.minArea : 0.0),
        gap_(options.standingGap >= 0.0 ? std::min(options.standingGap, kFarAway) : 0.0) {}

  void add(const Cluster& cluster, SurfaceSearch& search) {
    Polygons polygons;
    std::vector<char> excluded(parts_.primitives.size(), 0);
    for (int i : cluster.facets) {
      const Facet& facet = parts_.facets[i];
      polygons.insert(polygons.end(), facet.polygons.begin(), facet.polygons.end());
      if (facet.element >= 0) {
        excluded[facet.element] = 1;  // the facet's own primitive lies below it
      }
    }
    polygons = unitePolygons(std::move(polygons));
    const double z = cluster.z;
    bool sectioned = false;
    Polygons sections;
    for (const Polygon2& polygon : polygons) {
      const double area = polygonArea(polygon);
      if (area < minArea_ && area <= search.largestDroppedArea) {
        continue;  // cuts only make it smaller: it changes nothing
      }
      if (!sectioned) {
        sections = standingSections(z);
        sectioned = true;
      }
      Polygons pieces = {polygon};
      const Polygons cuts = standing(polygon, z, excluded, sections);
      if (!cuts.empty()) {
        pieces = subtractPolygons(pieces, cuts);
      }
      for (Polygon2& piece : pieces) {
        SupportSurface surface;
        surface.area = polygonArea(piece);
        if (!(surface.area >= minArea_)) {
          search.largestDroppedArea = std::max(search.largestDroppedArea, surface.area);
          continue;
        }
        surface.z = z;
        surface.clearance = clearance(piece, z, excluded);
        surface.outer = std::move(piece.outer);
        surface.holes = std::move(piece.holes);
        search.surfaces.push_back(std::move(surface));
      }
    }
  }

 private:
  /// The meshes' cross-sections just above a surface at @p z: what of them stands on it.
  Polygons standingSections(double z) const {
    const double height = z + 0.5 * std::max(gap_, 2.0 * kHeightTolerance);
    Polygons sections;
    for (const WorldMesh& mesh : parts_.meshes) {
      if (mesh.zMax > height && mesh.zMin <= height) {
        const Polygons section = meshSection(mesh, height);
        sections.insert(sections.end(), section.begin(), section.end());
      }
    }
    return sections;
  }

  /// Whether geometry spanning [zMin, zMax] stands on a surface at @p z or passes through it.
  bool stands(double zMin, double zMax, double z) const {
    return zMax > z + kHeightTolerance && zMin < z + gap_;
  }
  /// Whether it is above a surface at @p z, beyond the standing gap.
  bool above(double zMin, double zMax, double z) const {
    return zMax > z + kHeightTolerance && zMin >= z + gap_;
  }

  /// The footprints to cut out of @p polygon.
  Polygons standing(const Polygon2& polygon, double z, const std::vector<char>& excluded,
                    const Polygons& sections) const {
    const Box2 box = ringBox(polygon.outer);
    Polygons cuts;
    for (std::size_t i = 0; i < parts_.primitives.size(); ++i) {
      const Obstacle& o = parts_.primitives[i];
      if (!excluded[i] && stands(o.zMin, o.zMax, z) && o.box.overlaps(box)) {
        cuts.push_back(Polygon2{o.footprint, {}});
      }
    }
    for (const TriangleObstacle& t : parts_.triangles) {
      if (stands(t.zMin, t.zMax, z) && t.box.overlaps(box)) {
        cuts.push_back(Polygon2{triangleFootprint(parts_.meshes[t.mesh], t.triangle), {}});
      }
    }
    for (const Polygon2& section : sections) {
      if (ringBox(section.outer).overlaps(box)) {
        cuts.push_back(section);
      }
    }
    return cuts;
  }

  /// The lowest geometry above @p piece whose footprint overlaps it, minus @p z.
  double clearance(const Polygon2& piece, double z, const std::vector<char>& excluded) const {
    const Box2 box = ringBox(piece.outer);
    // (lowest z, primitive index or -1 - triangle index), taken lowest first until one overlaps.
    std::vector<std::pair<double, long>> candidates;
    for (std::size_t i = 0; i < parts_.primitives.size(); ++i) {
      const Obstacle& o = parts_.primitives[i];
      if (!excluded[i] && above(o.zMin, o.zMax, z) && o.box.overlaps(box)) {
        candidates.emplace_back(o.zMin, static_cast<long>(i));
      }
    }
    for (std::size_t i = 0; i < parts_.triangles.size(); ++i) {
      const TriangleObstacle& t = parts_.triangles[i];
      if (above(t.zMin, t.zMax, z) && t.box.overlaps(box)) {
        candidates.emplace_back(t.zMin, -1 - static_cast<long>(i));
      }
    }
    const auto later = [](const auto& a, const auto& b) { return a > b; };
    std::make_heap(candidates.begin(), candidates.end(), later);
    while (!candidates.empty()) {
      std::pop_heap(candidates.begin(), candidates.end(), later);
      const auto [zMin, index] = candidates.back();
      candidates.pop_back();
      Polygon2 footprint;
      if (index >= 0) {
        footprint.outer = parts_.primitives[index].footprint;
      } else {
        const TriangleObstacle& t = parts_.triangles[-1 - index];
        footprint.outer = triangleFootprint(parts_.meshes[t.mesh], t.triangle);
      }
      if (overlapArea(piece, footprint) > kOverlapArea) {
        return zMin - z;
      }
    }
    return std::numeric_limits<double>::infinity();
  }

  const SurfaceParts& parts_;
  double minArea_;
  double gap_;
};

}  // namespace

SurfaceSearch findSupportSurfaces(const std::vector<Shape>& shapes, const Eigen::Isometry3d& pose,
                                  const SurfaceOptions& options) {
  // A tolerance beyond a right angle would take side faces; NaN takes none but exact +z.
  const double tolerance =
      options.normalTolerance >= 0.0 ? std::min(options.normalTolerance, 0.5 * M_PI) : 0.0;
  const double cosTolerance = std::cos(tolerance);
  SurfaceParts parts;
  for (const Shape& shape : shapes) {
    const Eigen::Isometry3d placed = pose * shape.pose;
    if (shape.type == ShapeType::Mesh) {
      if (shape.mesh) {
        addMesh(*shape.mesh, placed, cosTolerance, parts);
      }
    } else {
      addPrimitive(shape, placed, cosTolerance, parts);
    }
  }
  SurfaceSearch search;
  Extraction extraction(parts, options);
  for (const Cluster& cluster : clusterFacets(parts.facets)) {
    extraction.add(cluster, search);
  }
  std::vector<std::pair<Eigen::Vector2d, std::size_t>> keys;
  for (std::size_t i = 0; i < search.surfaces.size(); ++i) {
    keys.emplace_back(lowestXVertex(search.surfaces[i].outer), i);
  }
  std::stable_sort(keys.begin(), keys.end(), [&](const auto& a, const auto& b) {
    const double za = search.surfaces[a.second].z;
    const double zb = search.surfaces[b.second].z;
    if (za != zb) {
      return za < zb;
    }
    if (a.first.x() != b.first.x()) {
      return a.first.x() < b.first.x();
    }
    return a.first.y() < b.first.y();
  });
  std::vector<SupportSurface> sorted;
  sorted.reserve(keys.size());
  for (const auto& key : keys) {
    sorted.push_back(std::move(search.surfaces[key.second]));
  }
  search.surfaces.swap(sorted);
  return search;
}

SupportSurface movedSurface(const SupportSurface& surface, double yaw,
                            const Eigen::Vector3d& translation) {
  const Eigen::Rotation2Dd turn(yaw);
  const Eigen::Vector2d shift = translation.head<2>();
  SupportSurface moved = surface;
  moved.z = surface.z + translation.z();
  for (Eigen::Vector2d& p : moved.outer) {
    p = turn * p + shift;
  }
  for (auto& hole : moved.holes) {
    for (Eigen::Vector2d& p : hole) {
      p = turn * p + shift;
    }
  }
  return moved;
}

}  // namespace placement_samplers
