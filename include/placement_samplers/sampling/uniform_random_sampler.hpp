#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "placement_samplers/sampling/placement_sampler.hpp"
#include "placement_samplers/sampling/region.hpp"
#include "placement_samplers/sampling/relations.hpp"
#include "placement_samplers/sampling/surface_region.hpp"

namespace placement_samplers {

/// Rotation about the sampler's axis: robosuite's `rotation` argument.
struct RotationSpec {
  enum class Kind { Full, Fixed, Range };
  Kind kind = Kind::Full;  ///< Full: U(0, 2pi); Fixed: low; Range: U(low, high)
  double low = 0.0;        ///< [rad]
  double high = 0.0;       ///< [rad]

  static RotationSpec full() { return RotationSpec(); }
  static RotationSpec fixed(double angle);
  /// A pair in either order, as robosuite (min and max are taken).
  static RotationSpec range(double a, double b);
};

/// The parameters of robosuite's UniformRandomSampler, with its defaults.
struct UniformSamplerParams {
  Eigen::Vector2d xRange = Eigen::Vector2d::Zero();  ///< [min, max] around the reference [m]
  Eigen::Vector2d yRange = Eigen::Vector2d::Zero();  ///< [min, max] around the reference [m]
  RotationSpec rotation;
  int rotationAxis = 2;                     ///< 0 = x, 1 = y, 2 = z (world axes)
  bool ensureObjectBoundaryInRange = true;  ///< shrink the ranges by each horizontal radius
  bool ensureValidPlacement = true;         ///< run the collision test
  Eigen::Vector3d referencePos = Eigen::Vector3d::Zero();  ///< [m]
  double zOffset = 0.0;                                    ///< [m]
  std::uint32_t maxAttempts = 5000;                        ///< samples per object
  bool hides = false;  ///< its placements are hidden objects (hide()): not drawn
  /// Another shape instead of xRange/yRange (which stay zero), around the reference; a
  /// rectangle is turned into xRange/yRange.
  std::optional<RegionShape> region;
  /// The support surfaces of a fixture or earlier object instead of xRange/yRange (which stay
  /// zero); positions in the world frame (README, "Support surfaces").
  std::optional<SurfaceRegion> surface;
  std::vector<KeepOutZone> keepOut;  ///< where no placed object may be
  /// rejection: robosuite's blind attempts; free_space: draws only from grid cells not yet
  /// known to be blocked (the same distribution, uniform over the free positions); dense: the
  /// sites of a randomly shifted and turned hexagonal lattice, in random order (another
  /// distribution, past the random-packing limit)
  enum class Strategy { Rejection, FreeSpace, Dense };
  Strategy strategy = Strategy::Rejection;
  /// Upright: the objects as configured (robosuite's); Stable: each attempt first draws one of
  /// the object's resting poses by probability (README, "Resting poses").
  enum class Resting { Upright, Stable };
  Resting resting = Resting::Upright;
  double minProbability = 0.02;  ///< Stable: rarer resting poses are dropped
  bool allowRolling = false;     ///< Stable: also the poses that roll (a cylinder on its side)
  /// false: x_range, y_range, rotation, reference_pos and z_offset are taken as robosuite's
  /// code takes them from a Python caller, unchecked (reversed, emptied by the boundary
  /// shrink, not finite, beyond limits::kCoordinate); the caller's UniformSource checks each
  /// draw as numpy's Generator.uniform does (the Python module). Rectangular rejection only.
  bool checkInputs = true;
  /// false: a placement's orientation is not computed where no test needs it (it stays the
  /// identity); for a caller that computes its own from the angles its UniformSource is told
  /// (the Python module). Positions, draws and attempts are the same.
  bool orientations = true;
  /// Where its objects go relative to fixtures and earlier objects (README, "Relations"):
  /// position relations reject attempts, rotation relations set the turn.
  std::vector<Relation> relations;
};

/// robosuite's UniformRandomSampler: rejection sampling of x and y in ranges around a
/// reference, z from the reference, a rotation about one world axis applied after the object's
/// initial orientation.
class UniformRandomSampler : public PlacementSampler {
 public:
  /// @throw ConfigError naming the sampler and parameter when a range is reversed or not
  /// finite, or maxAttempts is 0
  UniformRandomSampler(std::string name, const UniformSamplerParams& params,
                       const std::vector<ObjectPtr>& objects = {});

