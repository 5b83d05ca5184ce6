// A surface region's selection of the support surfaces found on its target.
#include <algorithm>
#include <sstream>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/sampling/surface_region.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace {

/// Surfaces whose heights differ by less are at the same height for `select: top` [m].
constexpr double kSameHeight = 1e-3;

}  // namespace

SurfaceOptions SurfaceRegion::options() const {
  SurfaceOptions o;
  o.minArea = minArea;
  o.normalTolerance = normalTolerance;
  return o;
}

std::string selectText(const SurfaceRegion& region) {
  switch (region.select) {
    case SurfaceRegion::Select::All:
      return "all";
    case SurfaceRegion::Select::Top:
      return "top";
    case SurfaceRegion::Select::Indices:
      break;
  }
  std::ostringstream out;
  out << "[";
  for (std::size_t i = 0; i < region.indices.size(); ++i) {
    out << (i > 0 ? ", " : "") << region.indices[i];
  }
  out << "]";
  return out.str();
}

std::vector<std::size_t> selectIndices(const SurfaceRegion& region, const SurfaceSearch& found) {
  const std::vector<SupportSurface>& all = found.surfaces;
  if (all.empty()) {
    std::ostringstream out;
    out << "region.of " << quoteText(region.of) << " has no support surface of at least "
        << region.minArea << " m^2 (min_area) facing up within " << region.normalTolerance
        << " rad (normal_tolerance)";
    if (found.largestDroppedArea > 0.0) {
      out << "; the largest one found has " << found.largestDroppedArea << " m^2";
    } else {
      out << "; it has no up-facing face at all";
    }
    throw ConfigError(out.str());
  }
  switch (region.select) {
    case SurfaceRegion::Select::All: {
      std::vector<std::size_t> out(all.size());
      for (std::size_t i = 0; i < all.size(); ++i) {
        out[i] = i;
      }
      return out;
    }
    case SurfaceRegion::Select::Top: {
      double top = all.front().z;
      for (const SupportSurface& s : all) {
        top = std::max(top, s.z);
      }
      std::vector<std::size_t> out;
      for (std::size_t i = 0; i < all.size(); ++i) {
        if (all[i].z > top - kSameHeight) {
          out.push_back(i);
        }
      }
      return out;
    }
    case SurfaceRegion::Select::Indices:
      break;
  }
  for (std::size_t k = 0; k < region.indices.size(); ++k) {
    const std::size_t i = region.indices[k];
    if (std::find(region.indices.begin(), region.indices.begin() + static_cast<std::ptrdiff_t>(k),
                  i) != region.indices.begin() + static_cast<std::ptrdiff_t>(k)) {
      throw ConfigError("region.select: index " + std::to_string(i) + " is listed twice");
    }
    if (i >= all.size()) {
      std::ostringstream message;
      message << "region.select: index " << i << " is past the last support surface of "
              << quoteText(region.of) << ", which has " << countText(all.size(), "surface")
              << " (indices 0 to " << all.size() - 1 << ", as --describe lists them)";
      throw ConfigError(message.str());
    }
  }
  return region.indices;
}

std::vector<SupportSurface> selectSurfaces(const SurfaceRegion& region,
                                           const SurfaceSearch& found) {
  std::vector<SupportSurface> out;
  for (const std::size_t i : selectIndices(region, found)) {
    out.push_back(found.surfaces[i]);
  }
  return out;
}

std::vector<SupportSurface> surfacesOf(const SurfaceRegion& region, const ObjectModel& object,
                                       const Eigen::Vector3d& position,
                                       const Eigen::Quaterniond& orientation) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = position;
  pose.linear() = orientation.normalized().toRotationMatrix();
  return selectSurfaces(region, findSupportSurfaces(object.shapes, pose, region.options()));
}

const SurfaceDrawCache::Value* SurfaceDrawCache::find(const Key& key) const {
  for (const auto& [k, v] : entries_) {
    if (k == key) {
      return &v;
    }
  }
  return nullptr;
}

const SurfaceDrawCache::Value& SurfaceDrawCache::store(const Key& key, Value value) {
  for (auto& [k, v] : entries_) {
    if (k.sampler == key.sampler && k.object == key.object) {
      k = key;
      v = std::move(value);
      return v;
    }
  }
  entries_.emplace_back(key, std::move(value));
  return entries_.back().second;
}

}  // namespace placement_samplers
