// From clusters of coplanar facets to support surfaces: the union of each cluster's polygons,
// standing geometry cut out, clearance from the geometry above, small surfaces dropped.

#include <algorithm>
#include <iterator>
#include <memory>
#include <optional>

#include "geometry/box_grid.hpp"
#include "geometry/surface_parts.hpp"

namespace placement_samplers {
namespace surfaces {
namespace {

/// Footprints overlapping a surface by less than this only touch it [m^2].
constexpr double kOverlapArea = 1e-12;
/// Queries answered by a scan of all obstacles before they are indexed in a grid.
constexpr int kScannedQueries = 8;
/// Mesh triangles visited by cross-sections, all clusters together. Beyond it (thousands of
/// surfaces at different heights over a large mesh) a mesh reaching above a surface is cut out
/// as its whole convex footprint: conservative, and bounded in time.
constexpr std::size_t kSectionBudget = 20000000;

class Extraction {
 public:
  Extraction(const SurfaceParts& parts, const std::vector<Cluster>& clusters,
             const SurfaceOptions& options)
      : parts_(parts),
        clusters_(clusters),
        minArea_(options.minArea >= 0.0 ? options.minArea : 0.0),
        gap_(options.standingGap >= 0.0 ? std::min(options.standingGap, kFarAway) : 0.0),
        sections_(clusters.size()),
        hulls_(parts.meshes.size()),
        owner_(parts.primitives.size(), -1) {}

  SurfaceSearch run() {
    struct Item {
      int cluster;
      double area;
      Polygon2 polygon;
    };
    std::vector<Item> items;
    std::vector<int> remaining(clusters_.size(), 0);
    for (std::size_t c = 0; c < clusters_.size(); ++c) {
      for (Polygon2& polygon : clusterPolygons(clusters_[c])) {
        const double area = polygonArea(polygon);
        items.push_back(Item{static_cast<int>(c), area, std::move(polygon)});
        ++remaining[c];
      }
    }
    // Largest first: the section budget goes to them, and what cannot change
    // largestDroppedArea is skipped.
    std::stable_sort(items.begin(), items.end(),
                     [](const Item& a, const Item& b) { return a.area > b.area; });
    SurfaceSearch search;
    for (Item& item : items) {
      if (!(item.area < minArea_ && item.area <= search.largestDroppedArea)) {
        add(item.cluster, std::move(item.polygon), search);
      }
      if (--remaining[item.cluster] == 0) {
        sections_[item.cluster].reset();
      }
    }
    return search;
  }

 private:
  /// The union of @p cluster's polygons: of each group of facets whose boxes touch (no
  /// Boolean operation for a facet alone, nor for facets apart).
  Polygons clusterPolygons(const Cluster& cluster) const {
    std::vector<Box2> boxes;
    for (int i : cluster.facets) {
      boxes.push_back(parts_.facets[i].box);
    }
    Polygons united;
    // Facets joined when they overlap or share boundary: convex ones tested exactly (the
    // triangles of a rough mesh touch at corners), others taken as joined.
    std::vector<char> convex(cluster.facets.size(), 0);
    for (std::size_t k = 0; k < cluster.facets.size(); ++k) {
      const Polygons& p = parts_.facets[cluster.facets[k]].polygons;
      convex[k] = p.size() == 1 && p.front().holes.empty() && isConvex(p.front().outer);
    }
    const auto joined = [&](int a, int b) {
      return !(convex[a] && convex[b]) ||
             convexJoined(parts_.facets[cluster.facets[a]].polygons.front().outer,
                          parts_.facets[cluster.facets[b]].polygons.front().outer);
    };
    for (const std::vector<int>& group : touchingGroups(boxes, joined)) {
      Polygons polygons;
      for (int k : group) {
        const Facet& facet = parts_.facets[cluster.facets[k]];
        polygons.insert(polygons.end(), facet.polygons.begin(), facet.polygons.end());
      }
      if (polygons.size() > 1) {
        polygons = unitePolygons(std::move(polygons));
      }
      std::move(polygons.begin(), polygons.end(), std::back_inserter(united));
    }
    return united;
  }

  void add(int c, Polygon2 polygon, SurfaceSearch& search) {
    for (int i : clusters_[c].facets) {
      if (parts_.facets[i].element >= 0) {
        owner_[parts_.facets[i].element] = c;  // the facet's own primitive lies below it
      }
    }
    const double z = clusters_[c].z;
    Polygons pieces = {std::move(polygon)};
    const Polygons cuts = standing(pieces.front(), c);
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
      surface.clearance = clearance(piece, c);
      surface.outer = std::move(piece.outer);
      surface.holes = std::move(piece.holes);
      search.surfaces.push_back(std::move(surface));
    }
  }

  /// Indices of the obstacles (primitives, then mesh triangles) whose boxes may overlap @p box.
  void nearby(const Box2& box, std::vector<int>& out) {
    const std::size_t primitives = parts_.primitives.size();
    const std::size_t count = primitives + parts_.triangles.size();
    if (!grid_ && ++queries_ > kScannedQueries && count > 256) {
      std::vector<Box2> boxes;
      boxes.reserve(count);
      for (const Obstacle& o : parts_.primitives) {
        boxes.push_back(o.box);
      }
      for (const TriangleObstacle& t : parts_.triangles) {
        boxes.push_back(t.box);
      }
      grid_ = std::make_unique<BoxGrid>(boxes);
    }
    if (grid_) {
      grid_->query(box, out);
      std::sort(out.begin(), out.end());  // the order of a scan: results do not depend on it
      return;
    }
    out.clear();
    for (std::size_t i = 0; i < count; ++i) {
      const Box2& b =
          i < primitives ? parts_.primitives[i].box : parts_.triangles[i - primitives].box;
      if (b.overlaps(box)) {
        out.push_back(static_cast<int>(i));
      }
    }
  }

