#include "placement_samplers/ros/placement_server.hpp"

#include <sstream>

#include "placement_samplers/config_builder.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/random.hpp"
#include "placement_samplers/ros/conversions.hpp"
#include "placement_samplers/ros/param_reader.hpp"
#include "placement_samplers/ros/scene_markers.hpp"

namespace placement_samplers {
namespace ros_interface {

PlacementServer::PlacementServer(const ros::NodeHandle& privateHandle)
    : privateHandle_(privateHandle) {}

PlacementServer::~PlacementServer() {
  {
    std::lock_guard<std::mutex> lock(pendingMutex_);
    stopping_ = true;
  }
  pendingReady_.notify_one();
  if (publisher_.joinable()) {
    publisher_.join();
  }
}

void PlacementServer::publishLoop() {
  for (;;) {
    PendingScene next;
    {
      std::unique_lock<std::mutex> lock(pendingMutex_);
      pendingReady_.wait(lock, [this] { return stopping_ || pending_.has_value(); });
      if (stopping_) {
        return;
      }
      next = std::move(*pending_);
      pending_.reset();
    }
    publish(next);
  }
}

namespace {

/// The configuration in the parameters; urdf_param objects read their URDF from the parameter
/// server (names resolved as any ROS name: relative to the node's namespace, ~ = private).
std::shared_ptr<const SceneGenerator> loadGenerator(const ros::NodeHandle& privateHandle) {
  BuildOptions options;
  options.urdfParam = [](const std::string& name) {
    std::string text;
    if (!ros::param::get(name, text)) {
      throw ConfigError("parameter '" + ros::names::resolve(name) +
                        "' does not exist or does not hold URDF text");
    }
    return text;
  };
  return std::make_shared<const SceneGenerator>(
      buildSceneConfig(readParameters(privateHandle), options));
}

}  // namespace

void PlacementServer::start() {
  auto generator = loadGenerator(privateHandle_);
  const std::uint64_t seed = generator->config().seed;
  seedStream_.seed(seed != 0 ? seed : randomSeed());
  {
    std::lock_guard<std::mutex> lock(generatorMutex_);
    generator_ = generator;
  }
  advertise();
  publisher_ = std::thread(&PlacementServer::publishLoop, this);
  ROS_INFO_STREAM("placement_server: " << generator->config().objects.size() << " objects, "
                                       << generator->config().fixtures.size()
                                       << " fixtures; serving " << sampleService_.getService());
}

void PlacementServer::advertise() {
  std::lock_guard<std::mutex> lock(publishMutex_);
  // Dropping the old handles first unregisters them, so the new ones register afresh.
  sampleService_.shutdown();
  reloadService_.shutdown();
  pingService_.shutdown();
  markerPublisher_.shutdown();
  broadcaster_.reset();
  broadcaster_ = std::make_unique<tf2_ros::StaticTransformBroadcaster>();
  markerPublisher_ = privateHandle_.advertise<visualization_msgs::MarkerArray>("markers", 1, true);
  sampleService_ =
      privateHandle_.advertiseService("sample_placements", &PlacementServer::sample, this);
  reloadService_ = privateHandle_.advertiseService("reload", &PlacementServer::reload, this);
  pingService_ = privateHandle_.advertiseService("ping", &PlacementServer::ping, this);
  if (!frames_.empty()) {
    std::vector<geometry_msgs::TransformStamped> frames;
    for (const auto& entry : frames_) {
      frames.push_back(entry.second);
    }
    broadcaster_->sendTransform(frames);
    markerPublisher_.publish(lastMarkers_);
  }
}

void PlacementServer::watchMaster(const ros::WallDuration& period) {
  masterTimer_ = privateHandle_.createWallTimer(period, &PlacementServer::checkMaster, this);
}

void PlacementServer::checkMaster(const ros::WallTimerEvent&) {
  const bool up = ros::master::check();
  if (up && !masterUp_) {
    ROS_WARN("placement_server: the master is back; registering services and topics again");
    advertise();
  } else if (!up && masterUp_) {
    ROS_WARN("placement_server: lost the master; waiting for it to come back");
  }
  masterUp_ = up;
}

unsigned PlacementServer::threads() const { return generator()->config().threads; }

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
    if (count > config.maxScenesPerRequest) {
      throw RequestError("num_scenes " + std::to_string(count) +
                         " exceeds max_scenes_per_request (" +
                         std::to_string(config.maxScenesPerRequest) + ")");
    }
    SampleRequest sampleRequest = toSampleRequest(request);
    sampleRequest.maxSeconds = config.maxRequestSeconds;
    PreparedRequest prepared = generator->prepare(sampleRequest);
    const std::uint64_t seed = request.seed != 0 ? request.seed : nextSeed();
    response.seed = seed;
    // Threads pay off only for large batches; the answer is the same either way.
    const unsigned threads = count >= 256 ? 0 : 1;
    std::vector<SceneResult> scenes = generator->sampleScenes(prepared, seed, count, threads);

    response.success = true;
    std::size_t failed = 0;
    response.scenes.reserve(scenes.size());
    for (const SceneResult& scene : scenes) {
      response.scenes.push_back(toSceneMsg(scene));
      if (!scene.success) {
        if (failed == 0) {
          response.message = count == 1
                                 ? scene.message
                                 : "scene " + std::to_string(scene.index) + ": " + scene.message;
        }
        ++failed;
      }
    }
    if (failed > 0) {
      response.success = false;
      if (failed > 1) {
        response.message +=
            " (" + std::to_string(failed) + " of " + std::to_string(count) + " scenes failed)";
      }
    } else if (!request.dry_run) {
      {
        std::lock_guard<std::mutex> lock(pendingMutex_);
        pending_ = PendingScene{generator, std::move(prepared), std::move(scenes.front())};
      }
      pendingReady_.notify_one();
    }
  } catch (const std::exception& e) {
    response.success = false;
    response.message = e.what();
    response.scenes.clear();
  }
  return true;
}

void PlacementServer::publish(const PendingScene& pending) {
  const SceneConfig& config = pending.generator->config();
  const PreparedRequest& request = pending.request;
  const SceneResult& scene = pending.scene;
  const ros::Time now = ros::Time::now();
  std::vector<geometry_msgs::TransformStamped> frames =
      toTransforms(scene, request.fixtures, config.frameId, config.tfPrefix, now);
  visualization_msgs::MarkerArray markers = makeSceneMarkers(request, scene, config.frameId, now);
  std::lock_guard<std::mutex> lock(publishMutex_);
  broadcaster_->sendTransform(frames);
  markerPublisher_.publish(markers);
  for (const auto& frame : frames) {
    frames_[frame.child_frame_id] = frame;
  }
  lastMarkers_ = std::move(markers);
}

bool PlacementServer::reload(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  try {
    auto generator = loadGenerator(privateHandle_);
    {
      std::lock_guard<std::mutex> lock(generatorMutex_);
      generator_ = generator;
    }
    response.success = true;
    response.message =
        "configuration reloaded: " + std::to_string(generator->config().objects.size()) +
        " objects, " + std::to_string(generator->config().fixtures.size()) + " fixtures";
    ROS_INFO_STREAM("placement_server: " << response.message);
  } catch (const std::exception& e) {
    response.success = false;
    response.message = std::string("configuration refused, the previous one stays: ") + e.what();
    ROS_ERROR_STREAM("placement_server: " << response.message);
  }
  return true;
}

}  // namespace ros_interface
}  // namespace placement_samplers
