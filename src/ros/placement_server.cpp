#include "placement_samplers/ros/placement_server.hpp"

#include <ros/package.h>
#include <tf2_msgs/TFMessage.h>

#include <chrono>
#include <sstream>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/process/malloc_tuning.hpp"
#include "placement_samplers/sampling/failure_summary.hpp"
#include "placement_samplers/sampling/random.hpp"
#include "placement_samplers/text.hpp"
#include "placement_samplers/ros/conversions.hpp"
#include "placement_samplers/ros/node_diagnostics.hpp"
#include "placement_samplers/ros/param_reader.hpp"
#include "placement_samplers/ros/reconfigure.hpp"
#include "placement_samplers/ros/region_handles.hpp"
#include "placement_samplers/ros/sample_action.hpp"
#include "placement_samplers/ros/scene_markers.hpp"
#include "placement_samplers/ros/validation_service.hpp"
#include "ros/thread_priority.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

/// The configuration of a parameter tree; urdf_param objects read their URDF from the
/// parameter server (names resolved as any ROS name: relative to the node's namespace, ~ =
/// private).
std::shared_ptr<const SceneGenerator> buildGenerator(const ConfigNode& tree) {
  BuildOptions options;
  // urdf_param and mjcf_param: names resolved as any ROS name.
  const auto textParam = [](const char* what) {
    return [what](const std::string& name) {
      std::string text;
      if (!ros::param::get(name, text)) {
        throw ConfigError("parameter '" + ros::names::resolve(name) +
                          "' does not exist or does not hold " + what + " text");
      }
      return text;
    };
  };
  // package:// URIs through ROS's own lookup (rospack) rather than the core's stand-in.
  options.packageResolver = [](const std::string& package) {
    return ros::package::getPath(package);
  };
  options.urdfParam = textParam("URDF");
  options.mjcfParam = textParam("MJCF");
  return std::make_shared<const SceneGenerator>(buildSceneConfig(tree, options));
}

std::string joined(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) {
    out += (out.empty() ? "" : "; ") + p;
  }
  return out;
}

}  // namespace

PlacementServer::PlacementServer(const ros::NodeHandle& privateHandle)
    : privateHandle_(privateHandle), lightHandle_(privateHandle) {
  lightHandle_.setCallbackQueue(&lightQueue_);
  // "/robot1/placement_server" -> "robot1/placement_server/": tf2 frame names have no leading
  // slash, and two nodes never share a frame.
  defaultTfPrefix_ = ros::this_node::getName();
  while (!defaultTfPrefix_.empty() && defaultTfPrefix_.front() == '/') {
    defaultTfPrefix_.erase(0, 1);
  }
  defaultTfPrefix_ += '/';
}

PlacementServer::~PlacementServer() {
  // The light thread runs the components' callbacks: it stops first, then the components (the
  // action cancels its goals and waits for them).
  if (lightSpinner_) {
    lightSpinner_->stop();
  }
  action_.reset();
  handles_.reset();
  reconfigure_.reset();
  diagnostics_.reset();
  {
    std::lock_guard<std::mutex> lock(pendingMutex_);
    stopping_ = true;
  }
  pendingReady_.notify_all();
  for (std::thread* t : {&publisher_, &watcher_}) {
    if (t->joinable()) {
      t->join();
    }
  }
}

void PlacementServer::start(const ros::WallDuration& masterPeriod) {
  XmlRpc::XmlRpcValue tree = readParameterTree(privateHandle_);
  auto generator = buildGenerator(toConfigNode(tree, privateHandle_.getNamespace()));
  const SceneConfig& config = generator->config();
  seedStream_.seed(config.seed != 0 ? config.seed : randomSeed());
  threads_ = config.threads;
  {
    std::lock_guard<std::mutex> lock(generatorMutex_);
    generator_ = generator;
  }
  {
    std::lock_guard<std::mutex> lock(publishMutex_);
    tfStatic_ = config.tfStatic;
    tfRate_ = config.tfRate;
  }
  for (const std::string& warning : config.warnings) {
    ROS_WARN_STREAM(ros::this_node::getName() << ": " << warning);
  }
  advertise();
  publisher_ = std::thread(&PlacementServer::publishLoop, this);
  diagnostics_ = std::make_unique<NodeDiagnostics>(threads_);
  diagnostics_->served(treeDigest(tree), false);
  watcher_ = std::thread(&PlacementServer::watchLoop, this, masterPeriod);
  startLive(generator);
  // Last: the light thread runs the callbacks of every component started above.
  lightSpinner_ = std::make_unique<ros::AsyncSpinner>(1, &lightQueue_);
  lightSpinner_->start();
  ROS_INFO_STREAM(ros::this_node::getName()
                  << ": " << countText(config.objects.size(), "object") << ", "
                  << countText(config.fixtures.size(), "fixture") << "; serving "
                  << sampleService_.getService() << "; frames "
                  << config.tfPrefix.value_or(defaultTfPrefix_) << "<name> on "
                  << (config.tfStatic ? "/tf_static" : "/tf"));
}

