#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "placement_samplers/sampling/placement_sampler.hpp"

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
  std::vector<ObjectPtr> objects() const override;
  void reset() override;

  const UniformSamplerParams& params() const { return params_; }

  /// The x or y interval the centre of @p object is drawn from, relative to the reference [m].
  Eigen::Vector2d effectiveRange(const ObjectModel& object, int axis) const;

 private:
  struct Entry {
    ObjectPtr object;
    Eigen::Vector2d x;  ///< effective x interval [m]
    Eigen::Vector2d y;  ///< effective y interval [m]
  };

  Eigen::Quaterniond sampleOrientation(Engine& engine, const ObjectModel& object) const;
  bool placeOne(SampleContext& context, const Entry& entry, const Eigen::Vector3d& base,
                bool onTop) const;

  UniformSamplerParams params_;
  Eigen::Vector3d axis_;
  std::vector<Entry> entries_;
};

}  // namespace placement_samplers
