#include "placement_samplers/validation/scene_validator.hpp"

#include <cmath>
#include <memory>
#include <sstream>
#include <unordered_map>

#include "placement_samplers/collision/make_collision_checker.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/sampling/sample_context.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"
#include "placement_samplers/validation/check_relations.hpp"
#include "placement_samplers/validation/region_test.hpp"
#include "validation/overlap_search.hpp"
#include "validation/surface_check.hpp"
#include "validation/verdict_text.hpp"

namespace placement_samplers {
namespace {

using detail::addViolation;
using detail::metres;

/// Replays the sampler tree over the given poses: the same fixtures, references, heights and
/// collision tests as sampling, each pose taking the place of the accepted candidate.
class Validator {
 public:
  Validator(const SceneGenerator& generator, const PreparedRequest& request,
            const ValidationOptions& options)
      : request_(request),
        options_(options),
        checker_(makeCollisionChecker(request.collisionCheck, generator.config().collisionMargin)),
        overlaps_(request.collisionCheck, generator.config().collisionMargin, options),
        context_(engine_, *checker_) {}

  SceneVerdict run(const std::vector<GivenPose>& poses) {
    SceneVerdict verdict;
    // The sampler's objects first, in sampling order; then what does not belong.
    for (const ObjectPtr& object : request_.sampler->objects()) {
      slots_.emplace(object->name, verdict.objects.size());
      verdict.objects.push_back(ObjectVerdict{object->name, true, {}});
    }
    for (const GivenPose& pose : poses) {
      const auto slot = slots_.find(pose.name);
      if (slot == slots_.end()) {
        ObjectVerdict unknown{pose.name, false, {}};
        addViolation(unknown, Violation::Kind::Unknown, "", "", 0.0,
                     "object " + quoteText(pose.name) + " is not placed by sampler " +
                         quoteText(request_.sampler->name()));
        verdict.objects.push_back(std::move(unknown));
        continue;
      }
      if (!given_.emplace(pose.name, &pose).second) {
        addViolation(
            verdict.objects[slot->second], Violation::Kind::Duplicate, "", "", 0.0,
            "object " + quoteText(pose.name) + " is given more than once: the first pose counts");
      }
    }
    objects_ = &verdict.objects;
    for (const FixtureSpec& f : request_.fixtures) {
      context_.addFixture(f.name, f.object.get(), f.position, f.orientation);
    }
    request_.sampler->forEachUniform(
        request_.reference, request_.onTop,
        [this](const UniformRandomSampler& uniform, const Reference& reference, bool onTop) {
          visit(uniform, reference, onTop);
        });
    for (const ObjectVerdict& o : verdict.objects) {
      verdict.valid = verdict.valid && o.valid;
    }
    return verdict;
  }

 private:
  void visit(const UniformRandomSampler& uniform, const Reference& reference, bool onTop) {
    const PlacedEntry* ref =
        reference.kind == Reference::Kind::Name ? context_.find(reference.name) : nullptr;
    const std::optional<Eigen::Vector3d> base =
        uniform.base(reference, onTop, ref ? &ref->position : nullptr, ref ? ref->object : nullptr);
    for (const ObjectPtr& object : uniform.objects()) {
      check(uniform, *object, base ? &*base : nullptr, reference, onTop);
    }
  }

  void check(const UniformRandomSampler& sampler, const ObjectModel& object,
             const Eigen::Vector3d* base, const Reference& reference, bool onTop) {
    ObjectVerdict& verdict = (*objects_)[slots_.at(object.name)];
    const std::string& s = sampler.name();
    const auto given = given_.find(object.name);
    if (given == given_.end()) {
      // A hidden object is parked far away by sampling; a scene arranged by hand or measured
      // does not hold it, so it may be left out (a given pose of it is still checked).
      if (sampler.params().hides) {
        return;
      }
      addViolation(
          verdict, Violation::Kind::Missing, s, "", 0.0,
          "object " + quoteText(object.name) + " of sampler " + quoteText(s) + " is missing");
      return;
    }
    const GivenPose& pose = *given->second;
    const double norm = pose.orientation.coeffs().norm();
    const bool bounded =
        pose.position.allFinite() && (pose.position.array().abs() <= limits::kCoordinate).all();
    if (!bounded || !std::isfinite(norm) || norm < 1e-6) {
      addViolation(
          verdict, Violation::Kind::BadPose, "", "", 0.0,
          "object " + quoteText(object.name) + ": " +
              (!bounded ? "the position must be finite and within +-" + metres(limits::kCoordinate)
                        : std::string("the orientation must be a finite non-zero quaternion")));
      return;
    }
    Candidate candidate;
    candidate.object = &object;
    candidate.position = pose.position;
    // Normalised only when it is not a unit quaternion already: a sampled pose is tested with
    // the very bits it was sampled with.
    candidate.orientation = std::abs(norm - 1.0) > 1e-12
                                ? Eigen::Quaterniond(pose.orientation.coeffs() / norm)
                                : pose.orientation;
    const UniformSamplerParams& params = sampler.params();
    // resting: stable: the resting pose it is in (its bounds decide region and height).
    const ObjectModel& posed = restingModel(verdict, sampler, object, candidate.orientation);
    candidate.object = &posed;
    if (base == nullptr) {
      addViolation(verdict, Violation::Kind::ReferenceMissing, s, reference.name, 0.0,
                   "object " + quoteText(object.name) + ": reference " + quoteText(reference.name) +
                       " of sampler " + quoteText(s) +
                       " is neither a fixture nor an object placed before it");
    } else if (params.surface) {
      detail::checkOnSurface(verdict, sampler, posed, *base, candidate, context_,
                             &request_.surfaces, options_);
    } else {
      const double outside = distanceOutsideRegion(sampler, posed, *base, pose.position);
      if (outside > options_.regionTolerance) {
        addViolation(verdict, Violation::Kind::OutsideRegion, s, "", outside,
                     "object " + quoteText(object.name) + " is outside the region of sampler " +
                         quoteText(s) + " by " + metres(outside));
      }
      const double z = sampler.height(posed, *base, onTop);
      const double off = std::abs(pose.position.z() - z);
      if (!(off <= options_.heightTolerance)) {
        addViolation(verdict, Violation::Kind::Height, s, "", off,
                     "object " + quoteText(object.name) + " is at z " + metres(pose.position.z()) +
                         ", off the height of sampler " + quoteText(s) + " (" + metres(z) +
                         ") by " + metres(off));
      }
    }
    for (RelationMiss& miss : checkRelations(sampler, object, candidate, context_)) {
      addViolation(verdict, Violation::Kind::Relation, s, miss.target, miss.value,
                   std::move(miss.message));
    }
    if (params.ensureValidPlacement) {
      const std::ptrdiff_t hit = context_.firstCollision(candidate);
      if (hit != CollisionChecker::kNone) {
        overlaps_.list(verdict, candidate, object.name, s, hit, context_.entries());
      }
    }
    context_.addPlacement(s, candidate, 1, params.hides);
  }

