#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "placement_samplers/collision/collision_checker.hpp"

namespace placement_samplers {

/// The exact test, with FCL 0.7: a candidate is rejected when its collision geometry, at the
/// candidate pose, comes closer than the margin to the geometry of a placed entry.
///
/// - Touching is not a collision (an object resting on its support touches it): with a zero
///   margin, shapes in contact are rejected only when they penetrate deeper than
///   kTouchTolerance; with a positive margin, when their distance is below
///   margin - kTouchTolerance (so a resting object is then rejected: give it a z_offset).
/// - FCL geometry is made once per ObjectModel (meshes once per process, as BVHModel<OBBRSS>,
///   shared by every checker and thread) and FCL objects are moved with each pose, never
///   rebuilt per attempt. Placed entries are a list (a dynamic AABB tree beyond
///   kDefaultListLimit) updated as entries are added; the candidate's box is widened by the
///   margin.
/// - Upright boxes and cylinders (turned about the world z axis only) are decided by an exact
///   prism distance where it is more than 1e-5 m from the limit, so FCL's answer is known
///   without asking it; nearer pairs and other shapes go to FCL.
/// - Circles only skip pairs that cannot come within the margin: when both objects' radius
///   bounds their geometry (ObjectModel::radiusBoundsGeometry: not with an overridden smaller
///   radius) and both are turned about the world z axis only, from their init orientation,
///   so that the radius still bounds them horizontally.
/// - Meshes are surfaces: an object entirely inside a closed mesh, touching no triangle, is
///   not detected.
///
/// ObjectModels are cached by address: every object passed in must outlive the checker (the
/// scene generator's checkers live for one request). One checker per thread.
class FclChecker : public CollisionChecker {
 public:
  /// Penetration depth [m] up to which shapes in contact still count as touching.
  static constexpr double kTouchTolerance = 1e-6;

  /// Up to this many placed bodies the broadphase is a list checked in entry order, cheap
  /// tests first (faster than FCL's dynamic AABB tree up to 200 upright objects at least,
  /// docs/design.md); beyond, the tree. Both accept and reject the same candidates.
  static constexpr std::size_t kDefaultListLimit = 256;

  /// @param margin required clearance between objects [m], finite and non-negative
  /// @param listLimit placed bodies up to which the list is used (0 = always the tree)
  /// @throw ConfigError when @p margin breaks checkCollisionMargin()'s rule
  explicit FclChecker(double margin = 0.0, std::size_t listLimit = kDefaultListLimit);
  ~FclChecker() override;
  FclChecker(const FclChecker&) = delete;
  FclChecker& operator=(const FclChecker&) = delete;

  void clear() override;
  void added(const std::vector<PlacedEntry>& entries, std::size_t index) override;
  /// Moves this checker's FCL objects of the candidate's object to the candidate pose.
  /// @return the index of an entry that @p candidate comes too close to, or kNone
  std::ptrdiff_t firstCollision(const std::vector<PlacedEntry>& entries,
                                const Candidate& candidate) override;
  bool needsOrientation() const override { return true; }
  /// The smallest signed distance between the candidate's shapes and the entry's (FCL's
  /// distance apart, minus the penetration depth in contact).
  bool exactDistance(const std::vector<PlacedEntry>& entries, std::size_t index,
                     const Candidate& candidate, double& distance) override;

  double margin() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace placement_samplers
