#include "placement_samplers/collision/fcl_checker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>
#include <utility>

#include "collision/fcl_compat.hpp"
#include "collision/fcl_geometry.hpp"
#include "placement_samplers/collision/make_collision_checker.hpp"

namespace placement_samplers {
namespace {

using fcl_compat::Body;
using fcl_compat::GeometryPtr;

/// True when @p q turns only about the world z axis: horizontal distances from the origin, and
/// so a horizontal radius, are unchanged.
bool aboutWorldZ(const Eigen::Quaterniond& q) {
  return std::abs(q.x()) <= 1e-9 && std::abs(q.y()) <= 1e-9;
}

}  // namespace

struct FclChecker::Impl {
  /// One pose of an object: an FCL body per shape, and its circle.
  struct Instance {
    std::vector<std::unique_ptr<Body>> bodies;
    std::vector<detail::UprightPrism> prisms;  ///< of each body, at the pose
    bool bodiesPlaced = false;  ///< the FCL bodies are at the pose (the candidate's: on demand)
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    std::ptrdiff_t entry = kNone;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    double radius = 0.0;
    bool circle = false;  ///< the circle bounds the geometry at this pose
  };

  /// FCL geometry of one ObjectModel, the candidate's bodies, and a pool of placed instances
  /// reused from scene to scene.
  struct ObjectGeometry {
    const ObjectModel* object = nullptr;
    std::vector<GeometryPtr> geometries;
    std::vector<Eigen::Isometry3d> poses;  ///< of each shape in the object frame
    Instance candidate;
    std::vector<std::unique_ptr<Instance>> placed;
    std::size_t used = 0;  ///< placed instances in the current scene
  };

  struct Query {
    Impl* impl;
    const Instance* candidate;
    std::ptrdiff_t hit;
    std::ptrdiff_t support;  ///< the entry the candidate stands on: touching it needs no margin
  };

  explicit Impl(double m) : margin(m), threshold(m - kTouchTolerance) {
    // Contacts only when a pair intersects; many, because a mesh resting on a face touches it
    // with many triangles and a deep one must not be cut off.
    depthRequest.num_max_contacts = 1u << 16;
    depthRequest.enable_contact = true;
  }

  ObjectGeometry& geometryOf(const ObjectModel& object) {
    if (&object == lastObject) {  // attempts for one object come in runs
      return *lastGeometry;
    }
    std::unique_ptr<ObjectGeometry>& slot = objects[&object];
    if (!slot) {
      slot = std::make_unique<ObjectGeometry>();
      slot->object = &object;
      for (const Shape& shape : object.shapes) {
        slot->geometries.push_back(fcl_compat::makeGeometry(shape));
        slot->poses.push_back(shape.pose);
      }
      initInstance(*slot, slot->candidate);
    }
    lastObject = &object;
    lastGeometry = slot.get();
    return *slot;
  }

  /// Adds a placed body to the broadphase: a list while there are few, FCL's tree beyond.
  void registerBody(Body* body) {
    bodies.push_back(body);
    if (treeMode) {
      manager->registerObject(body);
    } else if (bodies.size() > listLimit) {
      for (Body* b : bodies) {
        manager->registerObject(b);
      }
      treeMode = true;
    }
  }

  /// The candidate's bodies against the placed ones; query.hit is set on the first collision.
  void collide(const ObjectGeometry& g, Instance& candidate, Query& query) {
    if (treeMode) {
      placeBodies(g, candidate, margin);
      for (const std::unique_ptr<Body>& body : candidate.bodies) {
        manager->collide(body.get(), &query, &Impl::onPair);
        if (query.hit != kNone) {
          return;
        }
      }
      return;
    }
    // In entry order, boxes first: for a few bodies cheaper than the tree. The candidate's FCL
    // bodies are moved only when a pair needs FCL.
    for (const std::unique_ptr<Body>& body : candidate.bodies) {
      for (Body* other : bodies) {
        const Verdict verdict = pairVerdict(*body, *other, query);
        if (verdict == Verdict::Clear) {
          continue;
        }
        if (verdict == Verdict::Unknown) {
          placeBodies(g, candidate, margin);
          if (!body->getAABB().overlap(other->getAABB()) || !tooClose(*body, *other, query)) {
            continue;
          }
        }
        query.hit = static_cast<const Instance*>(other->getUserData())->entry;
        return;
      }
    }
  }

  static void initInstance(const ObjectGeometry& g, Instance& instance) {
    instance.prisms.resize(g.geometries.size());
    for (std::size_t i = 0; i < g.geometries.size(); ++i) {
      instance.bodies.push_back(std::make_unique<Body>(g.geometries[i]));
      instance.bodies.back()->setUserData(&instance);
      instance.bodies.back()->prism = &instance.prisms[i];
    }
  }

