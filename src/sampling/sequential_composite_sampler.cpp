#include "placement_samplers/sampling/sequential_composite_sampler.hpp"

#include "placement_samplers/errors.hpp"
#include "placement_samplers/text.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"

namespace placement_samplers {

SequentialCompositeSampler::SequentialCompositeSampler(std::string name)
    : PlacementSampler(std::move(name)) {
  samplerNames_.insert(this->name());
}

void SequentialCompositeSampler::checkNotPresent(const std::vector<ObjectPtr>& objects) const {
  for (const ObjectPtr& object : objects) {
    if (objectNames_.count(object->name) != 0) {
      throw ConfigError("sampler " + quoteText(name()) + ": object " + quoteText(object->name) +
                        " already has a sampler");
    }
  }
}

void SequentialCompositeSampler::appendSampler(SamplerPtr sampler, SampleArgs args) {
  if (!sampler) {
    throw ConfigError("sampler " + quoteText(name()) + ": cannot append a null sampler");
  }
  std::vector<const PlacementSampler*> incoming;
  sampler->collectSamplers(incoming);
  for (const PlacementSampler* s : incoming) {
    if (samplerNames_.count(s->name()) != 0) {
      throw ConfigError("sampler " + quoteText(name()) + ": a sampler named " +
                        quoteText(s->name()) + " is already here");
    }
  }
  const std::vector<ObjectPtr> objects = sampler->objects();
  checkNotPresent(objects);
  for (const PlacementSampler* s : incoming) {
    samplerNames_.insert(s->name());
  }
  for (const ObjectPtr& object : objects) {
    objectNames_.insert(object->name);
  }
  children_.push_back(Child{std::move(sampler), std::move(args)});
}

PlacementSampler* SequentialCompositeSampler::findMutable(const std::string& name) {
  return const_cast<PlacementSampler*>(find(name, nullptr));
}

void SequentialCompositeSampler::addObjectsToSampler(const std::string& samplerName,
                                                     const std::vector<ObjectPtr>& objects) {
  auto* target = dynamic_cast<UniformRandomSampler*>(findMutable(samplerName));
  if (target == nullptr) {
    throw ConfigError("sampler " + quoteText(name()) + ": no uniform sub-sampler named " +
                      quoteText(samplerName));
  }
  checkNotPresent(objects);
  target->addObjects(objects);
  for (const ObjectPtr& object : objects) {
    objectNames_.insert(object->name);
  }
}

void SequentialCompositeSampler::hide(const std::vector<ObjectPtr>& objects) {
  checkNotPresent(objects);
  if (auto* existing = dynamic_cast<UniformRandomSampler*>(findMutable(kHideSamplerName))) {
    existing->addObjects(objects);
    for (const ObjectPtr& object : objects) {
      objectNames_.insert(object->name);
    }
    return;
  }
  UniformSamplerParams params;
  params.xRange = Eigen::Vector2d(-20.0, -10.0);
  params.yRange = Eigen::Vector2d(-20.0, -10.0);
  params.rotation = RotationSpec::fixed(0.0);
  params.zOffset = 10.0;
  params.ensureObjectBoundaryInRange = false;
  params.ensureValidPlacement = false;
  params.hides = true;
  // Hidden objects go far away whatever reference a call gives.
  SampleArgs args;
  args.reference = Reference::at(Eigen::Vector3d::Zero());
  args.onTop = true;
  appendSampler(std::make_shared<UniformRandomSampler>(kHideSamplerName, params, objects), args);
}

namespace {

/// A child's own sample_args, else what the composite was called with.
const Reference& childReference(const SampleArgs& args, const Reference& reference) {
  return args.reference ? *args.reference : reference;
}

bool childOnTop(const SampleArgs& args, bool onTop) { return args.onTop ? *args.onTop : onTop; }

}  // namespace

bool SequentialCompositeSampler::sample(SampleContext& context, const Reference& reference,
                                        bool onTop) const {
  for (const Child& child : children_) {
    if (!child.sampler->sample(context, childReference(child.args, reference),
                               childOnTop(child.args, onTop))) {
      return false;
    }
  }
  return true;
}

void SequentialCompositeSampler::forEachUniform(const Reference& reference, bool onTop,
                                                const UniformVisitor& visit) const {
  for (const Child& child : children_) {
    child.sampler->forEachUniform(childReference(child.args, reference),
                                  childOnTop(child.args, onTop), visit);
  }
}

std::vector<ObjectPtr> SequentialCompositeSampler::objects() const {
  std::vector<ObjectPtr> out;
  for (const Child& child : children_) {
    const std::vector<ObjectPtr> sub = child.sampler->objects();
    out.insert(out.end(), sub.begin(), sub.end());
  }
  return out;
}

void SequentialCompositeSampler::reset() {
  for (Child& child : children_) {
    child.sampler->reset();
  }
  objectNames_.clear();
}

void SequentialCompositeSampler::collectSamplers(std::vector<const PlacementSampler*>& out) const {
  out.push_back(this);
  for (const Child& child : children_) {
    child.sampler->collectSamplers(out);
  }
}

const PlacementSampler* SequentialCompositeSampler::find(const std::string& name,
                                                         SampleArgs* args) const {
  if (const PlacementSampler* self = PlacementSampler::find(name, args)) {
    return self;
  }
  for (const Child& child : children_) {
    if (child.sampler->name() == name) {
      if (args != nullptr) {
        *args = child.args;
      }
      return child.sampler.get();
    }
    if (const PlacementSampler* found = child.sampler->find(name, args)) {
      // In a full run this composite's own sample_args fill in what the inner ones leave unset.
      if (args != nullptr) {
        if (!args->reference) {
          args->reference = child.args.reference;
        }
        if (!args->onTop) {
          args->onTop = child.args.onTop;
        }
      }
      return found;
    }
  }
  return nullptr;
}

}  // namespace placement_samplers