  /// Obstacle @p i's height extent and footprint.
  void obstacle(int i, double& zMin, double& zMax) const {
    const std::size_t primitives = parts_.primitives.size();
    if (static_cast<std::size_t>(i) < primitives) {
      zMin = parts_.primitives[i].zMin;
      zMax = parts_.primitives[i].zMax;
    } else {
      zMin = parts_.triangles[i - primitives].zMin;
      zMax = parts_.triangles[i - primitives].zMax;
    }
  }
  Ring footprint(int i) const {
    const std::size_t primitives = parts_.primitives.size();
    if (static_cast<std::size_t>(i) < primitives) {
      return parts_.primitives[i].footprint;
    }
    const TriangleObstacle& t = parts_.triangles[i - primitives];
    return triangleFootprint(parts_.meshes[t.mesh], t.triangle);
  }
  bool own(int i, int c) const {
    return static_cast<std::size_t>(i) < owner_.size() && owner_[i] == c;
  }

  /// The meshes' cross-sections just above cluster @p c: what of them stands on it.
  const Polygons& sections(int c) {
    std::optional<Polygons>& cached = sections_[c];
    if (cached) {
      return *cached;
    }
    cached.emplace();
    const double height = clusters_[c].z + 0.5 * std::max(gap_, 2.0 * kHeightTolerance);
    for (std::size_t m = 0; m < parts_.meshes.size(); ++m) {
      const WorldMesh& mesh = parts_.meshes[m];
      if (!(mesh.zMax > height && mesh.zMin <= height)) {
        continue;
      }
      Polygons section;
      if (sectionWork_ + mesh.triangles.size() <= kSectionBudget) {
        sectionWork_ += mesh.triangles.size();
        section = meshSection(mesh, height);
      } else {
        if (!hulls_[m]) {
          std::vector<Point2> points;
          for (const Eigen::Vector3d& p : mesh.vertices) {
            points.push_back(p.head<2>());
          }
          hulls_[m] = convexHull(std::move(points));
        }
        section = {Polygon2{*hulls_[m], {}}};
      }
      cached->insert(cached->end(), section.begin(), section.end());
    }
    return *cached;
  }

  /// The footprints to cut out of @p polygon of cluster @p c: geometry that reaches above it
  /// and begins less than the standing gap above it.
  Polygons standing(const Polygon2& polygon, int c) {
    const double z = clusters_[c].z;
    const Box2 box = ringBox(polygon.outer);
    const bool convex = isConvex(polygon.outer);
    Polygons cuts;
    nearby(box, found_);
    for (int i : found_) {
      double zMin, zMax;
      obstacle(i, zMin, zMax);
      if (!own(i, c) && zMax > z + kHeightTolerance && zMin < z + gap_) {
        Ring cut = footprint(i);
        // A wall beside a floor only touches it: no Boolean operation for that.
        if (!(convex && convexApart(polygon.outer, cut))) {
          cuts.push_back(Polygon2{std::move(cut), {}});
        }
      }
    }
    for (const Polygon2& section : sections(c)) {
      if (ringBox(section.outer).overlaps(box)) {
        cuts.push_back(section);
      }
    }
    return cuts;
  }

  /// The lowest geometry above @p piece of cluster @p c whose footprint overlaps it, minus the
  /// cluster's height; infinity when there is none.
  double clearance(const Polygon2& piece, int c) {
    const double z = clusters_[c].z;
    const bool convex = isConvex(piece.outer);
    nearby(ringBox(piece.outer), found_);
    std::vector<std::pair<double, int>> above;  // lowest z, obstacle
    for (int i : found_) {
      double zMin, zMax;
      obstacle(i, zMin, zMax);
      if (!own(i, c) && zMax > z + kHeightTolerance && zMin >= z + gap_) {
        above.emplace_back(zMin, i);
      }
    }
    // Lowest first, until one overlaps: a heap, as most are never looked at.
    const auto later = [](const auto& a, const auto& b) { return a > b; };
    std::make_heap(above.begin(), above.end(), later);
    while (!above.empty()) {
      std::pop_heap(above.begin(), above.end(), later);
      const auto [zMin, i] = above.back();
      above.pop_back();
      Ring overhead = footprint(i);
      if (!(convex && convexApart(piece.outer, overhead)) &&
          overlapArea(piece, Polygon2{std::move(overhead), {}}) > kOverlapArea) {
        return zMin - z;
      }
    }
    return std::numeric_limits<double>::infinity();
  }

  const SurfaceParts& parts_;
  const std::vector<Cluster>& clusters_;
  double minArea_;
  double gap_;
  std::vector<std::optional<Polygons>> sections_;  ///< per cluster, while it has items left
  std::vector<std::optional<Ring>> hulls_;         ///< per mesh, once the budget is spent
  std::size_t sectionWork_ = 0;
  std::vector<int> owner_;  ///< per primitive: the cluster last processed that it has a face in
  std::unique_ptr<BoxGrid> grid_;
  int queries_ = 0;
  std::vector<int> found_;
};

}  // namespace

SurfaceSearch extractSurfaces(const SurfaceParts& parts, const std::vector<Cluster>& clusters,
                              const SurfaceOptions& options) {
  return Extraction(parts, clusters, options).run();
}

}  // namespace surfaces
}  // namespace placement_samplers
