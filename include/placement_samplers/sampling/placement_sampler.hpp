#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "placement_samplers/geometry/object_model.hpp"
#include "placement_samplers/sampling/sample_context.hpp"

namespace placement_samplers {

/// What positions are relative to: the sampler's own reference_pos, a named fixture or placed
/// object (its origin, plus its top offset when on_top), or a point.
struct Reference {
  enum class Kind { Default, Name, Point };
  Kind kind = Kind::Default;
  std::string name;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< [m]

  static Reference byDefault() { return Reference(); }
  static Reference named(const std::string& name);
  static Reference at(const Eigen::Vector3d& point);
};

/// robosuite's sample_args: the reference and on_top a composite passes to one sub-sampler.
/// Unset members take the values of the composite's own call.
struct SampleArgs {
  std::optional<Reference> reference;
  std::optional<bool> onTop;
};

class UniformRandomSampler;

/// Called for each uniform sampler of a tree with the reference and on_top it runs with.
using UniformVisitor = std::function<void(const UniformRandomSampler& sampler,
                                          const Reference& reference, bool onTop)>;

/// Base of the samplers: a name, and sample() over a context.
class PlacementSampler {
 public:
  explicit PlacementSampler(std::string name);
  virtual ~PlacementSampler() = default;
  PlacementSampler(const PlacementSampler&) = delete;
  PlacementSampler& operator=(const PlacementSampler&) = delete;

  const std::string& name() const { return name_; }

  /// Places this sampler's objects into @p context, relative to @p reference.
  /// @param onTop as robosuite: subtract the object's bottom offset, add a named reference's top
  /// @return false when the scene failed; the reason is in context.failure()
  virtual bool sample(SampleContext& context, const Reference& reference, bool onTop) const = 0;

  /// Every object of this sampler and its sub-samplers, in sampling order.
  virtual std::vector<ObjectPtr> objects() const = 0;
  /// Removes every object (robosuite's reset()).
  virtual void reset() = 0;

  /// The sampler called @p name in this tree (this one included), or nullptr. @p args receives
  /// the sample_args it gets in a full run: its parent's, completed by those of the composites
  /// above (empty for this one).
  virtual const PlacementSampler* find(const std::string& name, SampleArgs* args) const;
  /// This sampler and every sampler below it, depth first in sampling order.
  virtual void collectSamplers(std::vector<const PlacementSampler*>& out) const;

  /// Calls @p visit for every uniform sampler of this tree in sampling order, with the
  /// reference and on_top that sample() would give it when called with @p reference and
  /// @p onTop: the one walk for code that follows a scene's sampling (rviz regions, validation).
  virtual void forEachUniform(const Reference& reference, bool onTop,
                              const UniformVisitor& visit) const = 0;

 private:
  std::string name_;
};

using SamplerPtr = std::shared_ptr<PlacementSampler>;

}  // namespace placement_samplers
