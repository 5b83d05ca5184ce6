#include "placement_samplers/sampling/scene_generator.hpp"

#include <algorithm>
#include <atomic>
#include <limits>
#include <thread>
#include <utility>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/text.hpp"
#include "sampling/cache_line.hpp"
#include "sampling/parallel.hpp"
#include "sampling/scene_worker.hpp"

namespace placement_samplers {

SceneGenerator::SceneGenerator(std::shared_ptr<const SceneConfig> config)
    : config_(std::move(config)) {
  if (!config_ || !config_->root) {
    throw std::invalid_argument("SceneGenerator needs a built configuration");
  }
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
