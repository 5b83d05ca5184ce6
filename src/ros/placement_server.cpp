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
#include "placement_samplers/ros/param_reader.hpp"
#include "placement_samplers/ros/scene_markers.hpp"
#include "placement_samplers/ros/validation_service.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

/// The configuration in the parameters; urdf_param objects read their URDF from the parameter
/// server (names resolved as any ROS name: relative to the node's namespace, ~ = private).
std::shared_ptr<const SceneGenerator> loadGenerator(const ros::NodeHandle& privateHandle) {
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
  return std::make_shared<const SceneGenerator>(
      buildSceneConfig(readParameters(privateHandle), options));
}

tf2_msgs::TFMessage tfMessage(const std::vector<geometry_msgs::TransformStamped>& frames) {
  tf2_msgs::TFMessage message;
  message.transforms = frames;
  return message;
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
  if (lightSpinner_) {
    lightSpinner_->stop();
  }
}

void PlacementServer::start(const ros::WallDuration& masterPeriod) {
  auto generator = loadGenerator(privateHandle_);
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
  lightSpinner_ = std::make_unique<ros::AsyncSpinner>(1, &lightQueue_);
  lightSpinner_->start();
  publisher_ = std::thread(&PlacementServer::publishLoop, this);
  watcher_ = std::thread(&PlacementServer::watchLoop, this, masterPeriod);
  ROS_INFO_STREAM(ros::this_node::getName()
                  << ": " << countText(config.objects.size(), "object") << ", "
                  << countText(config.fixtures.size(), "fixture") << "; serving "
                  << sampleService_.getService() << "; frames "
                  << config.tfPrefix.value_or(defaultTfPrefix_) << "<name> on "
                  << (config.tfStatic ? "/tf_static" : "/tf"));
}

void PlacementServer::advertise() {
  std::lock_guard<std::mutex> lock(publishMutex_);
  // Dropping the old handles first unregisters them, so the new ones register afresh.
  sampleService_.shutdown();
  validateService_.shutdown();
  reloadService_.shutdown();
  pingService_.shutdown();
  markerPublisher_.shutdown();
  scenePublisher_.shutdown();
  tfPublisher_.shutdown();
  tfStaticPublisher_.shutdown();
  ros::NodeHandle global;
  tfPublisher_ = global.advertise<tf2_msgs::TFMessage>("/tf", 100);
  tfStaticPublisher_ = global.advertise<tf2_msgs::TFMessage>("/tf_static", 100, true);
  markerPublisher_ = privateHandle_.advertise<visualization_msgs::MarkerArray>("markers", 1, true);
  scenePublisher_ = privateHandle_.advertise<PlacedScene>("scene", 1, true);
  sampleService_ =
      privateHandle_.advertiseService("sample_placements", &PlacementServer::sample, this);
  validateService_ =
      privateHandle_.advertiseService("validate_placements", &PlacementServer::validate, this);
  reloadService_ = lightHandle_.advertiseService("reload", &PlacementServer::reload, this);
  pingService_ = lightHandle_.advertiseService("ping", &PlacementServer::ping, this);
  // Latched topics carry the current scene to whoever subscribes after a master restart.
  if (!shown_.markers.markers.empty()) {
    markerPublisher_.publish(shown_.markers);
  }
  if (shown_.scene) {
    scenePublisher_.publish(*shown_.scene);
  }
  if (tfStatic_ && !shown_.frames.empty()) {
    tfStaticPublisher_.publish(tfMessage(shown_.frames));
  }
}

void PlacementServer::watchLoop(ros::WallDuration period) {
  // A thread of its own: the check must run while every service thread is busy.
  bool up = true;
  const auto step = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(period.toSec()));
  std::unique_lock<std::mutex> lock(pendingMutex_);
  while (!stopping_) {
    // Shares the condition with the publishing thread: the predicate ignores its wake-ups.
    if (pendingReady_.wait_until(lock, std::chrono::steady_clock::now() + step,
                                 [this] { return stopping_; })) {
      return;
    }
    lock.unlock();
    const bool now = ros::master::check();
    if (now && !up) {
      ROS_WARN("placement_server: the master is back; registering services and topics again");
      advertise();
    } else if (!now && up) {
      ROS_WARN("placement_server: lost the master; waiting for it to come back");
    }
    up = now;
    lock.lock();
  }
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
  // Every error becomes an answer: roscpp would turn an exception into a bare failure.
  try {
    const std::shared_ptr<const SceneGenerator> generator = this->generator();
    const SceneConfig& config = generator->config();
    response.frame_id = config.frameId;
    const std::uint32_t count = std::max<std::uint32_t>(request.num_scenes, 1);
    SampleRequest sampleRequest = toSampleRequest(request);
    sampleRequest.maxSeconds = config.maxRequestSeconds;
    PreparedRequest prepared = generator->prepare(sampleRequest);
    generator->checkRequestSize(prepared, count);  // refused before any scene is sampled
    const std::uint64_t placements = count * generator->placementsPerScene(prepared);
    const std::uint64_t seed = request.seed != 0 ? request.seed : nextSeed();
    response.seed = seed;
    // Threads pay off only for large batches (or a few simulated scenes, milliseconds each);
    // the answer is the same either way.
    const bool simulated = prepared.physics.mode != PhysicsMode::None;
    const unsigned threads = count >= 256 || (simulated && count >= 8) ? 0 : 1;
    std::vector<SceneResult> scenes =
        generator->sampleSceneRange(prepared, seed, request.first_scene, count, threads);
    if (placements >= kTrimAfterPlacements) {
      // roscpp frees the answer after this callback: the publishing thread trims a little later.
      std::lock_guard<std::mutex> lock(pendingMutex_);
      trimPlacements_ = std::max(trimPlacements_, placements);
      trimAt_ = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
    }

    FailureSummary failures;
    response.scenes.reserve(scenes.size());
    for (const SceneResult& scene : scenes) {
      response.scenes.push_back(toSceneMsg(scene));
      failures.add(scene);
    }
    response.success = failures.failed() == 0;
    if (!response.success) {
      response.message = failures.message(count);
    } else {
      response.message = joined(prepared.notes);
      if (!request.dry_run) {
        {
          std::lock_guard<std::mutex> lock(pendingMutex_);
          pending_ = ShownScene{generator, std::move(prepared), std::move(scenes.front()), seed,
                                request.sampler};
        }
        pendingReady_.notify_all();
      }
    }
  } catch (const std::exception& e) {
    response.success = false;
    response.message = e.what();
    response.scenes.clear();
  }
  return true;
}

