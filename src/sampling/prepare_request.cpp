// SceneGenerator::prepare(): a request checked against the configuration and completed, so
// that sampling needs no more checks.
#include <cmath>
#include <sstream>
#include <string>
#include <unordered_set>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/geometry/unit_quaternion.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/sampling/packing_bound.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "placement_samplers/text.hpp"
#include "sampling/request_surfaces.hpp"
#include "sampling/scene_physics.hpp"

namespace placement_samplers {

namespace {

/// Finite and within +-limits::kCoordinate: sums of such values stay finite.
bool isBounded(const Eigen::Vector3d& v) {
  return v.allFinite() && (v.array().abs() <= limits::kCoordinate).all();
}

std::string coordinateLimit() {
  std::ostringstream out;
  out << "finite and within [-" << limits::kCoordinate << ", " << limits::kCoordinate << "] m";
  return out.str();
}

}  // namespace

namespace {

/// True when a call-level argument (@p field of SampleArgs) reaches a uniform sampler below
/// @p sampler: some path to it has no sample_args that set the field.
template <typename Field>
bool reachesUniform(const PlacementSampler& sampler, Field SampleArgs::*field) {
  const auto* composite = dynamic_cast<const SequentialCompositeSampler*>(&sampler);
  if (composite == nullptr) {
    return true;
  }
  for (const SequentialCompositeSampler::Child& child : composite->children()) {
    if (!(child.args.*field) && reachesUniform(*child.sampler, field)) {
      return true;
    }
  }
  return false;
}

}  // namespace

PreparedRequest SceneGenerator::prepare(const SampleRequest& request) const {
  // The request's clock starts here: checking thousands of fixtures takes time too.
  const auto start = std::chrono::steady_clock::now();
  const SceneConfig& config = *config_;
  PreparedRequest prepared;
  prepared.collisionCheck = request.collisionCheck.value_or(config.collisionCheck);
  prepared.maxAttempts = request.maxAttempts;
  if (!std::isfinite(request.maxSeconds) || request.maxSeconds < 0.0) {
    throw RequestError("the time limit must be a non-negative number of seconds");
  }
  if (request.maxSeconds > limits::kRequestSeconds) {
    std::ostringstream out;
    out << "the time limit must be at most " << limits::kRequestSeconds << " s, got "
        << request.maxSeconds;
    throw RequestError(out.str());
  }
  prepared.maxSeconds = request.maxSeconds;
  if (!std::isfinite(request.maxSceneSeconds) || request.maxSceneSeconds < 0.0 ||
      request.maxSceneSeconds > limits::kRequestSeconds) {
    std::ostringstream out;
    out << "the time limit of a scene must be a number of seconds in [0, "
        << limits::kRequestSeconds << "], got " << request.maxSceneSeconds;
    throw RequestError(out.str());
  }
  prepared.maxSceneSeconds = request.maxSceneSeconds;
  if (request.maxSeconds > 0.0) {
    prepared.deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                    std::chrono::duration<double>(request.maxSeconds));
  }
  if (request.fixtures.size() > config.maxFixturesPerRequest) {
    throw RequestError("the request has " + countText(request.fixtures.size(), "fixture") +
                       ", more than max_fixtures_per_request (" +
                       std::to_string(config.maxFixturesPerRequest) + ")");
  }
  prepared.fixtures = config.fixtures;
  prepared.fixtures.reserve(config.fixtures.size() + request.fixtures.size());
  // Fixture names seen so far: a set, so that many fixtures cost near-linear time.
  std::unordered_set<std::string_view> fixtureNames;
  for (const FixtureSpec& f : config.fixtures) {
    fixtureNames.insert(f.name);
  }