  /// Moves @p instance to a pose: its prisms and circle now, its FCL bodies by placeBodies().
  static void place(const ObjectGeometry& g, Instance& instance, const Eigen::Vector3d& position,
                    const Eigen::Quaterniond& orientation) {
    const ObjectModel& object = *g.object;
    instance.pose.linear() = orientation.normalized().toRotationMatrix();
    instance.pose.translation() = position;
    for (std::size_t i = 0; i < instance.prisms.size(); ++i) {
      instance.prisms[i] = detail::uprightPrism(object.shapes[i], instance.pose * g.poses[i]);
    }
    instance.bodiesPlaced = false;
    instance.centre = position.head<2>();
    instance.radius = object.horizontalRadius;
    instance.circle = object.radiusBoundsGeometry && std::isfinite(object.horizontalRadius) &&
                      aboutWorldZ(orientation * object.initOrientation.conjugate());
  }

  /// Moves the FCL bodies of @p instance to its pose, their boxes widened by @p grow [m].
  static void placeBodies(const ObjectGeometry& g, Instance& instance, double grow) {
    if (instance.bodiesPlaced) {
      return;
    }
    for (std::size_t i = 0; i < instance.bodies.size(); ++i) {
      instance.bodies[i]->place(instance.pose * g.poses[i], grow);
    }
    instance.bodiesPlaced = true;
  }

  /// The deepest penetration of two bodies [m] when FCL's yes/no test finds them in contact
  /// (then asked for every contact), else nullopt.
  std::optional<double> contactDepth(const Body& a, const Body& b) {
    result.clear();
    fcl::collide(&a, &b, boolRequest, result);
    if (!result.isCollision()) {
      return std::nullopt;
    }
    result.clear();
    fcl::collide(&a, &b, depthRequest, result);
    double depth = 0.0;
    for (std::size_t i = 0; i < result.numContacts(); ++i) {
      depth = std::max(depth, result.getContact(i).penetration_depth);
    }
    return depth;
  }

  /// FCL's distance of two bodies apart [m].
  double apart(const Body& a, const Body& b) {
    distance.clear();
    fcl::distance(&a, &b, distanceRequest, distance);
    return distance.min_distance;
  }

  /// True when the two bodies come closer than the margin (penetrate, with a zero margin);
  /// @p limit: the signed distance below which they do.
  bool tooClose(const Body& a, const Body& b, double limit) {
    if (const std::optional<double> depth = contactDepth(a, b)) {
      // Signed distance -depth against margin - tolerance: with a zero margin a contact
      // counts only beyond the tolerance; with a positive one any contact counts.
      return -*depth < limit;
    }
    return limit > 0.0 && apart(a, b) < limit;
  }

  /// The signed distance of two bodies [m]: apart, FCL's distance; in contact, minus the
  /// deepest contact's penetration.
  double signedDistance(const Body& a, const Body& b) {
    const std::optional<double> depth = contactDepth(a, b);
    return depth ? -*depth : apart(a, b);
  }

  enum class Verdict { Clear, Hit, Unknown };

  /// What the cheap tests say of a pair: the circles when both bound their geometry, the exact
  /// prism distance when both bodies are upright boxes or cylinders. A prism verdict is given
  /// only kDecisive [m] away from the limit, where FCL's own answer is the same: its boolean
  /// test works to 1e-6 m, its distance is never below the true one, and its penetration depth
  /// is exact for two boxes and not below the true depth otherwise; nearer pairs go to FCL.
  static Verdict pairVerdict(const Body& mine, const Body& other, const Query& query) {
    const Instance& placed = *static_cast<const Instance*>(other.getUserData());
    const Instance& candidate = *query.candidate;
    if (candidate.circle && placed.circle) {
      const double reach = candidate.radius + placed.radius + query.impl->margin;
      if ((candidate.centre - placed.centre).squaredNorm() > reach * reach) {
        return Verdict::Clear;  // the circles bound both: no point of one comes within the margin
      }
    }
    if (mine.prism->kind == detail::UprightPrism::Kind::None ||
        other.prism->kind == detail::UprightPrism::Kind::None) {
      return Verdict::Unknown;
    }
    const double limit = query.impl->limitFor(placed, query);
    const detail::SignedDistanceBounds d = detail::prismDistance(*mine.prism, *other.prism);
    if (d.lower > limit + kDecisive) {
      return Verdict::Clear;
    }
    // Apart but within a positive margin stays FCL's: its distance of cylinders is up to
    // 0.1 mm above the true one (upright_prism_test.cpp).
    return d.upper < std::min(limit, 0.0) - kDecisive ? Verdict::Hit : Verdict::Unknown;
  }

  /// The signed distance below which the candidate is too close to @p placed [m]. The surface
  /// an object stands on touches it: the margin keeps others away, not it.
  double limitFor(const Instance& placed, const Query& query) const {
    return placed.entry == query.support ? -kTouchTolerance : threshold;
  }

  bool tooClose(const Body& mine, const Body& other, const Query& query) {
    const Instance& placed = *static_cast<const Instance*>(other.getUserData());
    return tooClose(mine, other, limitFor(placed, query));
  }

