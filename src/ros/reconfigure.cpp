#include "placement_samplers/ros/reconfigure.hpp"

#include <XmlRpcValue.h>

#include "placement_samplers/collision/make_collision_checker.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

bool sameKnobs(const PlacementServerConfig& a, const PlacementServerConfig& b) {
  return a.collision_check == b.collision_check && a.collision_margin == b.collision_margin &&
         a.max_attempts == b.max_attempts && a.physics == b.physics &&
         a.physics_seconds == b.physics_seconds &&
         a.physics_position_tolerance == b.physics_position_tolerance &&
         a.physics_rotation_tolerance == b.physics_rotation_tolerance && a.tf_rate == b.tf_rate &&
         a.max_request_seconds == b.max_request_seconds;
}

}  // namespace

PlacementServerConfig knobsOf(const SceneConfig& config) {
  PlacementServerConfig knobs = PlacementServerConfig::__getDefault__();
  knobs.collision_check = collisionModeName(config.collisionCheck);
  knobs.collision_margin = config.collisionMargin;
  // dynamic_reconfigure's integers are 32-bit signed, as rosparam's.
  knobs.max_attempts = static_cast<int>(std::min<std::uint32_t>(config.maxAttempts, 0x7fffffff));
  knobs.physics = physicsModeName(config.physics.mode);
  knobs.physics_seconds = config.physics.seconds;
  knobs.physics_position_tolerance = config.physics.positionTolerance;
  knobs.physics_rotation_tolerance = config.physics.rotationTolerance;
  knobs.tf_rate = config.tfRate;
  knobs.max_request_seconds = config.maxRequestSeconds;
  return knobs;
}

void setKnobs(const PlacementServerConfig& knobs, XmlRpc::XmlRpcValue& tree) {
  tree["collision_check"] = knobs.collision_check;
  tree["collision_margin"] = knobs.collision_margin;
  tree["max_attempts"] = knobs.max_attempts;
  tree["physics"] = knobs.physics;
  tree["physics_seconds"] = knobs.physics_seconds;
  tree["physics_position_tolerance"] = knobs.physics_position_tolerance;
  tree["physics_rotation_tolerance"] = knobs.physics_rotation_tolerance;
  tree["tf_rate"] = knobs.tf_rate;
  tree["max_request_seconds"] = knobs.max_request_seconds;
}

Reconfigure::Reconfigure(const ros::NodeHandle& handle, Apply apply)
    : handle_(handle), apply_(std::move(apply)) {}

void Reconfigure::start(const SceneConfig& served) {
  boost::recursive_mutex::scoped_lock lock(mutex_);
  served_ = knobsOf(served);
  restart();
}

void Reconfigure::restart() {
  boost::recursive_mutex::scoped_lock lock(mutex_);
  server_.reset();
  // The server reads each knob's parameter and writes them all back; then it shows the knobs
  // served (the same, unless the parameters went with a master), so its first call of the
  // callback changes nothing.
  server_ = std::make_unique<dynamic_reconfigure::Server<PlacementServerConfig>>(mutex_, handle_);
  server_->updateConfig(served_);
  server_->setCallback(
      [this](PlacementServerConfig& config, std::uint32_t level) { onChange(config, level); });
}

void Reconfigure::show(const SceneConfig& served) {
  boost::recursive_mutex::scoped_lock lock(mutex_);
  served_ = knobsOf(served);
  // Inside onChange() the server shows the values the callback leaves itself.
  if (server_ && !inCallback_) {
    server_->updateConfig(served_);
  }
}

void Reconfigure::onChange(PlacementServerConfig& config, std::uint32_t) {
  if (sameKnobs(config, served_)) {
    return;  // the start-up call, or nothing changed
  }
  std::string error;
  inCallback_ = true;
  const bool applied = apply_(config, error);
  inCallback_ = false;
  if (!applied) {
    // The answer and the parameter server keep the values in use.
    ROS_ERROR_STREAM(ros::this_node::getName()
                     << ": dynamic_reconfigure: refused, the previous values stay: " << error);
    config = served_;
    return;
  }
  served_ = config;
}

}  // namespace ros_interface
}  // namespace placement_samplers
