#pragma once

#include <string>
#include <unordered_set>
#include <vector>

#include "placement_samplers/sampling/placement_sampler.hpp"

namespace placement_samplers {

/// robosuite's SequentialCompositeSampler: sub-samplers run in order, each seeing what the
/// earlier ones placed, so later objects can be placed on or around earlier ones.
///
/// A composite keeps the names of the samplers and objects added through it (appendSampler,
/// addObjectsToSampler, hide), so that its checks take constant time whatever the size of the
/// tree: build a nested composite completely before appending it.
class SequentialCompositeSampler : public PlacementSampler {
 public:
  /// Name of the sampler that hide() creates.
  static constexpr const char* kHideSamplerName = "HideSampler";

  explicit SequentialCompositeSampler(std::string name);

  /// Appends @p sampler with its @p args.
  /// @throw ConfigError when its name is taken in this tree or one of its objects is here
  void appendSampler(SamplerPtr sampler, SampleArgs args = SampleArgs());

  /// Adds @p objects to the uniform sub-sampler @p samplerName (searched in the whole tree), as
  /// robosuite's add_objects_to_sampler(): API for code that builds samplers like robosuite.
  /// @throw ConfigError when there is no such uniform sampler or an object is already here
  void addObjectsToSampler(const std::string& samplerName, const std::vector<ObjectPtr>& objects);

  /// Places @p objects far away (x, y in [-20, -10] m, 10 m up) with no checks, as robosuite's
  /// hide(). The first call appends the hide sampler; later calls add to it.
  /// @throw ConfigError when an object is already here
  void hide(const std::vector<ObjectPtr>& objects);

  bool sample(SampleContext& context, const Reference& reference, bool onTop) const override;
  void forEachUniform(const Reference& reference, bool onTop,
                      const UniformVisitor& visit) const override;
  std::vector<ObjectPtr> objects() const override;
  /// Removes every object from every sub-sampler; the sub-samplers stay.
  void reset() override;
  const PlacementSampler* find(const std::string& name, SampleArgs* args) const override;
  void collectSamplers(std::vector<const PlacementSampler*>& out) const override;

  /// A sub-sampler and the sample_args given with it.
  struct Child {
    SamplerPtr sampler;
    SampleArgs args;
  };

  const std::vector<Child>& children() const { return children_; }
  std::size_t size() const { return children_.size(); }

 private:
  PlacementSampler* findMutable(const std::string& name);
  void checkNotPresent(const std::vector<ObjectPtr>& objects) const;

  std::vector<Child> children_;
  std::unordered_set<std::string> samplerNames_;  ///< this one's and those appended below it
  std::unordered_set<std::string> objectNames_;   ///< objects of the samplers below it
};

}  // namespace placement_samplers
