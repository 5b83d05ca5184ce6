#include "sampling/scene_physics.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace {

/// How far a gap between an offset and the geometry lets an object drop [m]: none when negative.
double drop(double gap) { return std::max(0.0, gap); }

}  // namespace

ScenePhysics::ScenePhysics(const SceneConfig& config, const PreparedRequest& request)
    : settings_(request.physics) {
  for (const FixtureSpec& f : request.fixtures) {
    keep_.push_back(f.object);
    fixtures_.push_back(PhysicsFixture{f.object.get(), f.position, f.orientation});
  }
  // The clearance each object is sampled with on purpose, which moved does not count: its
  // sampler's z_offset; placed on top, the gap by which its geometry ends above its bottom
  // offset (an MJCF bottom_site below the mesh) and, on a named reference, the gap by which that
  // one's top offset lies above its geometry; and its reference's clearance when that is an
  // object placed before it (a cup on a plate lifted by 1 cm drops with the plate). Gaps the
  // other way (geometry reaching past an offset) are no clearance: those objects start
  // overlapping, and MuJoCo's push counts.
  request.sampler->forEachUniform(
      request.reference, request.onTop,
      [&](const UniformRandomSampler& sampler, const Reference& reference, bool onTop) {
        if (sampler.params().hides) {
          return;  // hidden objects are far away, out of the scene
        }
        for (const ObjectPtr& object : sampler.objects()) {
          bool hidden = false;
          for (const std::string& name : config.hidden) {
            hidden = hidden || name == object->name;
          }
          if (hidden || bodyIndex_.count(object.get()) != 0) {
            continue;
          }
          double zOffset = sampler.params().zOffset + (onTop ? drop(object->bottomGap) : 0.0);
          if (reference.kind == Reference::Kind::Name) {
            for (const PhysicsBody& below : bodies_) {
              if (below.object->name == reference.name) {
                zOffset += below.zOffset + (onTop ? drop(below.object->topGap) : 0.0);
              }
            }
            for (const FixtureSpec& f : request.fixtures) {
              if (f.name == reference.name && onTop) {
                zOffset += drop(f.object->topGap);
              }
            }
          }
          bodyIndex_[object.get()] = static_cast<int>(bodies_.size());
          // Under resting: stable a placement points at the object in its pose: same body.
          for (const UniformRandomSampler::RestingChoice& c : sampler.restingChoices(*object)) {
            bodyIndex_[c.object] = static_cast<int>(bodies_.size());
          }
          const double density = object->density > 0.0 ? object->density : settings_.density;
          bodies_.push_back(PhysicsBody{object.get(), zOffset, density});
        }
      });
}

std::shared_ptr<const PhysicsModel> ScenePhysics::model() const {
  std::call_once(once_, [this] {
    model_ = std::make_shared<const PhysicsModel>(fixtures_, bodies_, settings_);
  });
  return model_;
}

int ScenePhysics::bodyOf(const ObjectModel* object) const {
  const auto found = bodyIndex_.find(object);
  return found == bodyIndex_.end() ? -1 : found->second;
}

unsigned ScenePhysics::simulatingThreads(unsigned threads) const {
  const std::uint64_t perThread = model()->worldBytes();
  const std::uint64_t cap = std::uint64_t{settings_.maxMemoryMb} << 20;
  // model() refused a model whose one simulation does not fit.
  return static_cast<unsigned>(std::max<std::uint64_t>(
      1, std::min<std::uint64_t>(threads, cap / std::max<std::uint64_t>(perThread, 1))));
}

std::uint64_t ScenePhysics::threadShare(unsigned threads) const {
  return (std::uint64_t{settings_.maxMemoryMb} << 20) / std::max(threads, 1u);
}

PhysicsStep::PhysicsStep(const ScenePhysics& physics, std::uint64_t maxBytes)
    : physics_(physics), world_(physics.model(), maxBytes) {}

PhysicsStatus PhysicsStep::run(SceneResult& result,
                               std::optional<std::chrono::steady_clock::time_point> deadline) {
  std::vector<ObjectPlacement>& placements = result.placements;
  poses_.assign(physics_.model()->bodyCount(), BodyPose());
  for (const ObjectPlacement& p : placements) {
    const int body = physics_.bodyOf(p.object);
    if (body >= 0) {
      poses_[static_cast<std::size_t>(body)] = BodyPose{p.position, p.orientation};
    }
  }
  PhysicsStatus status = PhysicsStatus::TimedOut;
  try {
    status = world_.simulate(poses_, outcomes_, deadline);
  } catch (const std::runtime_error& e) {
    result.success = false;
    result.message = std::string("physics: MuJoCo failed: ") + escapeText(e.what());
    return PhysicsStatus::TimedOut;
  }
  if (status == PhysicsStatus::TimedOut) {
    result.success = false;
    result.message = "not finished: the request ran out of time while simulating the scene";
    return status;
  }
  if (status == PhysicsStatus::TooLarge) {
    result.success = false;
    result.message = "physics: the scene has more contacts than MuJoCo's buffers of " +
                     std::to_string(world_.contactCapacity()) + " contacts hold, and twice as " +
                     "many would take more than this thread's share of physics_max_memory_mb (" +
                     std::to_string(world_.maxBytes()) + " bytes of its " +
                     std::to_string(physics_.settings().maxMemoryMb) + " MiB)";
    return PhysicsStatus::TimedOut;
  }
  result.simulated = true;
  result.stable = status == PhysicsStatus::Stable;
  result.physics.resize(placements.size());
  const bool settle = physics_.settings().mode == PhysicsMode::Settle;
  for (std::size_t k = 0; k < placements.size(); ++k) {
    ObjectPlacement& p = placements[k];
    const int body = physics_.bodyOf(p.object);
    if (body < 0) {
      result.physics[k] = PhysicsOutcome();
      result.physics[k].sampledPosition = p.position;
      result.physics[k].sampledOrientation = p.orientation;
      continue;
    }
    result.physics[k] = outcomes_[static_cast<std::size_t>(body)];
    if (settle) {
      p.position = poses_[static_cast<std::size_t>(body)].position;
      p.orientation = poses_[static_cast<std::size_t>(body)].orientation;
    }
  }
  if (status == PhysicsStatus::Diverged) {
    result.message =
        "physics: the simulation diverged (MuJoCo reset it), so the scene counts as unstable";
  }
  return status;
}

std::string PhysicsStep::unstableMessage(const SceneResult& result, std::uint32_t draws) {
  std::ostringstream out;
  out << "physics: no stable scene in " << draws << (draws == 1 ? " draw" : " draws");
  std::size_t worst = result.physics.size();
  for (std::size_t k = 0; k < result.physics.size(); ++k) {
    const PhysicsOutcome& o = result.physics[k];
    if (worst == result.physics.size() || o.fallen > result.physics[worst].fallen ||
        (o.fallen == result.physics[worst].fallen && o.moved > result.physics[worst].moved)) {
      worst = k;
    }
  }
  if (worst < result.physics.size()) {
    const PhysicsOutcome& o = result.physics[worst];
    out << "; in the last, " << quoteText(std::string(result.placements[worst].name)) << " moved "
        << o.moved << " m and turned " << o.turned << " rad" << (o.fallen ? " and fell" : "");
  }
  return out.str();
}

}  // namespace placement_samplers