std::shared_ptr<const SceneGenerator> PlacementServer::generator() const {
  std::lock_guard<std::mutex> lock(generatorMutex_);
  return generator_;
}

std::uint64_t PlacementServer::nextSeed() {
  std::lock_guard<std::mutex> lock(seedMutex_);
  std::uint64_t seed = 0;
  while (seed == 0) {
    seed = seedStream_();
  }
  return seed;
}

bool PlacementServer::sample(SamplePlacements::Request& request,
                             SamplePlacements::Response& response) {
  CallOptions options;
  answer(request, response, options);
  return true;
}

void PlacementServer::answer(const SamplePlacements::Request& request,
                             SamplePlacements::Response& response, CallOptions& options) {
  lowerThreadPriority();
  const auto started = std::chrono::steady_clock::now();
  CallRecord record;
  diagnostics_->callStarted();
  // Every error becomes an answer: roscpp would turn an exception into a bare failure.
  try {
    const std::shared_ptr<const SceneGenerator> generator = this->generator();
    const SceneConfig& config = generator->config();
    response.frame_id = config.frameId;
    const std::uint32_t count = std::max<std::uint32_t>(request.num_scenes, 1);
    SampleRequest sampleRequest = toSampleRequest(request);
    // A goal's client sees its progress and can cancel it: only a scene is bounded.
    (options.goal ? sampleRequest.maxSceneSeconds : sampleRequest.maxSeconds) =
        config.maxRequestSeconds;
    PreparedRequest prepared = generator->prepare(sampleRequest);
    try {
      generator->checkRequestSize(prepared, count);  // refused before any scene is sampled
    } catch (const RequestError&) {
      record.refusedForSize = true;
      throw;
    }
    const std::uint64_t placements = count * generator->placementsPerScene(prepared);
    const std::uint64_t seed = request.seed != 0 ? request.seed : nextSeed();
    response.seed = seed;
    // Threads pay off only for large batches (or a few simulated scenes, milliseconds each);
    // the answer is the same either way.
    const bool simulated = prepared.physics.mode != PhysicsMode::None;
    const unsigned threads = count >= 256 || (simulated && count >= 8) ? 0 : 1;
    std::vector<SceneResult> scenes;
    const bool gaveUp =
        generator->sampleSceneRangeOrGiveUp(prepared, seed, request.first_scene, count, threads,
                                            kGiveUpProbeScenes, scenes, options.progress);
    if (placements >= kTrimAfterPlacements) {
      scheduleTrim(placements);
    }
    // Cancelled: the scenes before the first one not sampled, so that a call from
    // first_scene + their number continues exactly (other threads' later scenes go).
    const auto cut = std::find_if(scenes.begin(), scenes.end(), wasCancelled);
    options.cancelled = cut != scenes.end();
    scenes.erase(cut, scenes.end());

    FailureSummary failures;
    response.scenes.reserve(scenes.size());
    for (const SceneResult& scene : scenes) {
      response.scenes.push_back(toSceneMsg(scene));
      failures.add(scene);
      record.sceneFailed.push_back(!scene.success);
    }
    response.success = failures.failed() == 0 && !options.cancelled;
    if (options.cancelled) {
      response.message = "cancelled after " + std::to_string(scenes.size()) + " of " +
                         countText(count, "scene") +
                         (failures.failed() != 0 ? "; " + failures.message(scenes.size()) : "");
    } else if (gaveUp) {
      response.message = "gave up: the first " + std::to_string(scenes.size()) + " of " +
                         std::to_string(count) + " scenes all failed, the rest were not sampled; " +
                         failures.message(scenes.size());
    } else if (!response.success) {
      response.message = failures.message(count);
    } else {
      response.message = joined(prepared.notes);
      if (!request.dry_run) {
        show(generator, std::move(prepared), std::move(scenes.front()), seed, request.sampler,
             response);
      }
    }
  } catch (const std::exception& e) {
    response.success = false;
    response.message = e.what();
    response.scenes.clear();
    record.error = e.what();
  }
  if (!response.success && record.error.empty() && !options.cancelled) {
    record.error = response.message;
  }
  record.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  diagnostics_->callFinished(record);
}

