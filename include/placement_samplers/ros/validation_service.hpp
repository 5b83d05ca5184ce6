#pragma once

#include "placement_samplers/ValidatePlacements.h"
#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {
namespace ros_interface {

/// Answers ~validate_placements against @p generator (validateScene()). Never throws: a request
/// that cannot be validated (unknown sampler, bad fixture, unknown check, negative tolerance)
/// gets valid false, no objects and the reason in @p response.message. A placement with
/// `simulated` set (from an answer under physics check or settle) is validated at its
/// `sampled_pose`, any other at its `pose`.
void answerValidation(const SceneGenerator& generator, const ValidatePlacements::Request& request,
                      ValidatePlacements::Response& response);

}  // namespace ros_interface
}  // namespace placement_samplers
