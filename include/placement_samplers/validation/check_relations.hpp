#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "placement_samplers/collision/collision_checker.hpp"
#include "placement_samplers/sampling/sample_context.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"

namespace placement_samplers {

/// One relation of a sampler that does not hold for one object.
struct RelationMiss {
  std::size_t index = 0;  ///< in the sampler's relations
  std::string target;
  /// next_to, away_from: the gap [m]; align_with, face: how far the yaw is off [rad]
  double value = 0.0;
  std::string message;  ///< the whole sentence
};

/// The relations of @p sampler that apply to @p object and do not hold for @p candidate (the
/// object's pose; its `object` the model in its resting pose, whose radius counts), against
/// the fixtures and objects already in @p context. Position relations are decided by the very
/// test sampling uses (PositionTest::holds(), or in the fcl modes PositionTest::holdsGap() with
/// the shapes' exact distance from @p context's checker); angles with kRelationAngleSlack.
std::vector<RelationMiss> checkRelations(const UniformRandomSampler& sampler,
                                         const ObjectModel& object, const Candidate& candidate,
                                         SampleContext& context);

}  // namespace placement_samplers
