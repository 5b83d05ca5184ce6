#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <vector>

#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {

/// A pose to validate: one object of the configuration.
struct GivenPose {
  std::string name;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< object origin [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

/// One reason why an object's pose is not one the configuration allows.
struct Violation {
  enum class Kind {
    OutsideRegion,     ///< outside its sampler's region by @ref distance
    Overlap,           ///< overlaps @ref other under the check @ref check
    Height,            ///< its z is off the sampler's by @ref distance
    Unknown,           ///< not an object of the sampler validated against
    Missing,           ///< an object of the sampler that was not given (hidden ones may be absent)
    Duplicate,         ///< given more than once (the first is validated)
    ReferenceMissing,  ///< its sampler's reference (@ref other) is not in the scene
    BadPose,           ///< a coordinate is not finite or too large, or the quaternion is zero
    RestPose,          ///< resting: stable, and in none of the object's resting poses
    Relation,          ///< a relation of its sampler (@ref other: its target) does not hold by @ref
                       ///< distance
  };
  Kind kind = Kind::Unknown;
  /// The object's sampler ("" for Unknown, Duplicate, BadPose).
  std::string sampler;
  std::string other;  ///< Overlap: the object or fixture; ReferenceMissing: the reference
  std::string check;  ///< Overlap: "radius", "fcl" or "radius_and_fcl"
  /// OutsideRegion, Height: by how much [m]; Relation: the gap [m] (next_to, away_from) or how
  /// far the yaw is off [rad] (align_with, face)
  double distance = 0.0;
  std::string message;  ///< the whole sentence
};

/// The verdict on one object.
struct ObjectVerdict {
  std::string name;
  bool valid = true;
  std::vector<Violation> reasons;  ///< every reason it is not valid
};

/// The verdict on a scene: every object of the sampler (in sampling order), then the unknown
/// and duplicate names given.
struct SceneVerdict {
  bool valid = true;
  std::vector<ObjectVerdict> objects;
};

/// Tolerances of a validation.
struct ValidationOptions {
  /// How far an object's z may be from the height its sampler gives [m].
  double heightTolerance = 0.005;
  /// How far outside its region an object may be [m]: covers the rounding of sampling's
  /// x = u + reference (read back as x - reference).
  double regionTolerance = 1e-9;
  /// Overlaps listed per object (as reasons, in the order of the fixtures and objects before
  /// it): the message of the last one says how many more there are. 0 lists none: a single
  /// reason without `other` then gives their number.
  std::size_t maxOverlapsListed = 10;
  /// Pair tests of one scene's overlap search (one per overlapping object and fixture or object
  /// before it). Once they are used up, an overlapping object lists the overlap its sampling
  /// test found and its message says that others were not searched.
  std::size_t maxOverlapTests = 250000;
};

/// Whether @p poses form a scene that @p request (its sampler, fixtures, collision check) of
/// @p generator could sample: each object inside its uniform sampler's x-y region around the
/// resolved reference (after the boundary shrink), at the sampler's height within the
/// tolerance, and, when its sampler checks placements, overlapping no fixture and no object
/// placed before it in sampling order under the request's check, and every relation of its
/// sampler holding (check_relations.hpp). Named references resolve against the fixtures and the
/// given poses, as in sampling. Orientations are not checked, but by align_with and face.
/// Objects the configuration hides (`hide`) may be left out: a real scene does not hold them.
/// @throw RequestError when a tolerance is negative or not finite, or when @p poses has more
/// than limits::kValidatedPlacements poses
SceneVerdict validateScene(const SceneGenerator& generator, const PreparedRequest& request,
                           const std::vector<GivenPose>& poses,
                           const ValidationOptions& options = {});

/// The kind's name in outputs: "outside_region", "overlap", "height", "unknown_object",
/// "missing_object", "duplicate", "reference_missing", "bad_pose", "rest_pose" or "relation".
const char* violationKindName(Violation::Kind kind);

}  // namespace placement_samplers
