#include "placement_samplers/sampling/scene_generator.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <utility>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>
#include <thread>
#include <unordered_set>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/collision/make_collision_checker.hpp"
#include "placement_samplers/text.hpp"
#include "placement_samplers/geometry/unit_quaternion.hpp"
#include "placement_samplers/sampling/packing_bound.hpp"
#include "sampling/cache_line.hpp"
#include "sampling/parallel.hpp"
#include "sampling/request_surfaces.hpp"
#include "sampling/scene_worker.hpp"

namespace placement_samplers {

SceneGenerator::SceneGenerator(std::shared_ptr<const SceneConfig> config)
    : config_(std::move(config)) {
  if (!config_ || !config_->root) {
    throw std::invalid_argument("SceneGenerator needs a built configuration");
  }
}

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

namespace {

/// The next scenes for a thread to sample, [first, second): a share of what is left, in
/// multiples of @p chunk, from 64 chunks down to one. Large shares first write the counter
/// that all threads share a few dozen times a batch instead of once per chunk (each write
/// moves its line between the cores); one chunk at the end keeps the threads finishing
/// together; 64 at most keep the scenes a cancel discards few (those after the first not
/// sampled). @p chunk 1 (simulated scenes): one at a time. Empty when none is left.
std::pair<std::uint64_t, std::uint64_t> takeScenes(std::atomic<std::uint64_t>& next,
                                                   std::uint64_t count, std::uint64_t chunk,
                                                   unsigned threads) {
  constexpr std::uint64_t kMaxChunks = 64;
  std::uint64_t begin = next.load(std::memory_order_relaxed);
  for (;;) {
    if (begin >= count) {
      return {count, count};
    }
    const std::uint64_t left = count - begin;
    const std::uint64_t chunks = chunk == 1 ? 1 : left / (4 * std::uint64_t{threads}) / chunk;
    const std::uint64_t share = chunk * std::clamp<std::uint64_t>(chunks, 1, kMaxChunks);
    const std::uint64_t end = begin + std::min(left, share);
    if (next.compare_exchange_weak(begin, end, std::memory_order_relaxed)) {
      return {begin, end};
    }
  }
}

}  // namespace

bool wasCancelled(const SceneResult& scene) {
  return !scene.success && scene.message == kCancelledMessage;
}

void checkSceneRange(std::uint64_t first, std::uint64_t count) {
  if (count > 0 && count - 1 > std::numeric_limits<std::uint64_t>::max() - first) {
    throw RequestError("first scene " + std::to_string(first) + " + " + countText(count, "scene") +
                       ": scene indices must stay below 2^64");
  }
}

std::uint64_t SceneGenerator::placementsPerScene(const PreparedRequest& request) const {
  return request.sampler->objects().size();
}

void SceneGenerator::checkAnswerSize(const PreparedRequest& request,
                                     std::uint64_t numScenes) const {
  const std::uint64_t perScene = placementsPerScene(request);
  const std::uint64_t limit = config_->maxPlacementsPerRequest;
  // perScene * numScenes > limit, without overflowing.
  if (perScene != 0 && numScenes > limit / perScene) {
    throw RequestError(
        countText(numScenes, "scene") + " of " + countText(perScene, "placement") +
        (numScenes == 1 ? " exceeds" : " each exceed") + " max_placements_per_request (" +
        std::to_string(limit) + "): ask for at most " +
        countText(std::max<std::uint64_t>(limit / perScene, 1), "scene") + " per request");
  }
}

void SceneGenerator::checkRequestSize(const PreparedRequest& request,
                                      std::uint64_t numScenes) const {
  if (numScenes > config_->maxScenesPerRequest) {
    throw RequestError("num_scenes " + std::to_string(numScenes) +
                       " exceeds max_scenes_per_request (" +
                       std::to_string(config_->maxScenesPerRequest) + ")");
  }
  checkAnswerSize(request, numScenes);
}

SceneResult SceneGenerator::sampleScene(const PreparedRequest& request, std::uint64_t seed,
                                        std::uint64_t index) const {
  Worker worker(request, config_->collisionMargin);
  worker.setDeadline(request.deadline);
  SceneResult result;
  worker.run(seed, index, result);
  return result;
}

std::vector<SceneResult> SceneGenerator::sampleScenes(const PreparedRequest& request,
                                                      std::uint64_t seed, std::uint64_t count,
                                                      unsigned threads) const {
  checkAnswerSize(request, count);
  return sampleSceneRange(request, seed, 0, count, threads);
}

std::vector<SceneResult> SceneGenerator::sampleSceneRange(const PreparedRequest& request,
                                                          std::uint64_t seed, std::uint64_t first,
                                                          std::uint64_t count,
                                                          unsigned threads) const {
  std::vector<SceneResult> results;
  sampleSceneRange(request, seed, first, count, threads, results);
  return results;
}

void SceneGenerator::sampleSceneRange(const PreparedRequest& request, std::uint64_t seed,
                                      std::uint64_t first, std::uint64_t count, unsigned threads,
                                      std::vector<SceneResult>& results,
                                      SampleProgress* progress) const {
  checkSceneRange(first, count);
  results.resize(count);
  sampleInto(request, seed, first, count, threads, results.data(), progress);
}

bool SceneGenerator::sampleSceneRangeOrGiveUp(const PreparedRequest& request, std::uint64_t seed,
                                              std::uint64_t first, std::uint64_t count,
                                              unsigned threads, std::uint64_t probe,
                                              std::vector<SceneResult>& results,
                                              SampleProgress* progress) const {
  checkSceneRange(first, count);
  results.resize(count);
  if (probe == 0 || probe >= count) {
    sampleInto(request, seed, first, count, threads, results.data(), progress);
    return false;
  }
  // The probe scenes are the first ones of the range, so the answer does not depend on timing.
  sampleInto(request, seed, first, probe, threads, results.data(), progress);
  // Cancelled probe scenes failed for another reason than the request: not hopeless.
  const bool hopeless =
      std::none_of(results.begin(), results.begin() + probe,
                   [](const SceneResult& r) { return r.success || wasCancelled(r); });
  if (hopeless) {
    results.resize(probe);
    return true;
  }
  sampleInto(request, seed, first + probe, count - probe, threads, results.data() + probe,
             progress);
  return false;
}

void SceneGenerator::sampleInto(const PreparedRequest& request, std::uint64_t seed,
                                std::uint64_t first, std::uint64_t count, unsigned threads,
                                SceneResult* results, SampleProgress* progress) const {
  if (threads == 0) {
    threads = std::max(1u, std::thread::hardware_concurrency());
  }
  threads =
      static_cast<unsigned>(std::min<std::uint64_t>(threads, std::max<std::uint64_t>(count, 1)));
  if (request.physicsModel && count > 0) {
    // Each simulating thread holds MuJoCo data of its own: as many as the memory allows.
    threads = request.physicsModel->simulatingThreads(threads);
  }
  // The next scene to take, alone on its line: the threads write it for each chunk, and the
  // locals beside it are read on every scene.
  struct alignas(detail::kCacheLine) {
    std::atomic<std::uint64_t> value{0};
  } next;
  const auto deadline = request.deadline;
  auto work = [&] {
    Worker worker(request, config_->collisionMargin, threads);
    worker.setDeadline(deadline);
    worker.setProgress(progress);
    // Small chunks keep the threads balanced when some scenes take many attempts. A simulated
    // scene takes milliseconds: one at a time, so that the threads finish the scenes nearly
    // in order (a cancelled range keeps the scenes before the first one not sampled).
    const std::uint64_t chunk = request.physicsModel ? 1 : Worker::kChunk;
    for (;;) {
      const auto [begin, end] = takeScenes(next.value, count, chunk, threads);
      if (begin == end) {
        break;
      }
      for (std::uint64_t b = begin; b < end; b += chunk) {
        const std::uint64_t e = std::min(end, b + chunk);
        worker.runChunk(seed, first + b, static_cast<std::size_t>(e - b), results + b);
      }
    }
  };
  // An exception in any worker (out of memory) stops the others and reaches the caller.
  detail::runOnThreads(threads, work, [&] { next.value = count; });
}

}  // namespace placement_samplers
