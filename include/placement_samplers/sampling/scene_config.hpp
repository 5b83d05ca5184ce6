#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "placement_samplers/collision/collision_checker.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/geometry/object_model.hpp"
#include "placement_samplers/physics/physics_settings.hpp"
#include "placement_samplers/sampling/sequential_composite_sampler.hpp"

namespace placement_samplers {

/// Something already in the scene: checked against, never moved.
struct FixtureSpec {
  std::string name;        ///< unique among fixtures and objects; its tf frame name
  std::string objectName;  ///< the configured object it takes its geometry from ("" for a shape)
  ObjectPtr object;        ///< geometry, with bounds derived under the fixture's orientation
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

/// A validated, immutable configuration: what the builder produces from one schema, for the CLI
/// and the node alike.
struct SceneConfig {
  std::string frameId = "world";  ///< parent frame of every pose
  /// Child frame of object NAME is tfPrefix + NAME; unset: the node uses its own name and
  /// namespace ("robot1/placement_server/"), so two nodes never share a frame.
  std::optional<std::string> tfPrefix;
  std::uint64_t seed = 0;  ///< 0 = a fresh seed from std::random_device
  CollisionMode collisionCheck = CollisionMode::Radius;
  double collisionMargin = 0.0;       ///< clearance in the exact modes [m]
  std::uint32_t maxAttempts = 5000;   ///< default samples per object
  std::vector<ObjectPtr> objects;     ///< every configured object, in configuration order
  std::vector<FixtureSpec> fixtures;  ///< configured fixtures
  std::vector<std::string> hidden;    ///< objects placed far away by hide()
  std::shared_ptr<SequentialCompositeSampler> root;  ///< the root composite, named "root"

  // Settings of the node's service (the CLI has flags of its own).
  unsigned threads = 16;                      ///< service calls served at once
  std::uint32_t maxScenesPerRequest = 10000;  ///< larger num_scenes are refused
  double maxRequestSeconds = 10.0;            ///< a request stops after this long [s]
  /// Requests with more fixtures are refused (SceneGenerator::prepare).
  std::uint32_t maxFixturesPerRequest = limits::kDefaultFixturesPerRequest;
  /// Requests whose scenes x placed objects exceed it are refused
  /// (SceneGenerator::checkAnswerSize, called by sampleScenes).
  std::uint64_t maxPlacementsPerRequest = limits::kDefaultPlacementsPerRequest;
  /// Frames on the latched /tf_static (they stay with every listener) instead of on /tf,
  /// re-sent at tfRate (frames of an older scene vanish).
  bool tfStatic = false;
  double tfRate = 10.0;  ///< how often the current scene's frames are sent on /tf [Hz]

  /// MuJoCo's check or settling of each sampled scene (README, "Physics").
  PhysicsSettings physics;

  /// What the builder found suspicious but accepted (objects that nothing places, ...): the
  /// CLI prints them on stderr, the node logs them as warnings.
  std::vector<std::string> warnings;

  /// The configured object called @p name, or nullptr. Constant time once indexObjects() ran
  /// after the last change to @ref objects (the builder does), linear otherwise.
  const ObjectModel* findObject(std::string_view name) const;
  ObjectPtr findObjectPtr(std::string_view name) const;
  /// Indexes @ref objects by name for findObject().
  void indexObjects();

 private:
  std::unordered_map<std::string, std::size_t> objectIndex_;
};

/// Name of the root composite sampler.
constexpr const char* kRootSamplerName = "root";

/// True for names made of [A-Za-z0-9_-], at least one character: valid in tf frames.
bool isValidName(const std::string& name);

}  // namespace placement_samplers