  /// Adds objects, after the ones already there.
  /// @throw ConfigError when an object is already here or its shrunk region is empty
  void addObjects(const std::vector<ObjectPtr>& objects);

  bool sample(SampleContext& context, const Reference& reference, bool onTop) const override;
  void forEachUniform(const Reference& reference, bool onTop,
                      const UniformVisitor& visit) const override;

  /// The point the ranges are around for @p reference: reference_pos (the default), the
  /// call's point, or the named reference's @p namedPosition, raised by its top when @p onTop
  /// (robosuite's rule). std::nullopt for a name whose entry is not in the scene
  /// (@p namedPosition null). Sampling, validation and rviz all resolve it here.
  std::optional<Eigen::Vector3d> base(const Reference& reference, bool onTop,
                                      const Eigen::Vector3d* namedPosition,
                                      const ObjectModel* namedObject) const;
  /// z of @p object's origin [m] above the resolved @p base (robosuite's rule): base z plus
  /// z_offset, minus the object's bottom offset when @p onTop. Sampling and validation use it.
  double height(const ObjectModel& object, const Eigen::Vector3d& base, bool onTop) const {
    return params_.zOffset + base.z() - (onTop ? object.bottomOffset.z() : 0.0);
  }
  std::vector<ObjectPtr> objects() const override;
  void reset() override;

  const UniformSamplerParams& params() const { return params_; }

  /// The x or y interval the centre of @p object is drawn from, relative to the reference [m].
  Eigen::Vector2d effectiveRange(const ObjectModel& object, int axis) const;

  /// Binds a surface region to the target the configuration knows (surface_placement.cpp): a
  /// configured fixture at its pose (its surfaces in the world, drawn from for every call), or
  /// with @p objectFrame an object an earlier sampler places (its surfaces at its origin under
  /// its initial orientation, moved to where it is placed in each scene).
  /// @throw ConfigError when the target has no surface (selectSurfaces()) or some object of
  ///        this sampler fits on none of the selected ones
  void bindSurfaces(const ObjectModel& target, const Eigen::Vector3d& position,
                    const Eigen::Quaterniond& orientation, bool objectFrame);
  /// The surface region's selected surfaces on @p target (its `of`, found in a scene) in the
  /// world: bound ones, the request's (@p request, found by SceneGenerator::prepare()), or
  /// found now. @p indices (if given) receives their indices among all the target's surfaces.
  /// @throw ConfigError as selectSurfaces()
  std::vector<SupportSurface> surfacesOn(const PlacedEntry& target, const RequestSurfaces* request,
                                         std::vector<std::size_t>* indices = nullptr) const;
  /// One resting pose of an object under resting: stable.
  struct RestingChoice {
    std::int16_t index = 0;               ///< as --describe lists them (ObjectPlacement)
    const ObjectModel* object = nullptr;  ///< the object in that pose (initOrientation: the pose)
    double probability = 0.0;             ///< after min_probability, renormalised
  };
  /// @p object's resting poses (matched by name) under resting: stable; empty otherwise.
  std::vector<RestingChoice> restingChoices(const ObjectModel& object) const;
  /// True when bindSurfaces() found the surface region's surfaces.
  bool surfacesBound() const { return boundSurfaces_ != nullptr; }
  /// Every surface bindSurfaces() found on the target (nullptr: none bound), at the object's
  /// origin when surfacesBoundToObject(); selectedSurfaces() are the indices `select` takes.
  const SurfaceSearch* foundSurfaces() const { return foundSurfaces_.get(); }
  const std::vector<std::size_t>& selectedSurfaces() const { return selectedIndices_; }
  bool surfacesBoundToObject() const { return boundToObject_; }
  /// The inset a surface region keeps @p object's centre from the surfaces' edges [m]: its
  /// horizontal radius under ensure_object_boundary_in_range, plus the region's margin.
  double surfaceInset(const ObjectModel& object) const;
  /// Why @p object fits on none of @p surfaces of the surface region's target.
  std::string noFitMessage(const ObjectModel& object, const SurfaceDraw::NoFit& why) const;

