#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "placement_samplers/sampling/placement.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {

/// Where a uniform sampler drew its x-y positions in one scene, for display.
struct SamplerRegion {
  std::string sampler;
  Eigen::Vector3d centre =
      Eigen::Vector3d::Zero();  ///< centre of the range, at base z + z_offset [m]
  Eigen::Vector2d size = Eigen::Vector2d::Zero();  ///< extents of x_range and y_range [m]
  /// A region shape other than robosuite's rectangle, or a keep-out zone: filled triangles
  /// (three corners each) in the sampler's frame_id at the region's height [m]; empty for a
  /// rectangle of x_range and y_range (centre and size).
  std::vector<Eigen::Vector3d> triangles;
  bool keepOut = false;  ///< a keep-out zone of the sampler, not where it draws
  /// A support surface of a surface region (its triangles at the surface's height; each
  /// surface once, whatever number of samplers draw on it) with @ref label
  /// "shelf1: surface i, clearance c m" at @ref centre.
  bool surface = false;
  std::string label;
};

/// The regions and keep-out zones of every uniform sampler that @p request ran in @p scene
/// (hidden ones left out),
/// with named references resolved against the scene's fixtures and placements. A sampler whose
/// reference is not in the scene (it failed before) is left out.
std::vector<SamplerRegion> samplerRegions(const PreparedRequest& request, const SceneResult& scene);

}  // namespace placement_samplers
