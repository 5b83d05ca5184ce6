#include "placement_samplers/physics/physics_model.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <new>
#include <sstream>
#include <stdexcept>

#include "geometry/mujoco_compile.hpp"
#include "physics/physics_buffers.hpp"
#include "physics/physics_mjcf.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {

struct PhysicsModel::Impl {
  PhysicsSettings settings;
  std::vector<PhysicsBody> bodies;
  std::size_t bodyGeoms = 0;
  std::string mjcf;
  detail::PhysicsBuffers buffers;  ///< the model's: a world starts with them
  std::uint64_t worldBytes = 0;    ///< of a world's data with them
  detail::MujocoModelPtr model;
  std::vector<int> qposAddress;  ///< of each body's free joint: x, y, z, qw, qx, qy, qz
  /// The lowest support: the ground plane, else the lowest fixture bottom [m]; unset = none.
  std::optional<double> support;
};

namespace {

/// MuJoCo's @p message with its "Object name = body3" followed by the object and its density;
/// for a body too light, what to change first.
std::string namedBodies(std::string message, const std::vector<PhysicsBody>& bodies) {
  const std::string prefix = "Object name = body";
  const std::size_t at = message.find(prefix);
  if (at == std::string::npos) {
    return message;
  }
  std::size_t end = at + prefix.size();
  std::size_t index = 0;
  while (end < message.size() && std::isdigit(static_cast<unsigned char>(message[end])) != 0 &&
         index <= bodies.size()) {
    index = 10 * index + static_cast<std::size_t>(message[end++] - '0');
  }
  if (end == at + prefix.size() || index >= bodies.size()) {
    return message;
  }
  const PhysicsBody& body = bodies[index];
  std::ostringstream named;
  if (message.find("mjMINVAL") != std::string::npos) {
    // A body too light or too small: the fix is in the configuration.
    named << "object " << quoteText(body.object->name) << " is too light for MuJoCo: with density "
          << body.density << " kg/m^3 its mass or rotational inertia is below mjMINVAL (1e-15); "
          << "give it a larger density or size (MuJoCo: " << message << ")";
    return named.str();
  }
  named << " (object " << quoteText(body.object->name) << ", density " << body.density
        << " kg/m^3)";
  return message.insert(end, named.str());
}

}  // namespace