 private:
  struct Entry {
    ObjectPtr object;
    Eigen::Vector2d x = Eigen::Vector2d::Zero();  ///< effective x interval [m]
    Eigen::Vector2d y = Eigen::Vector2d::Zero();  ///< effective y interval [m]
    /// The inset region's draws when there is a region shape or a keep-out zone (else x, y).
    std::shared_ptr<const RegionDraw> draw;
    /// A surface region bound to a configured fixture: the draws on its surfaces.
    std::shared_ptr<const SurfaceDraw> surfaceDraw;
    /// resting: stable: one entry per resting pose (its object: the object in that pose),
    /// drawn by @ref cumulative; empty: the object as configured.
    std::vector<Entry> poses;
    std::vector<double> cumulative;  ///< running sums of the poses' probabilities
    std::int16_t restPose = ObjectPlacement::kUpright;  ///< a pose entry's index
    bool usable = true;   ///< a pose entry the region has room for (else its attempts fail)
    std::string problem;  ///< why not
    /// The indices of the relations that apply to the object (a pose entry: its object's).
    std::vector<std::uint16_t> relations;
    double heading0 = 0.0;  ///< the heading of the object's initial orientation [rad]
  };

  Eigen::Quaterniond sampleOrientation(Engine& engine, const ObjectModel& object) const;
  /// The rotation angle of one placement [rad], from @p draws (the engine or a UniformSource).
  template <class Draws>
  double drawAngle(Draws& draws) const;
  /// The orientation of @p object turned by @p angle about the sampler's axis.
  Eigen::Quaterniond orientationOf(double angle, const ObjectModel& object) const;
  /// The stream this sampler draws from: the scene's, or the hidden objects' own (hide()).
  Engine& engineOf(SampleContext& context) const {
    return params_.hides ? context.hiddenEngine() : context.engine();
  }
  /// Attempts per object: the request's max_attempts when it sets one, else the sampler's.
  std::uint32_t attemptLimit(const SampleContext& context) const {
    return context.maxAttempts() != 0 ? context.maxAttempts() : params_.maxAttempts;
  }
  bool placeOne(SampleContext& context, const Entry& entry, const Eigen::Vector3d& base,
                bool onTop) const;
  /// placeOne() in a rectangle, drawing from @p draws; @p relations (kRelated) tests the
  /// position relations and turns the object (relation_placement.cpp).
  template <bool kRelated, class Draws>
  bool placeInRectangle(SampleContext& context, const Entry& entry, const Eigen::Vector3d& base,
                        bool onTop, Draws& draws, PlacementRelations* relations) const;
  /// Checks the relations (constructor; relation_placement.cpp).
  void checkRelations(const std::string& where) const;
  /// The relations that apply to @p entry's object (addObjects()).
  /// @throw ConfigError when two of them set its yaw, or it has no heading to turn
  void bindRelations(Entry& entry) const;
  /// Resolves @p entry's relations in this scene; the centres are drawn from the box @p lo ..
  /// @p hi [m] (world; lo > hi: not known). False, after fail(), when a target is not in the
  /// scene or a rotation relation cannot hold.
  bool resolveRelations(SampleContext& context, const Entry& entry, const Eigen::Vector2d& lo,
                        const Eigen::Vector2d& hi, PlacementRelations& out) const;
  /// At attempt kRelationProbeAttempts of a placement loop: false, after fail(), when a position
  /// relation cannot hold anywhere in @p relations' box.
  bool relationsPossible(SampleContext& context, const ObjectModel& object,
                         const PlacementRelations& relations) const;
  /// True when every position relation holds for @p candidate (its pose and posed object): the
  /// disks' gaps, or in the fcl modes (@p relations.exact) the shapes' exact distances; counts
  /// the first that does not.
  bool relationsHold(SampleContext& context, PlacementRelations& relations,
                     const Candidate& candidate) const;
  /// relationsHold() for @p candidate, its turn drawn first in the fcl modes (@p relations.exact:
  /// their exact gaps need it); out of line, for the loops that test relations in a lambda.
  bool relationsAccept(SampleContext& context, Engine& engine, PlacementRelations& relations,
                       Candidate& candidate) const;
  /// The orientation of @p object at @p p: the sampler's rotation draw, or the one of a
  /// rotation relation (README, "Relations").
  Eigen::Quaterniond relatedOrientation(Engine& engine, const ObjectModel& object,
                                        const Eigen::Vector2d& p,
                                        const PlacementRelations* relations) const;
  /// placeOne() for a region shape or keep-out zones (shaped_placement.cpp).
  bool placeOneShaped(SampleContext& context, const Entry& entry, const Eigen::Vector3d& base,
                      bool onTop, PlacementRelations* relations) const;
  /// The entry of @p object without its resting poses: ranges and draws (sampler_entries.cpp).
  /// @throw ConfigError when the region leaves it no room
  Entry makeEntry(const ObjectPtr& object);
  /// The draws of @p entry on the bound surfaces (when there are bound surfaces).
  /// @throw ConfigError when it fits on none
  void bindEntrySurfaces(Entry& entry) const;
  /// @p entry's resting poses under resting: stable (sampler_entries.cpp).
  /// @throw ConfigError when the region has room for none of them
  void addRestingPoses(Entry& entry);
  /// placeOne() under resting: stable (resting_placement.cpp).
  bool placeOneResting(SampleContext& context, const Entry& entry, const Eigen::Vector3d& base,
                       bool onTop, PlacementRelations* relations) const;
  /// placeOne() for a surface region (surface_placement.cpp).
  bool placeOnSurface(SampleContext& context, const Entry& entry, const Eigen::Vector3d& base,
                      PlacementRelations* relations) const;
  /// The draws of @p entry's object on @p target's surfaces, made once per thread and target
  /// pose; nullptr and @p error when there are none.
  const SurfaceDraw* surfaceDrawOn(SampleContext& context, const Entry& entry,
                                   const PlacedEntry& target, std::string& error) const;
  /// sample() with strategy dense (dense_placement.cpp).
  bool sampleDense(SampleContext& context, const Eigen::Vector3d& base, bool onTop) const;
  /// sample() with strategy free_space (free_space_placement.cpp).
  bool sampleFreeSpace(SampleContext& context, const Eigen::Vector3d& base, bool onTop) const;
  /// sampleFreeSpace() on a surface region (surface_free_space.cpp).
  bool sampleFreeSpaceOnSurfaces(SampleContext& context, const Eigen::Vector3d& base) const;
  /// Records that @p object could not be placed in @p limit attempts; @p outside of them fell
  /// outside the inset region or into a keep-out zone. @return false
  bool failPlacement(SampleContext& context, const ObjectModel& object, std::uint32_t limit,
                     const std::vector<std::uint32_t>* counts, std::uint32_t outside,
                     const PlacementRelations* relations = nullptr) const;
  /// Records that the scene failed at @p object (nullptr: before any object) after
  /// @p attempts, with @p message; every placement loop fails through it. @return false
  bool fail(SampleContext& context, const ObjectModel* object, std::uint32_t attempts,
            std::string message) const;
  /// fail() for a request whose time ran out while placing @p object. @return false
  bool failOutOfTime(SampleContext& context, const ObjectModel& object,
                     std::uint32_t attempts) const;
  /// The collision test of an attempt in the shaped, resting and surface loops: true when
  /// @p candidate is blocked, its blocker counted in @p counts and the attempt in @p collided.
  static bool collidesCounted(SampleContext& context, const Candidate& candidate,
                              std::vector<std::uint32_t>& counts, std::uint32_t& collided);
  /// True when a disk of radius @p margin at @p local (relative to the reference; @p offset is
  /// the reference's x-y) reaches into one of the keep-out zones, in order.
  bool inKeepOut(const Eigen::Vector2d& local, const Eigen::Vector2d& offset, double margin) const {
    for (const KeepOutZone& zone : params_.keepOut) {
      if (keepOutBlocks(zone, zone.world ? Eigen::Vector2d(local + offset) : local, margin)) {
        return true;
      }
    }
    return false;
  }
  /// Checks region and keep-out zones (constructor).
  void checkShapes(const std::string& where);
  /// The draws for @p object, shared by the objects of one horizontal radius (addObjects()).
  std::shared_ptr<const RegionDraw> regionDraw(const ObjectModel& object);

  UniformSamplerParams params_;
  Eigen::Vector3d axis_;
  Eigen::Vector2d boundsLo_ = Eigen::Vector2d::Zero();  ///< the region's bounds [m]
  Eigen::Vector2d boundsHi_ = Eigen::Vector2d::Zero();
  std::vector<Entry> entries_;
  /// A surface region's target's selected surfaces, when bindSurfaces() found them.
  std::shared_ptr<const std::vector<SupportSurface>> boundSurfaces_;
  bool boundToObject_ = false;  ///< boundSurfaces_ are at the object's origin
  std::shared_ptr<const SurfaceSearch> foundSurfaces_;  ///< all of them, for --describe
  std::vector<std::size_t> selectedIndices_;
};

}  // namespace placement_samplers