  for (std::size_t i = 0; i < request.fixtures.size(); ++i) {
    const RequestFixture& f = request.fixtures[i];
    if ((i & 63u) == 63u && prepared.deadline &&
        std::chrono::steady_clock::now() > *prepared.deadline) {
      throw RequestError("the request ran out of time while checking its " +
                         countText(request.fixtures.size(), "fixture"));
    }
    const std::string label = "fixture " + quoteText(f.name);
    if (!isValidName(f.name)) {
      throw RequestError("fixture name " + quoteText(f.name) + " must match [A-Za-z0-9_-]+");
    }
    if (config.findObject(f.name) != nullptr) {
      throw RequestError(label + ": the name is already a configured object");
    }
    if (fixtureNames.count(f.name) != 0) {
      throw RequestError(label + ": the name is used twice");
    }
    if (!f.position.allFinite()) {
      throw RequestError(label + ": position must be finite");
    }
    if (!isBounded(f.position)) {
      throw RequestError(label + ": position must be " + coordinateLimit());
    }
    if (!isUnitQuaternion(f.orientation)) {
      throw RequestError(label + ": orientation must be a finite unit quaternion");
    }
    FixtureSpec spec;
    spec.name = f.name;
    spec.objectName = f.object;
    spec.position = f.position;
    spec.orientation = f.orientation.normalized();
    if (!f.object.empty()) {
      const ObjectModel* object = config.findObject(f.object);
      if (object == nullptr) {
        throw RequestError(label + ": unknown object " + quoteText(f.object));
      }
      spec.object = std::make_shared<ObjectModel>(reorientedObject(*object, spec.orientation));
    } else {
      if (!f.shape) {
        throw RequestError(label + ": give an object name or a shape");
      }
      try {
        validateShape(*f.shape);
      } catch (const ConfigError& e) {
        throw RequestError(label + ": " + e.what());
      }
      spec.object = std::make_shared<ObjectModel>(makeObject(f.name, {*f.shape}, spec.orientation));
    }
    prepared.fixtures.push_back(std::move(spec));
    // A view of the name in the request, which outlives this function.
    fixtureNames.insert(f.name);
  }

  SampleArgs args;
  if (request.sampler.empty()) {
    prepared.sampler = config.root.get();
  } else {
    prepared.sampler = config.root->find(request.sampler, &args);
    if (prepared.sampler == nullptr) {
      std::vector<const PlacementSampler*> all;
      config.root->collectSamplers(all);
      std::string names;
      for (const PlacementSampler* s : all) {
        if (names.size() > 2000) {
          names += ", ...";
          break;
        }
        names += (names.empty() ? "" : ", ") + escapeText(s->name());
      }
      throw RequestError("unknown sampler " + quoteText(request.sampler) +
                         " (configured: " + names + ")");
    }
  }

  const Reference& reference = request.reference;
  if (reference.kind == Reference::Kind::Point && !reference.point.allFinite()) {
    throw RequestError("reference_point must be finite");
  }
  if (reference.kind == Reference::Kind::Point && !isBounded(reference.point)) {
    throw RequestError("reference_point must be " + coordinateLimit());
  }
  if (reference.kind == Reference::Kind::Name) {
    const bool known =
        config.findObject(reference.name) != nullptr || fixtureNames.count(reference.name) != 0;
    if (!known) {
      throw RequestError("unknown reference " + quoteText(reference.name) +
                         " (not a configured object or a fixture)");
    }
  }
  // A sampler run alone keeps the sample_args its parent gives it; the call fills in the rest.
  prepared.reference = args.reference ? *args.reference : reference;
  prepared.onTop = args.onTop ? *args.onTop : request.onTop.value_or(true);
  if (reference.kind != Reference::Kind::Default &&
      (args.reference || !reachesUniform(*prepared.sampler, &SampleArgs::reference))) {
    prepared.notes.push_back(
        "the call's reference was not used: every sampler it would reach sets its own in "
        "sample_args");
  }
  if (request.onTop && (args.onTop || !reachesUniform(*prepared.sampler, &SampleArgs::onTop))) {
    prepared.notes.push_back(
        "the call's on_top was not used: every sampler it would reach sets its own in "
        "sample_args");
  }
  // A sampler whose objects cannot fit at any packing fails every scene: say so at once.
  if (auto why = findOverfullSampler(*prepared.sampler, prepared.reference, prepared.onTop,
                                     prepared.collisionCheck)) {
    throw RequestError(*why);
  }
  detail::prepareRequestSurfaces(prepared);
  prepared.physics = config.physics;
  prepared.physics.mode = request.physics.value_or(config.physics.mode);
  if (prepared.physics.mode != PhysicsMode::None) {
    prepared.physicsModel = std::make_shared<ScenePhysics>(config, prepared);  // compiled later
  }
  return prepared;
}

}  // namespace placement_samplers