bool PlacementServer::validate(ValidatePlacements::Request& request,
                               ValidatePlacements::Response& response) {
  ros_interface::answerValidation(*generator(), request, response);  // never throws
  return true;
}

PlacementServer::Shown PlacementServer::render(const ShownScene& shown) const {
  const SceneConfig& config = shown.generator->config();
  const std::string prefix = config.tfPrefix.value_or(defaultTfPrefix_);
  const ros::Time now = ros::Time::now();
  Shown out;
  out.frames = toTransforms(shown.scene, shown.request.fixtures, config.frameId, prefix, now);
  out.markers = makeSceneMarkers(shown.request, shown.scene, config.frameId, now);
  PlacedScene scene;
  scene.header.frame_id = config.frameId;
  scene.header.stamp = now;
  scene.seed = shown.seed;
  scene.sampler = shown.sampler;
  scene.tf_prefix = prefix;
  scene.placements = toSceneMsg(shown.scene).placements;
  for (const FixtureSpec& f : shown.request.fixtures) {
    scene.fixtures.push_back(toFixtureMsg(f));
  }
  out.scene = std::move(scene);
  return out;
}

void PlacementServer::sendFrames(bool restamp) {
  // Called with publishMutex_ held.
  if (shown_.frames.empty()) {
    return;
  }
  if (tfStatic_) {
    tfStaticPublisher_.publish(tfMessage(shown_.frames));
    return;
  }
  if (restamp) {
    const ros::Time now = ros::Time::now();
    for (auto& frame : shown_.frames) {
      frame.header.stamp = now;
    }
  }
  tfPublisher_.publish(tfMessage(shown_.frames));
}

void PlacementServer::publishLoop() {
  using Clock = std::chrono::steady_clock;
  Clock::time_point nextTick = Clock::now();
  std::unique_lock<std::mutex> lock(pendingMutex_);
  for (;;) {
    pendingReady_.wait_until(lock, nextTick,
                             [this] { return stopping_ || pending_ || clearPending_; });
    if (stopping_) {
      return;
    }
    std::optional<ShownScene> next = std::move(pending_);
    pending_.reset();
    const bool clear = clearPending_;
    clearPending_ = false;
    std::uint64_t trim = 0;
    if (trimPlacements_ > 0 && Clock::now() >= trimAt_) {
      trim = trimPlacements_;
      trimPlacements_ = 0;
    }
    lock.unlock();
    if (trim > 0) {
      trimAfterBatch(trim);
    }

    std::optional<Shown> rendered;
    if (next) {
      rendered = render(*next);
    }
    {
      std::lock_guard<std::mutex> publishLock(publishMutex_);
      if (rendered) {
        // Only the current scene's frames are held: frames of an older one are not re-sent.
        shown_ = std::move(*rendered);
        sendFrames(false);
        markerPublisher_.publish(shown_.markers);
        scenePublisher_.publish(*shown_.scene);
      } else if (clear) {
        shown_.frames.clear();
        shown_.markers = makeClearMarkers();
        markerPublisher_.publish(shown_.markers);
        if (tfStatic_) {
          tfStaticPublisher_.publish(tf2_msgs::TFMessage());
        }
      } else if (!tfStatic_) {
        sendFrames(true);
      }
    }
    const Clock::time_point now = Clock::now();
    if (now >= nextTick) {
      double rate = 10.0;
      {
        std::lock_guard<std::mutex> publishLock(publishMutex_);
        rate = tfRate_;
      }
      nextTick = now + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double>(1.0 / rate));
    }
    lock.lock();
  }
}

bool PlacementServer::reload(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  try {
    auto generator = loadGenerator(privateHandle_);
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
    response.success = true;
    response.message = "configuration reloaded: " + countText(config.objects.size(), "object") +
                       ", " + countText(config.fixtures.size(), "fixture");
    for (const std::string& warning : config.warnings) {
      response.message += "; warning: " + warning;
      ROS_WARN_STREAM(ros::this_node::getName() << ": " << warning);
    }
    if (config.threads != threads_) {
      response.message += "; threads " + std::to_string(config.threads) +
                          " takes effect when the node restarts (serving with " +
                          std::to_string(threads_) + ")";
    }
    ROS_INFO_STREAM(ros::this_node::getName() << ": " << response.message);
  } catch (const std::exception& e) {
    response.success = false;
    response.message = std::string("configuration refused, the previous one stays: ") + e.what();
    ROS_ERROR_STREAM(ros::this_node::getName() << ": " << response.message);
  }
  return true;
}

}  // namespace ros_interface
}  // namespace placement_samplers