void PlacementServer::show(const std::shared_ptr<const SceneGenerator>& generator,
                           PreparedRequest prepared, SceneResult scene, std::uint64_t seed,
                           const std::string& sampler, SamplePlacements::Response& response) {
  if (beforeShowHook_) {
    beforeShowHook_();
  }
  bool current = false;
  {
    // Under pendingMutex_: a reload swaps the generator before it clears what is pending, so
    // a scene of the old configuration is either cleared or never queued.
    std::lock_guard<std::mutex> lock(pendingMutex_);
    current = this->generator() == generator;
    if (current) {
      pending_ = ShownScene{generator, std::move(prepared), std::move(scene), seed, sampler};
    }
  }
  if (current) {
    pendingReady_.notify_all();
  } else {
    response.message =
        joined({response.message, "not shown: the configuration was reloaded during the call"});
  }
}

void PlacementServer::scheduleTrim(std::uint64_t placements) {
  // roscpp frees the request and the answer after the callback: the publishing thread trims a
  // little later.
  std::lock_guard<std::mutex> lock(pendingMutex_);
  trimPlacements_ = std::max(trimPlacements_, placements);
  trimAt_ = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
}

bool PlacementServer::validate(ValidatePlacements::Request& request,
                               ValidatePlacements::Response& response) {
  lowerThreadPriority();
  ros_interface::answerValidation(*generator(), request, response);  // never throws
  // A large request (refused or not) leaves roscpp's copy of it freed but kept by malloc.
  if (request.placements.size() + request.fixtures.size() >= kTrimAfterValidatedPoses) {
    scheduleTrim(kTrimAfterPlacements);
  }
  return true;
}

bool PlacementServer::reload(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  std::string message;
  try {
    XmlRpc::XmlRpcValue tree = readParameterTree(privateHandle_);
    response.success = serveTree(tree, true, message);
  } catch (const std::exception& e) {
    response.success = false;
    message = e.what();
    diagnostics_->reloadFailed(message);
  }
  if (response.success) {
    response.message = message;
    ROS_INFO_STREAM(ros::this_node::getName() << ": " << response.message);
  } else {
    response.message = "configuration refused, the previous one stays: " + message;
    ROS_ERROR_STREAM(ros::this_node::getName() << ": " << response.message);
  }
  return true;
}

bool PlacementServer::serveTree(XmlRpc::XmlRpcValue& tree, bool reload, std::string& message) {
  std::lock_guard<std::recursive_mutex> serving(serveMutex_);
  std::shared_ptr<const SceneGenerator> generator;
  try {
    generator = buildGenerator(toConfigNode(tree, privateHandle_.getNamespace()));
  } catch (const std::exception& e) {
    message = e.what();
    reload ? diagnostics_->reloadFailed(message) : diagnostics_->refused(message);
    return false;
  }
  const SceneConfig& config = generator->config();
  {
    std::lock_guard<std::mutex> lock(generatorMutex_);
    generator_ = generator;
  }
  {
    std::lock_guard<std::mutex> lock(publishMutex_);
    tfStatic_ = config.tfStatic;
    tfRate_ = config.tfRate;
  }
  {
    // The shown scene belongs to the old configuration: its frames and markers go.
    std::lock_guard<std::mutex> lock(pendingMutex_);
    pending_.reset();
    clearPending_ = true;
  }
  pendingReady_.notify_all();
  message = "configuration reloaded: " + countText(config.objects.size(), "object") + ", " +
            countText(config.fixtures.size(), "fixture");
  for (const std::string& warning : config.warnings) {
    message += "; warning: " + warning;
    ROS_WARN_STREAM(ros::this_node::getName() << ": " << warning);
  }
  if (config.threads != threads_) {
    message += "; threads " + std::to_string(config.threads) +
               " takes effect when the node restarts (serving with " + std::to_string(threads_) +
               ")";
  }
  diagnostics_->served(treeDigest(tree), reload);
  if (reconfigure_) {
    reconfigure_->show(config);
  }
  if (handles_) {
    handles_->show(generator);
  }
  return true;
}

}  // namespace ros_interface
}  // namespace placement_samplers