  /// Under resting: stable, @p object in the resting pose that @p orientation is (the pose
  /// turned about z); a RestPose violation and @p object itself when it is in none. @p object
  /// otherwise.
  const ObjectModel& restingModel(ObjectVerdict& verdict, const UniformRandomSampler& sampler,
                                  const ObjectModel& object,
                                  const Eigen::Quaterniond& orientation) {
    const std::vector<UniformRandomSampler::RestingChoice> choices = sampler.restingChoices(object);
    if (choices.empty()) {
      return object;
    }
    constexpr double kTurnTolerance = 1e-6;  // of the quaternion's x and y parts
    for (const UniformRandomSampler::RestingChoice& c : choices) {
      const Eigen::Quaterniond turn = orientation * c.object->initOrientation.inverse();
      if (std::abs(turn.x()) < kTurnTolerance && std::abs(turn.y()) < kTurnTolerance) {
        return *c.object;
      }
    }
    addViolation(verdict, Violation::Kind::RestPose, sampler.name(), "", 0.0,
                 "object " + quoteText(object.name) + " is in none of its " +
                     countText(choices.size(), "resting pose") +
                     " (each turned about z only) of sampler " + quoteText(sampler.name()));
    return object;
  }

  const PreparedRequest& request_;
  ValidationOptions options_;
  Engine engine_;  // SampleContext wants one; validation draws nothing
  std::unique_ptr<CollisionChecker> checker_;
  detail::OverlapSearch overlaps_;
  SampleContext context_;
  std::unordered_map<std::string, std::size_t> slots_;
  std::unordered_map<std::string, const GivenPose*> given_;
  std::vector<ObjectVerdict>* objects_ = nullptr;
};

}  // namespace

const char* violationKindName(Violation::Kind kind) {
  switch (kind) {
    case Violation::Kind::OutsideRegion:
      return "outside_region";
    case Violation::Kind::Overlap:
      return "overlap";
    case Violation::Kind::Height:
      return "height";
    case Violation::Kind::Unknown:
      return "unknown_object";
    case Violation::Kind::Missing:
      return "missing_object";
    case Violation::Kind::Duplicate:
      return "duplicate";
    case Violation::Kind::ReferenceMissing:
      return "reference_missing";
    case Violation::Kind::BadPose:
      return "bad_pose";
    case Violation::Kind::RestPose:
      return "rest_pose";
    case Violation::Kind::Relation:
      return "relation";
  }
  return "unknown_object";
}

SceneVerdict validateScene(const SceneGenerator& generator, const PreparedRequest& request,
                           const std::vector<GivenPose>& poses, const ValidationOptions& options) {
  if (!std::isfinite(options.heightTolerance) || options.heightTolerance < 0.0) {
    std::ostringstream out;
    out << "height_tolerance: expected a finite non-negative number of metres, got "
        << options.heightTolerance;
    throw RequestError(out.str());
  }
  if (!std::isfinite(options.regionTolerance) || options.regionTolerance < 0.0) {
    throw RequestError("region tolerance: expected a finite non-negative number of metres");
  }
  if (poses.size() > limits::kValidatedPlacements) {
    throw RequestError("the scene has " + std::to_string(poses.size()) +
                       " placements, more than the limit of " +
                       std::to_string(limits::kValidatedPlacements));
  }
  Validator validator(generator, request, options);
  return validator.run(poses);
}

}  // namespace placement_samplers
