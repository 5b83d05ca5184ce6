#pragma once

// Internal to the core library: everything that depends on FCL's version, in one place (as
// MoveIt's fcl_compat.h). FclChecker uses these names only. Not installed.
//
// Written for FCL 0.6 and 0.7 (Debian 12 ships 0.7.0): the templated API with the `d` aliases,
// and CollisionObject's protected members cgeom, cgeom_const, t and aabb, which Body writes.

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/config.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <Eigen/Geometry>
#include <memory>

#include "collision/upright_prism.hpp"

#if FCL_MAJOR_VERSION != 0 || FCL_MINOR_VERSION < 6 || FCL_MINOR_VERSION > 7
#error "placement_samplers is written for FCL 0.6 or 0.7: check src/collision/fcl_compat.hpp"
#endif

namespace placement_samplers {
namespace fcl_compat {

using Geometry = fcl::CollisionGeometryd;
using GeometryPtr = std::shared_ptr<Geometry>;
using CollisionObject = fcl::CollisionObjectd;
using TreeManager = fcl::DynamicAABBTreeCollisionManagerd;
using Aabb = fcl::AABBd;
using MeshModel = fcl::BVHModel<fcl::OBBRSSd>;
using Box = fcl::Boxd;
using Cylinder = fcl::Cylinderd;
using Sphere = fcl::Sphered;
using Capsule = fcl::Capsuled;
using Vector3 = fcl::Vector3d;
using Triangle = fcl::Triangle;
using CollisionRequest = fcl::CollisionRequestd;
using CollisionResult = fcl::CollisionResultd;
using DistanceRequest = fcl::DistanceRequestd;
using DistanceResult = fcl::DistanceResultd;

/// An FCL object that shares its geometry without writing to it, and keeps a tight world box.
/// FCL's own constructor recomputes the geometry's local box (a write to geometry other threads
/// may be reading) and its computeAABB() bounds a rotated object by a cube around its bounding
/// sphere, loose for long objects.
class Body : public CollisionObject {
 public:
  explicit Body(const GeometryPtr& geometry) : CollisionObject(GeometryPtr()) {
    cgeom = geometry;
    cgeom_const = geometry;
  }

  /// Moves the body to @p pose and bounds it, widened by @p grow [m] on every side.
  void place(const Eigen::Isometry3d& pose, double grow) {
    t = pose;
    const Aabb& local = cgeom->aabb_local;
    const Eigen::Vector3d centre = pose * local.center();
    const Eigen::Vector3d half = pose.linear().cwiseAbs() * (0.5 * (local.max_ - local.min_)) +
                                 Eigen::Vector3d::Constant(grow);
    aabb.min_ = centre - half;
    aabb.max_ = centre + half;
  }

  /// The body as an upright prism at its pose, kept by its owner (kind None: not one).
  const detail::UprightPrism* prism = nullptr;
};

}  // namespace fcl_compat
}  // namespace placement_samplers
