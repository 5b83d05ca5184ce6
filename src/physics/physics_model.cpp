#include "placement_samplers/physics/physics_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>
#include <stdexcept>

#include "geometry/mujoco_compile.hpp"
#include "physics/physics_mjcf.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {

struct PhysicsModel::Impl {
  PhysicsSettings settings;
  std::vector<PhysicsBody> bodies;
  std::string mjcf;
  detail::MujocoModelPtr model;
  std::vector<int> qposAddress;  ///< of each body's free joint: x, y, z, qw, qx, qy, qz
  /// The lowest support: the ground plane, else the lowest fixture bottom [m]; unset = none.
  std::optional<double> support;
};

PhysicsModel::PhysicsModel(const std::vector<PhysicsFixture>& fixtures,
                           const std::vector<PhysicsBody>& bodies, const PhysicsSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.settings = settings;
  d.bodies = bodies;
  d.mjcf = detail::physicsMjcf(fixtures, bodies, settings);
  const detail::MujocoVfsPtr vfs = detail::makeVfs();
  constexpr const char* kName = "placement_samplers_scene.xml";
  try {
    detail::addVfsFile(*vfs, kName, d.mjcf);
    d.model = detail::compileMjcf(kName, vfs.get());
  } catch (const std::runtime_error& e) {
    throw RequestError(std::string("physics: MuJoCo could not build the scene: ") +
                       escapeText(e.what()));
  }
  const mjModel& m = *d.model;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const int body = mj_name2id(&m, mjOBJ_BODY, detail::physicsBodyName(i).c_str());
    if (body < 0 || m.body_jntnum[body] != 1) {
      throw std::logic_error("physics: generated body " + std::to_string(i) + " is missing");
    }
    d.qposAddress.push_back(m.jnt_qposadr[m.body_jntadr[body]]);
  }
  d.support = settings.groundZ;
  if (!d.support) {
    for (const PhysicsFixture& f : fixtures) {
      const double bottom = f.position.z() + shapesBounds(f.object->shapes, f.orientation).bottomZ;
      d.support = std::min(d.support.value_or(bottom), bottom);
    }
  }
}

PhysicsModel::~PhysicsModel() = default;

const PhysicsSettings& PhysicsModel::settings() const { return impl_->settings; }
std::size_t PhysicsModel::bodyCount() const { return impl_->bodies.size(); }
const std::string& PhysicsModel::mjcf() const { return impl_->mjcf; }

double PhysicsModel::mass(std::size_t body) const {
  const mjModel& m = *impl_->model;
  return m.body_mass[mj_name2id(&m, mjOBJ_BODY, detail::physicsBodyName(body).c_str())];
}

struct PhysicsWorld::Impl {
  std::shared_ptr<const PhysicsModel> model;
  detail::MujocoDataPtr data;
};

PhysicsWorld::PhysicsWorld(std::shared_ptr<const PhysicsModel> model)
    : impl_(std::make_unique<Impl>()) {
  if (!model) {
    throw std::invalid_argument("PhysicsWorld needs a model");
  }
  detail::installMujocoHandlers();
  impl_->data.reset(mj_makeData(model->impl_->model.get()));
  if (!impl_->data) {
    throw std::bad_alloc();
  }
  impl_->model = std::move(model);
}

PhysicsWorld::~PhysicsWorld() = default;

namespace {

/// Angle of the rotation from @p a to @p b [rad], in [0, pi].
double angleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  const Eigen::Quaterniond d = a.conjugate() * b;
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
}

}  // namespace

PhysicsStatus PhysicsWorld::simulate(
    std::vector<BodyPose>& poses, std::vector<PhysicsOutcome>& outcomes,
    std::optional<std::chrono::steady_clock::time_point> deadline) {
  const PhysicsModel::Impl& model = *impl_->model->impl_;
  const mjModel* m = model.model.get();
  mjData* d = impl_->data.get();
  const std::size_t n = model.bodies.size();
  if (poses.size() != n) {
    throw std::invalid_argument("PhysicsWorld::simulate: " + std::to_string(poses.size()) +
                                " poses for " + std::to_string(n) + " bodies");
  }
  // From reset data (zero velocities, no warm start): the same poses give the same answer
  // whatever this thread simulated before.
  mj_resetData(m, d);
  std::memset(d->warning, 0, sizeof(d->warning));
  for (std::size_t i = 0; i < n; ++i) {
    mjtNum* q = d->qpos + model.qposAddress[i];
    const BodyPose& p = poses[i];
    // Released at rest where it would land, its clearance taken away: MuJoCo 2.2.2's convex
    // contacts kick an object that drops onto a box or cylinder near its edge (docs/design.md).
    q[0] = p.position.x();
    q[1] = p.position.y();
    q[2] = p.position.z() - model.bodies[i].zOffset;
    q[3] = p.orientation.w();
    q[4] = p.orientation.x();
    q[5] = p.orientation.y();
    q[6] = p.orientation.z();
  }
  mj_forward(m, d);
  const std::uint64_t steps = model.settings.steps();
  for (std::uint64_t s = 0; s < steps; ++s) {
    if ((s & 63u) == 63u && deadline && std::chrono::steady_clock::now() > *deadline) {
      return PhysicsStatus::TimedOut;
    }
    mj_step(m, d);
  }
  outcomes.resize(n);
  // MuJoCo resets the state on a bad acceleration and drops contacts beyond its buffers: the
  // poses then mean nothing.
  if (d->warning[mjWARN_BADQACC].number > 0 || d->warning[mjWARN_BADQPOS].number > 0 ||
      d->warning[mjWARN_BADQVEL].number > 0 || d->warning[mjWARN_CONTACTFULL].number > 0 ||
      d->warning[mjWARN_CNSTRFULL].number > 0) {
    for (std::size_t i = 0; i < n; ++i) {
      outcomes[i] = PhysicsOutcome();
      outcomes[i].sampledPosition = poses[i].position;
      outcomes[i].sampledOrientation = poses[i].orientation;
    }
    return PhysicsStatus::Diverged;
  }
  const PhysicsSettings& settings = model.settings;
  bool stable = true;
  for (std::size_t i = 0; i < n; ++i) {
    const mjtNum* q = d->qpos + model.qposAddress[i];
    const Eigen::Vector3d position(q[0], q[1], q[2]);
    const Eigen::Quaterniond orientation = Eigen::Quaterniond(q[3], q[4], q[5], q[6]).normalized();
    PhysicsOutcome& o = outcomes[i];
    const PhysicsBody& body = model.bodies[i];
    o.sampledPosition = poses[i].position;
    o.sampledOrientation = poses[i].orientation;
    // The sampler lifts the object by z_offset on purpose: landing from there is no motion.
    const Eigen::Vector3d target = o.sampledPosition - Eigen::Vector3d(0.0, 0.0, body.zOffset);
    o.moved = (position - target).norm();
    o.turned = angleBetween(o.sampledOrientation, orientation);
    const double lowest = position.z() + shapesBounds(body.object->shapes, orientation).bottomZ;
    double floor = 0.0;
    if (model.support) {
      floor = *model.support;
    } else {
      // Nothing to land on: an object that went down is falling.
      floor = target.z() + shapesBounds(body.object->shapes, o.sampledOrientation).bottomZ;
    }
    o.fallen = lowest < floor - settings.positionTolerance;
    stable = stable && !o.fallen && o.moved < settings.positionTolerance &&
             o.turned < settings.rotationTolerance;
    poses[i].position = position;
    poses[i].orientation = orientation;
  }
  return stable ? PhysicsStatus::Stable : PhysicsStatus::Unstable;
}

}  // namespace placement_samplers