  static bool onPair(fcl_compat::CollisionObject* a, fcl_compat::CollisionObject* b, void* data) {
    Query& query = *static_cast<Query*>(data);
    const bool aIsCandidate = a->getUserData() == query.candidate;
    const Body& mine = static_cast<const Body&>(aIsCandidate ? *a : *b);
    const Body& other = static_cast<const Body&>(aIsCandidate ? *b : *a);
    const Verdict verdict = pairVerdict(mine, other, query);
    if (verdict == Verdict::Clear ||
        (verdict == Verdict::Unknown && !query.impl->tooClose(mine, other, query))) {
      return false;
    }
    query.hit = static_cast<const Instance*>(other.getUserData())->entry;
    return true;  // stops the broadphase
  }

  /// Distance from the limit [m] beyond which the prism test decides a pair without FCL.
  static constexpr double kDecisive = 1e-5;

  double margin;
  double threshold;  ///< reject below this signed distance [m]
  std::unordered_map<const ObjectModel*, std::unique_ptr<ObjectGeometry>> objects;
  const ObjectModel* lastObject = nullptr;  ///< the object of lastGeometry
  ObjectGeometry* lastGeometry = nullptr;
  std::vector<Body*> bodies;  ///< placed bodies of the scene, in entry order
  bool treeMode = false;      ///< bodies are in the manager too
  std::size_t listLimit = kDefaultListLimit;
  std::unique_ptr<fcl_compat::TreeManager> manager = std::make_unique<fcl_compat::TreeManager>();
  fcl_compat::CollisionRequest boolRequest;
  fcl_compat::CollisionRequest depthRequest;
  fcl_compat::DistanceRequest distanceRequest;
  fcl_compat::CollisionResult result;   ///< scratch of tooClose()
  fcl_compat::DistanceResult distance;  ///< scratch of tooClose()
};

FclChecker::FclChecker(double margin, std::size_t listLimit) {
  checkCollisionMargin(margin);
  impl_ = std::make_unique<Impl>(margin);
  impl_->listLimit = listLimit;
}

FclChecker::~FclChecker() = default;

double FclChecker::margin() const { return impl_->margin; }

void FclChecker::clear() {
  if (impl_->treeMode) {
    impl_->manager->clear();
    impl_->treeMode = false;
  }
  impl_->bodies.clear();
  for (auto& entry : impl_->objects) {
    entry.second->used = 0;
  }
}

void FclChecker::added(const std::vector<PlacedEntry>& entries, std::size_t index) {
  const PlacedEntry& entry = entries.at(index);
  Impl::ObjectGeometry& g = impl_->geometryOf(*entry.object);
  if (g.used == g.placed.size()) {
    g.placed.push_back(std::make_unique<Impl::Instance>());
    Impl::initInstance(g, *g.placed.back());
  }
  Impl::Instance& instance = *g.placed[g.used++];
  Impl::place(g, instance, entry.position, entry.orientation);
  Impl::placeBodies(g, instance, 0.0);
  instance.entry = static_cast<std::ptrdiff_t>(index);
  for (const std::unique_ptr<Body>& body : instance.bodies) {
    impl_->registerBody(body.get());
  }
}

std::ptrdiff_t FclChecker::firstCollision(const std::vector<PlacedEntry>& /*entries*/,
                                          const Candidate& candidate) {
  if (impl_->bodies.empty()) {
    return kNone;
  }
  Impl::ObjectGeometry& g = impl_->geometryOf(*candidate.object);
  Impl::place(g, g.candidate, candidate.position, candidate.orientation);
  Impl::Query query{impl_.get(), &g.candidate, kNone, candidate.support};
  impl_->collide(g, g.candidate, query);
  return query.hit;
}

bool FclChecker::exactDistance(const std::vector<PlacedEntry>& entries, std::size_t index,
                               const Candidate& candidate, double& distance) {
  const PlacedEntry& entry = entries.at(index);
  const Impl::ObjectGeometry& placed = impl_->geometryOf(*entry.object);
  const Impl::Instance* target = nullptr;
  for (std::size_t i = 0; i < placed.used; ++i) {
    if (placed.placed[i]->entry == static_cast<std::ptrdiff_t>(index)) {
      target = placed.placed[i].get();
    }
  }
  if (target == nullptr) {
    return false;
  }
  Impl::ObjectGeometry& g = impl_->geometryOf(*candidate.object);
  Impl::place(g, g.candidate, candidate.position, candidate.orientation);
  distance = std::numeric_limits<double>::infinity();
  for (const std::unique_ptr<Body>& mine : g.candidate.bodies) {
    for (const std::unique_ptr<Body>& other : target->bodies) {
      // Two upright prisms have an exact distance of their own (FCL's of cylinders is up to
      // 0.1 mm above the truth); two rectangles apart in x-y, and other shapes, ask FCL.
      if (mine->prism->kind != detail::UprightPrism::Kind::None &&
          other->prism->kind != detail::UprightPrism::Kind::None) {
        const detail::SignedDistanceBounds d = detail::prismDistance(*mine->prism, *other->prism);
        if (d.lower == d.upper) {
          distance = std::min(distance, d.lower);
          continue;
        }
      }
      Impl::placeBodies(g, g.candidate, impl_->margin);
      distance = std::min(distance, impl_->signedDistance(*mine, *other));
    }
  }
  return true;
}

}  // namespace placement_samplers
