#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "placement_samplers/sampling/relations.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {

/// One relation of one placed object in a scene, for display: from the object's origin to its
/// target's.
struct RelationLink {
  std::string sampler;
  std::string object;
  std::string target;
  std::size_t index = 0;  ///< in the sampler's relations
  Relation::Kind kind = Relation::Kind::NextTo;
  Eigen::Vector3d from = Eigen::Vector3d::Zero();  ///< the object's origin [m]
  Eigen::Vector3d to = Eigen::Vector3d::Zero();    ///< the target's origin [m]
  /// relationHolds(); in the fcl modes next_to and away_from by the shapes' exact distance
  bool satisfied = false;
};

/// The relations of every uniform sampler that @p request ran in @p scene, one link per placed
/// object (hidden ones left out) and relation that applies to it whose target is in the scene
/// (a request fixture or a placement).
std::vector<RelationLink> relationLinks(const PreparedRequest& request, const SceneResult& scene);

}  // namespace placement_samplers
