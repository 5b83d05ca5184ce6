#include "placement_samplers/ros/validation_service.hpp"

#include <cmath>
#include <exception>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/ros/conversions.hpp"
#include "placement_samplers/validation/scene_validator.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

std::uint8_t kindMsg(Violation::Kind kind) {
  switch (kind) {
    case Violation::Kind::OutsideRegion:
      return PoseViolation::OUTSIDE_REGION;
    case Violation::Kind::Overlap:
      return PoseViolation::OVERLAP;
    case Violation::Kind::Height:
      return PoseViolation::HEIGHT;
    case Violation::Kind::Unknown:
      return PoseViolation::UNKNOWN_OBJECT;
    case Violation::Kind::Missing:
      return PoseViolation::MISSING_OBJECT;
    case Violation::Kind::Duplicate:
      return PoseViolation::DUPLICATE;
    case Violation::Kind::ReferenceMissing:
      return PoseViolation::REFERENCE_MISSING;
    case Violation::Kind::BadPose:
      return PoseViolation::BAD_POSE;
    case Violation::Kind::RestPose:
      return PoseViolation::REST_POSE;
    case Violation::Kind::Relation:
      return PoseViolation::RELATION;
  }
  return PoseViolation::UNKNOWN_OBJECT;
}

}  // namespace

void answerValidation(const SceneGenerator& generator, const ValidatePlacements::Request& request,
                      ValidatePlacements::Response& response) {
  response.valid = false;
  response.objects.clear();
  try {
    // The sampler, fixtures and check as a sampling request takes them: one conversion.
    SamplePlacements::Request sampling;
    sampling.sampler = request.sampler;
    sampling.fixtures = request.fixtures;
    sampling.collision_check = request.collision_check;
    const PreparedRequest prepared = generator.prepare(toSampleRequest(sampling));
    ValidationOptions options;
    if (request.height_tolerance != 0.0) {
      options.heightTolerance = request.height_tolerance;
    }
    std::vector<GivenPose> poses;
    poses.reserve(request.placements.size());
    for (const Placement& p : request.placements) {
      // Validation is about sampled poses, as the CLI's: a simulated placement (an answer's
      // under physics check or settle) is validated at its sampled_pose, since a settled pose
      // need not validate; any other at its pose, which may have been edited or measured.
      const geometry_msgs::Pose& given = p.simulated ? p.sampled_pose : p.pose;
      GivenPose pose;
      pose.name = p.name;
      pose.position = Eigen::Vector3d(given.position.x, given.position.y, given.position.z);
      pose.orientation = Eigen::Quaterniond(given.orientation.w, given.orientation.x,
                                            given.orientation.y, given.orientation.z);
      poses.push_back(std::move(pose));
    }
    const SceneVerdict verdict = validateScene(generator, prepared, poses, options);
    response.valid = verdict.valid;
    response.message.clear();
    for (const ObjectVerdict& o : verdict.objects) {
      PoseVerdict out;
      out.name = o.name;
      out.valid = o.valid;
      for (const Violation& v : o.reasons) {
        PoseViolation r;
        r.kind = kindMsg(v.kind);
        r.sampler = v.sampler;
        r.other = v.other;
        r.check = v.check;
        r.distance = v.distance;
        r.message = v.message;
        out.reasons.push_back(std::move(r));
      }
      response.objects.push_back(std::move(out));
    }
  } catch (const std::exception& e) {
    response.valid = false;
    response.message = e.what();
    response.objects.clear();
  }
}

}  // namespace ros_interface
}  // namespace placement_samplers
