#include "placement_samplers/validation/scene_validator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "placement_samplers/collision/make_collision_checker.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/sampling/sample_context.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"
#include "placement_samplers/validation/check_relations.hpp"
#include "placement_samplers/validation/region_test.hpp"

namespace placement_samplers {
namespace {

std::string metres(double v) {
  std::ostringstream out;
  out << v << " m";
  return out.str();
}

/// Replays the sampler tree over the given poses: the same fixtures, references, heights and
/// collision tests as sampling, each pose taking the place of the accepted candidate.
class Validator {
 public:
  Validator(const SceneGenerator& generator, const PreparedRequest& request,
            const ValidationOptions& options)
      : request_(request),
        options_(options),
        checker_(makeCollisionChecker(request.collisionCheck, generator.config().collisionMargin)),
        margin_(generator.config().collisionMargin),
        pairChecker_(makeCollisionChecker(request.collisionCheck, margin_)),
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
        add(unknown, Violation::Kind::Unknown, "", "", 0.0,
            "object " + quoteText(pose.name) + " is not placed by sampler " +
                quoteText(request_.sampler->name()));
        verdict.objects.push_back(std::move(unknown));
        continue;
      }
      if (!given_.emplace(pose.name, &pose).second) {
        add(verdict.objects[slot->second], Violation::Kind::Duplicate, "", "", 0.0,
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
  static void add(ObjectVerdict& verdict, Violation::Kind kind, const std::string& sampler,
                  const std::string& other, double distance, std::string message) {
    Violation v;
    v.kind = kind;
    v.sampler = sampler;
    v.other = other;
    v.distance = distance;
    v.message = std::move(message);
    verdict.valid = false;
    verdict.reasons.push_back(std::move(v));
  }

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
      add(verdict, Violation::Kind::Missing, s, "", 0.0,
          "object " + quoteText(object.name) + " of sampler " + quoteText(s) + " is missing");
      return;
    }
    const GivenPose& pose = *given->second;
    const double norm = pose.orientation.coeffs().norm();
    const bool bounded =
        pose.position.allFinite() && (pose.position.array().abs() <= limits::kCoordinate).all();
    if (!bounded || !std::isfinite(norm) || norm < 1e-6) {
      add(verdict, Violation::Kind::BadPose, "", "", 0.0,
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
      add(verdict, Violation::Kind::ReferenceMissing, s, reference.name, 0.0,
          "object " + quoteText(object.name) + ": reference " + quoteText(reference.name) +
              " of sampler " + quoteText(s) +
              " is neither a fixture nor an object placed before it");
    } else if (params.surface) {
      checkSurface(verdict, sampler, posed, *base, candidate);
    } else {
      const double outside = distanceOutsideRegion(sampler, posed, *base, pose.position);
      if (outside > options_.regionTolerance) {
        add(verdict, Violation::Kind::OutsideRegion, s, "", outside,
            "object " + quoteText(object.name) + " is outside the region of sampler " +
                quoteText(s) + " by " + metres(outside));
      }
      const double z = sampler.height(posed, *base, onTop);
      const double off = std::abs(pose.position.z() - z);
      if (!(off <= options_.heightTolerance)) {
        add(verdict, Violation::Kind::Height, s, "", off,
            "object " + quoteText(object.name) + " is at z " + metres(pose.position.z()) +
                ", off the height of sampler " + quoteText(s) + " (" + metres(z) + ") by " +
                metres(off));
      }
    }
    for (RelationMiss& miss : checkRelations(sampler, object, candidate, context_)) {
      add(verdict, Violation::Kind::Relation, s, miss.target, miss.value, std::move(miss.message));
    }
    if (params.ensureValidPlacement) {
      const std::ptrdiff_t hit = context_.firstCollision(candidate);
      if (hit != CollisionChecker::kNone) {
        overlaps(verdict, candidate, object.name, s, hit);
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
    add(verdict, Violation::Kind::RestPose, sampler.name(), "", 0.0,
        "object " + quoteText(object.name) + " is in none of its " +
            countText(choices.size(), "resting pose") + " (each turned about z only) of sampler " +
            quoteText(sampler.name()));
    return object;
  }

  /// A surface region's checks of @p candidate: on a selected surface that the object fits
  /// under (OUTSIDE_REGION with the distance, keep-out zones too), at its height (HEIGHT);
  /// the target becomes the candidate's support, which the radius test skips.
  void checkSurface(ObjectVerdict& verdict, const UniformRandomSampler& sampler,
                    const ObjectModel& object, const Eigen::Vector3d& base, Candidate& candidate) {
    const std::string& s = sampler.name();
    const SurfaceRegion& region = *sampler.params().surface;
    const PlacedEntry* target = context_.find(region.of);
    if (target == nullptr) {
      add(verdict, Violation::Kind::ReferenceMissing, s, region.of, 0.0,
          "object " + quoteText(object.name) + ": region.of " + quoteText(region.of) +
              " of sampler " + quoteText(s) +
              " is neither a fixture nor an object placed before it");
      return;
    }
    candidate.support = target - context_.entries().data();
    std::vector<SupportSurface> surfaces;
    try {
      surfaces = sampler.surfacesOn(*target, &request_.surfaces);
    } catch (const ConfigError& e) {
      add(verdict, Violation::Kind::OutsideRegion, s, region.of, 0.0,
          "object " + quoteText(object.name) + ": sampler " + quoteText(s) + ": " + e.what());
      return;
    }
    const double height = object.topOffset.z() - object.bottomOffset.z();
    std::vector<SupportSurface> fitting;
    for (SupportSurface& surface : surfaces) {
      if (height <= surface.clearance) {
        fitting.push_back(std::move(surface));
      }
    }
    if (fitting.empty()) {
      add(verdict, Violation::Kind::OutsideRegion, s, region.of, 0.0,
          "object " + quoteText(object.name) + " fits on no selected surface of " +
              quoteText(region.of) + " (sampler " + quoteText(s) + ")");
      return;
    }
    // The surface it is on: the nearest in x-y, and of those as near (all it lies on:
    // shelves stack them) the one at the nearest height.
    const Eigen::Vector3d& p = candidate.position;
    const double lift = sampler.params().zOffset - object.bottomOffset.z();
    std::size_t nearest = 0;
    double outside = std::numeric_limits<double>::infinity();
    double off = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < fitting.size(); ++i) {
      const double d = surfaceShortfall(fitting[i], sampler.surfaceInset(object), p.head<2>());
      const double dz = std::abs(p.z() - (fitting[i].z + lift));
      const double tie = std::max(options_.regionTolerance, 1e-12);
      if (d < outside - tie || (std::abs(d - outside) <= tie && dz < off)) {
        nearest = i;
        outside = d;
        off = dz;
      }
    }
    const double margin =
        sampler.params().ensureObjectBoundaryInRange ? object.horizontalRadius : 0.0;
    for (const KeepOutZone& zone : sampler.params().keepOut) {
      const Eigen::Vector2d q =
          zone.world ? Eigen::Vector2d(p.head<2>()) : Eigen::Vector2d((p - base).head<2>());
      outside = std::max(outside, shapeDepth(zone.shape, q) + margin);
    }
    if (outside > options_.regionTolerance) {
      add(verdict, Violation::Kind::OutsideRegion, s, "", outside,
          "object " + quoteText(object.name) + " is outside the surfaces of " +
              quoteText(region.of) + " that sampler " + quoteText(s) + " draws on by " +
              metres(outside));
    }
    const double z = fitting[nearest].z + lift;
    if (!(off <= options_.heightTolerance)) {
      add(verdict, Violation::Kind::Height, s, "", off,
          "object " + quoteText(object.name) + " is at z " + metres(p.z()) +
              ", off the height of the surface of " + quoteText(region.of) + " it is on (" +
              metres(z) + ") by " + metres(off));
    }
  }

  /// The fixtures and earlier objects that @p candidate overlaps (@p hit is one of them, the
  /// scene checker's), one pair test each: the first options_.maxOverlapsListed as reasons,
  /// the number of the others in the last reason's message (a pile of n objects would
  /// otherwise give n^2 / 2 reasons). The scene's pair tests stop at options_.maxOverlapTests.
  void overlaps(ObjectVerdict& verdict, const Candidate& candidate, const std::string& name,
                const std::string& sampler, std::ptrdiff_t hit) {
    const char* mode = collisionModeName(request_.collisionCheck);
    const auto list = [&](const PlacedEntry& entry) {
      add(verdict, Violation::Kind::Overlap, sampler, std::string(entry.name), 0.0,
          "object " + quoteText(name) + " overlaps " + (entry.fixture ? "fixture " : "object ") +
              quoteText(entry.name) + " under the " + mode + " check");
      verdict.reasons.back().check = mode;
    };
    const std::vector<PlacedEntry>& entries = context_.entries();
    std::vector<PlacedEntry> one(1);
    std::size_t listed = 0;
    std::size_t more = 0;
    bool cut = false;
    for (const PlacedEntry& entry : entries) {
      if (tests_ >= options_.maxOverlapTests) {
        cut = true;
        break;
      }
      ++tests_;
      if (!pairCollides(entry, candidate, one)) {
        continue;
      }
      if (listed == options_.maxOverlapsListed) {
        ++more;
        continue;
      }
      ++listed;
      list(entry);
    }
    if (cut && listed == 0 && options_.maxOverlapsListed > 0) {
      list(entries[static_cast<std::size_t>(hit)]);  // not reached by the search
      ++listed;
    }
    const std::string stopped = "the scene's overlap search stopped after " +
                                std::to_string(options_.maxOverlapTests) + " tests";
    const std::string count = std::to_string(more);
    const char* kinds = more == 1 ? " fixture or object" : " fixtures and objects";
    if (listed > 0 && (more > 0 || cut)) {
      std::string note = more > 0 ? count + " more" + kinds + ", not listed" : "";
      if (cut) {
        note += std::string(more > 0 ? "; " : "") + "possibly others: " + stopped;
      }
      verdict.reasons.back().message += " (and " + note + ")";
    } else if (listed == 0 && (more > 0 || cut)) {
      add(verdict, Violation::Kind::Overlap, sampler, "", 0.0,
          "object " + quoteText(name) + " overlaps " +
              (more == 0 ? std::string("fixtures or objects")
                         : (cut ? "at least " : "") + count + kinds) +
              " under the " + mode + " check (not listed" + (cut ? "; " + stopped : "") + ")");
      verdict.reasons.back().check = mode;
    }
  }

  /// One pair test: @p entry alone against @p candidate. A checker keeps what it learnt of
  /// each object (FCL geometry) and visits it all when cleared, so a fresh one is taken every
  /// kPairObjects objects: a pair test then costs the same in a scene of any size.
  bool pairCollides(const PlacedEntry& entry, const Candidate& candidate,
                    std::vector<PlacedEntry>& one) {
    constexpr std::size_t kPairObjects = 64;
    pairObjects_.insert(entry.object);
    pairObjects_.insert(candidate.object);
    if (pairObjects_.size() > kPairObjects) {
      pairChecker_ = makeCollisionChecker(request_.collisionCheck, margin_);
      pairObjects_ = {entry.object, candidate.object};
    }
    one[0] = entry;
    // The candidate's support is the one entry here when it is this one.
    Candidate pair = candidate;
    pair.support =
        candidate.support >= 0 &&
                &entry == &context_.entries()[static_cast<std::size_t>(candidate.support)]
            ? 0
            : -1;
    pairChecker_->clear();
    pairChecker_->added(one, 0);
    return pairChecker_->firstCollision(one, pair) != CollisionChecker::kNone;
  }

  const PreparedRequest& request_;
  ValidationOptions options_;
  Engine engine_;  // SampleContext wants one; validation draws nothing
  std::unique_ptr<CollisionChecker> checker_;
  double margin_;
  std::unique_ptr<CollisionChecker> pairChecker_;
  std::unordered_set<const ObjectModel*> pairObjects_;  ///< what pairChecker_ has seen
  std::size_t tests_ = 0;                               ///< pair tests of the scene so far
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