PhysicsModel::PhysicsModel(const std::vector<PhysicsFixture>& fixtures,
                           const std::vector<PhysicsBody>& bodies, const PhysicsSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.settings = settings;
  d.bodies = bodies;
  for (const PhysicsBody& b : bodies) {
    d.bodyGeoms += b.object->shapes.size();
  }
  const std::uint64_t dofs = 6 * std::uint64_t{bodies.size()};
  d.buffers = detail::physicsBuffers(detail::restingContacts(d.bodyGeoms), dofs);
  // Checked before compiling: MuJoCo's compiler makes one mjData of these sizes to test it.
  checkBytes(detail::bufferBytes(d.buffers, dofs), detail::fitsMujoco(d.buffers, dofs));
  d.mjcf = detail::physicsMjcf(fixtures, bodies, settings, d.buffers);
  const detail::MujocoVfsPtr vfs = detail::makeVfs();
  constexpr const char* kName = "placement_samplers_scene.xml";
  try {
    detail::addVfsFile(*vfs, kName, d.mjcf);
    d.model = detail::compileMjcf(kName, vfs.get());
  } catch (const std::runtime_error& e) {
    throw RequestError(std::string("physics: MuJoCo could not build the scene: ") +
                       escapeText(namedBodies(e.what(), bodies)));
  }
  const mjModel& m = *d.model;
  d.worldBytes = detail::dataBytes(m, d.buffers);
  checkBytes(d.worldBytes, true);
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

void PhysicsModel::checkBytes(std::uint64_t bytes, bool fitsMujoco) const {
  const Impl& d = *impl_;
  if (bytes > (std::uint64_t{d.settings.maxMemoryMb} << 20)) {
    throw RequestError(
        detail::tooLargeMessage(bytes, d.bodies.size(), d.bodyGeoms, d.settings.maxMemoryMb));
  }
  if (!fitsMujoco) {
    throw RequestError("physics: simulating the scene takes an estimated " + std::to_string(bytes) +
                       " bytes of MuJoCo data (" + std::to_string(d.bodies.size()) +
                       " free bodies with " + std::to_string(d.bodyGeoms) +
                       " geoms), more than MuJoCo 2.2.2 can allocate for one simulation");
  }
}

std::uint64_t PhysicsModel::worldBytes() const { return impl_->worldBytes; }

const PhysicsSettings& PhysicsModel::settings() const { return impl_->settings; }
std::size_t PhysicsModel::bodyCount() const { return impl_->bodies.size(); }
const std::string& PhysicsModel::mjcf() const { return impl_->mjcf; }

double PhysicsModel::mass(std::size_t body) const {
  const mjModel& m = *impl_->model;
  return m.body_mass[mj_name2id(&m, mjOBJ_BODY, detail::physicsBodyName(body).c_str())];
}

struct PhysicsWorld::Impl {
  std::shared_ptr<const PhysicsModel> model;
  std::uint64_t maxBytes = 0;
  detail::PhysicsBuffers buffers;
  std::uint64_t bytes = 0;
  detail::MujocoModelPtr grown;  ///< a copy of the model with larger buffers, once needed
  detail::MujocoDataPtr data;

  const mjModel* mujocoModel() const { return grown ? grown.get() : model->impl_->model.get(); }

  /// Doubles the buffers when that stays within maxBytes; false otherwise.
  bool grow() {
    const mjModel& base = *model->impl_->model;
    const detail::PhysicsBuffers next = detail::physicsBuffers(2 * buffers.contacts, base.nv);
    const std::uint64_t nextBytes =
        detail::dataBytes(base, next) + static_cast<std::uint64_t>(mj_sizeModel(&base));
    if (nextBytes > maxBytes || !detail::fitsMujoco(next, base.nv)) {
      return false;
    }
    data.reset();  // the old buffers go before the new ones come
    grown.reset(mj_copyModel(nullptr, &base));
    if (!grown) {
      throw std::bad_alloc();
    }
    grown->nconmax = static_cast<int>(next.contacts);
    grown->njmax = static_cast<int>(next.rows);
    grown->nstack = static_cast<int>(next.stack);
    data.reset(mj_makeData(grown.get()));
    if (!data) {
      throw std::bad_alloc();
    }
    buffers = next;
    bytes = nextBytes;
    return true;
  }

  enum class Run { Done, TimedOut, Overflow };

  /// One simulation of the bodies released at @p poses; Overflow when MuJoCo's buffers were too
  /// small for the scene's contacts (it dropped some, or its stack ran out).
  Run run(const std::vector<BodyPose>& poses,
          std::optional<std::chrono::steady_clock::time_point> deadline);
};

PhysicsWorld::PhysicsWorld(std::shared_ptr<const PhysicsModel> model, std::uint64_t maxBytes)
    : impl_(std::make_unique<Impl>()) {
  if (!model) {
    throw std::invalid_argument("PhysicsWorld needs a model");
  }
  detail::installMujocoHandlers();
  impl_->data.reset(mj_makeData(model->impl_->model.get()));
  if (!impl_->data) {
    throw std::bad_alloc();
  }
  impl_->buffers = model->impl_->buffers;
  impl_->bytes = model->impl_->worldBytes;
  impl_->maxBytes = maxBytes;
  impl_->model = std::move(model);
}

PhysicsWorld::~PhysicsWorld() = default;

std::uint64_t PhysicsWorld::bytes() const { return impl_->bytes; }
std::uint64_t PhysicsWorld::maxBytes() const { return impl_->maxBytes; }
std::uint64_t PhysicsWorld::contactCapacity() const { return impl_->buffers.contacts; }

PhysicsWorld::Impl::Run PhysicsWorld::Impl::run(
    const std::vector<BodyPose>& poses,
    std::optional<std::chrono::steady_clock::time_point> deadline) {
  const PhysicsModel::Impl& shared = *model->impl_;
  const mjModel* m = mujocoModel();
  mjData* d = data.get();
  // From reset data (zero velocities, no warm start): the same poses give the same answer
  // whatever this thread simulated before, and whatever its buffers' sizes.
  mj_resetData(m, d);
  std::memset(d->warning, 0, sizeof(d->warning));
  for (std::size_t i = 0; i < poses.size(); ++i) {
    mjtNum* q = d->qpos + shared.qposAddress[i];
    const BodyPose& p = poses[i];
    // Released at rest where it would land, its clearance taken away: MuJoCo 2.2.2's convex
    // contacts kick an object that drops onto a box or cylinder near its edge (docs/design.md).
    q[0] = p.position.x();
    q[1] = p.position.y();
    q[2] = p.position.z() - shared.bodies[i].zOffset;
    q[3] = p.orientation.w();
    q[4] = p.orientation.x();
    q[5] = p.orientation.y();
    q[6] = p.orientation.z();
  }
  try {
    mj_forward(m, d);
    const std::uint64_t steps = shared.settings.steps();
    for (std::uint64_t s = 0; s < steps; ++s) {
      if ((s & 63u) == 63u && deadline && std::chrono::steady_clock::now() > *deadline) {
        return Run::TimedOut;
      }
      mj_step(m, d);
      // MuJoCo drops the contacts beyond its buffers: the rest of the run means nothing.
      if (d->warning[mjWARN_CONTACTFULL].number > 0 || d->warning[mjWARN_CNSTRFULL].number > 0) {
        return Run::Overflow;
      }
    }
  } catch (const std::runtime_error& e) {
    if (std::strstr(e.what(), "Stack overflow") != nullptr) {
      return Run::Overflow;
    }
    throw;
  }
  return Run::Done;
}

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
  const std::size_t n = model.bodies.size();
  if (poses.size() != n) {
    throw std::invalid_argument("PhysicsWorld::simulate: " + std::to_string(poses.size()) +
                                " poses for " + std::to_string(n) + " bodies");
  }
  // A scene with more contacts than the buffers hold runs again with larger ones: its result
  // is the one the largest buffers would give.
  for (;;) {
    const Impl::Run run = impl_->run(poses, deadline);
    if (run == Impl::Run::TimedOut) {
      return PhysicsStatus::TimedOut;
    }
    if (run == Impl::Run::Done) {
      break;
    }
    if (!impl_->grow()) {
      return PhysicsStatus::TooLarge;
    }
  }
  const mjData* d = impl_->data.get();
  outcomes.resize(n);
  // MuJoCo resets the state on a bad acceleration: the poses then mean nothing.
  if (d->warning[mjWARN_BADQACC].number > 0 || d->warning[mjWARN_BADQPOS].number > 0 ||
      d->warning[mjWARN_BADQVEL].number > 0) {
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
