#include "placement_samplers/config/config_builder.hpp"

#include <set>

#include "config/builder_parts.hpp"
#include "placement_samplers/collision/make_collision_checker.hpp"
#include "placement_samplers/config/object_config.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace {

/// State of one build: the names that a reference may use at each point of the sampling order.
class Builder {
 public:
  Builder(const ConfigNode& root, SceneConfig& config, const BuildOptions& options)
      : root_(root),
        config_(config),
        options_(options),
        meshes_(options.packageResolver, options.baseDirectory) {}

  void objects(const ConfigNode& node) {
    for (const auto& entry : node.entries()) {
      if (!isValidName(entry.first)) {
        entry.second.fail("object names must match [A-Za-z0-9_-]+");
      }
      config_.objects.push_back(std::make_shared<ObjectModel>(
          parseObject(entry.first, entry.second, options_, meshes_, &config_.warnings)));
    }
    config_.indexObjects();
  }

  void fixtures(const ConfigNode& node) {
    for (const ConfigNode& f : node.elements()) {
      f.checkKeys({"name", "object", "position", "orientation"});
      FixtureSpec fixture;
      fixture.name = f.at("name").asString();
      if (!isValidName(fixture.name)) {
        f.at("name").fail("fixture names must match [A-Za-z0-9_-]+, got " +
                          quoteText(fixture.name));
      }
      if (config_.findObject(fixture.name) != nullptr || available_.count(fixture.name) != 0) {
        f.at("name").fail(quoteText(fixture.name) + " is already the name of an object or fixture");
      }
      fixture.objectName = f.at("object").asString();
      const ObjectModel* object = config_.findObject(fixture.objectName);
      if (object == nullptr) {
        f.at("object").fail("unknown object " + quoteText(fixture.objectName) +
                            " (not under objects)");
      }
      fixtureObjects_.insert(fixture.objectName);
      fixture.position = parseBoundedVector(f.at("position"), "coordinates");
      if (const ConfigNode* q = f.get("orientation")) {
        fixture.orientation = parseQuaternion(*q);
      }
      fixture.object =
          std::make_shared<ObjectModel>(reorientedObject(*object, fixture.orientation));
      available_.insert(fixture.name);
      config_.fixtures.push_back(std::move(fixture));
    }
  }

  /// Appends the samplers of @p list to @p parent; @p inherited is the reference a call
  /// passes down (set when an enclosing composite's sample_args names one).
  void samplers(const ConfigNode& list, SequentialCompositeSampler& parent,
                const std::optional<Reference>& inherited) {
    for (const ConfigNode& item : list.elements()) {
      const detail::SamplerItem s = detail::resolveSamplerItem(root_, item);
      SampleArgs args = sampleArgs(*s.params);
      const std::optional<Reference> effective = args.reference ? args.reference : inherited;
      const ConfigNode* typeNode = s.params->get("type") ? s.params->get("type") : s.typeNode;
      const std::string type = typeNode ? typeNode->asString() : "uniform";
      if (type == "uniform") {
        parent.appendSampler(uniform(s, effective), args);
      } else if (type == "sequential") {
        detail::checkSamplerKeys(s, {"type", "samplers", "sample_args"});
        auto composite = std::make_shared<SequentialCompositeSampler>(samplerName(s));
        samplers(s.params->at("samplers"), *composite, effective);
        wrap(*s.params, [&] { parent.appendSampler(composite, args); });
      } else {
        typeNode->fail("expected uniform or sequential, got " + quoteText(type));
      }
    }
  }

  void hide(const ConfigNode& node) {
    std::vector<ObjectPtr> objects;
    for (const ConfigNode& n : node.elements()) {
      objects.push_back(object(n));
      config_.hidden.push_back(n.asString());
    }
    wrap(node, [&] { config_.root->hide(objects); });
  }

  /// Objects that no sampler places, that are not hidden and that no configured fixture uses:
  /// a warning each.
  void warnUnplaced() {
    for (const ObjectPtr& object : config_.objects) {
      // The geometry of a configured fixture is there on purpose.
      if (assigned_.count(object->name) != 0 || fixtureObjects_.count(object->name) != 0) {
        continue;
      }
      config_.warnings.push_back("object " + quoteText(object->name) +
                                 " is placed by no sampler, not hidden and no fixture's geometry:"
                                 " it appears in no scene unless a request uses it for a fixture");
    }
  }

 private:
  template <typename F>
  void wrap(const ConfigNode& node, F f) {
    try {
      f();
    } catch (const ConfigError& e) {
      node.fail(e.what());
    }
  }

  std::string samplerName(const detail::SamplerItem& s) {
    const ConfigNode& n = *s.nameNode;
    const std::string& name = s.name;
    if (name.empty()) {
      n.fail("expected a non-empty sampler name");
    }
    if (name == kRootSamplerName || name == SequentialCompositeSampler::kHideSamplerName) {
      n.fail("sampler name " + quoteText(name) + " is reserved (" + kRootSamplerName +
             " is the root, " + SequentialCompositeSampler::kHideSamplerName +
             " places the hidden objects)");
    }
    if (!samplerNames_.insert(name).second) {
      n.fail("sampler name " + quoteText(name) + " is already used by another sampler");
    }
    return name;
  }

  ObjectPtr object(const ConfigNode& n) {
    const std::string& name = n.asString();
    ObjectPtr object = config_.findObjectPtr(name);
    if (!object) {
      n.fail("unknown object " + quoteText(name) + " (not under objects)");
    }
    if (!assigned_.insert(name).second) {
      n.fail("object " + quoteText(name) + " is already placed by another sampler or hidden");
    }
    return object;
  }

  SampleArgs sampleArgs(const ConfigNode& s) {
    SampleArgs args;
    const ConfigNode* a = s.get("sample_args");
    if (a == nullptr) {
      return args;
    }
    a->checkKeys({"reference", "on_top"});
    if (const ConfigNode* r = a->get("reference")) {
      if (r->isString()) {
        args.reference = Reference::named(r->asString());
        referenceNodes_.push_back(r);
      } else if (r->isList()) {
        args.reference = Reference::at(parseBoundedVector(*r, "coordinates"));
      } else {
        r->fail("expected an object or fixture name, or a point [x, y, z]");
      }
    }
    if (const ConfigNode* t = a->get("on_top")) {
      args.onTop = t->asBool();
    }
    return args;
  }

  std::shared_ptr<UniformRandomSampler> uniform(const detail::SamplerItem& item,
                                                const std::optional<Reference>& reference) {
    detail::checkSamplerKeys(
        item, {"type", "objects", "x_range", "y_range", "rotation", "rotation_axis",
               "ensure_object_boundary_in_range", "ensure_valid_placement", "reference_pos",
               "z_offset", "sample_args", "max_attempts", "region", "keep_out", "strategy",
               "resting", "min_probability", "allow_rolling", "relations"});
    const std::string name = samplerName(item);
    const ConfigNode& s = *item.params;
    const UniformSamplerParams p = detail::parseUniformParams(s, config_.maxAttempts, name);
    // A named reference must exist before this sampler runs: a fixture or an earlier object.
    if (reference && reference->kind == Reference::Kind::Name &&
        available_.count(reference->name) == 0) {
      const ConfigNode* where = &s;
      for (const ConfigNode* r : referenceNodes_) {
        if (r->asString() == reference->name) {
          where = r;
        }
      }
      where->fail("reference " + quoteText(reference->name) + " of sampler " + quoteText(name) +
                  " is neither a fixture nor an object placed by an earlier sampler");
    }
    std::vector<ObjectPtr> objects;
    if (const ConfigNode* list = s.get("objects")) {
      for (const ConfigNode& n : list->elements()) {
        objects.push_back(object(n));
      }
    }
    if (const ConfigNode* list = s.get("relations")) {
      detail::checkRelationTargets(*list, p.relations, name, objects, available_, config_);
    }
    std::shared_ptr<UniformRandomSampler> sampler;
    try {
      sampler = std::make_shared<UniformRandomSampler>(name, p, objects);
    } catch (const ConfigError& e) {
      // Point at the parameter the sampler complains about when it names one.
      const std::string message = e.what();
      const ConfigNode* where = &s;
      for (const char* key : {"x_range", "y_range", "rotation", "reference_pos", "z_offset",
                              "max_attempts", "region", "relations"}) {
        if (message.find(std::string("': ") + key + " ") != std::string::npos && s.get(key)) {
          where = s.get(key);
        }
      }
      where->fail(message);
    }
    if (p.surface) {
      bindSurfaces(*sampler, *p.surface, objects, s.at("region"));
    }
    for (const ObjectPtr& o : objects) {
      available_.insert(o->name);
    }
    return sampler;
  }

  /// Finds the surfaces of a surface region's target when the configuration holds it: a
  /// configured fixture, or an object an earlier sampler places. Any other name must be a
  /// request's fixture (SceneGenerator::prepare() checks it).
  void bindSurfaces(UniformRandomSampler& sampler, const SurfaceRegion& region,
                    const std::vector<ObjectPtr>& objects, const ConfigNode& node) {
    const ConfigNode& of = node.at("of");
    for (const ObjectPtr& o : objects) {
      if (o->name == region.of) {
        of.fail("region.of " + quoteText(region.of) + " is an object of sampler " +
                quoteText(sampler.name()) +
                " itself: name a fixture or an object an earlier sampler places");
      }
    }
    for (const FixtureSpec& f : config_.fixtures) {
      if (f.name == region.of) {
        wrap(node, [&] { sampler.bindSurfaces(*f.object, f.position, f.orientation, false); });
        return;
      }
    }
    if (const ObjectModel* object = config_.findObject(region.of)) {
      if (available_.count(region.of) == 0) {
        of.fail("region.of " + quoteText(region.of) + " of sampler " + quoteText(sampler.name()) +
                " is an object that no earlier sampler places: it is not in the scene yet");
      }
      wrap(node, [&] {
        sampler.bindSurfaces(*object, Eigen::Vector3d::Zero(), object->initOrientation, true);
      });
      return;
    }
    config_.warnings.push_back("sampler " + quoteText(sampler.name()) + ": region.of " +
                               quoteText(region.of) +
                               " is neither a configured fixture nor an object: every request "
                               "must give a fixture of that name");
  }

  const ConfigNode& root_;
  SceneConfig& config_;
  const BuildOptions& options_;
  MeshLoader meshes_;                     // each mesh file read once per build
  std::set<std::string> available_;       // fixtures and objects placed so far, in sampling order
  std::set<std::string> assigned_;        // objects that have a sampler
  std::set<std::string> fixtureObjects_;  // objects whose geometry a configured fixture uses
  std::set<std::string> samplerNames_;
  std::vector<const ConfigNode*> referenceNodes_;
};

}  // namespace

std::shared_ptr<SceneConfig> buildSceneConfig(const ConfigNode& root) {
  return buildSceneConfig(root, BuildOptions());
}

std::shared_ptr<SceneConfig> buildSceneConfig(const ConfigNode& root, const BuildOptions& options) {
  detail::checkTreeSize(root);
  root.checkKeys(detail::allowedTopLevelKeys(root));
  auto config = std::make_shared<SceneConfig>();
  detail::readSettings(root, *config);
  Builder builder(root, *config, options);
  if (const ConfigNode* n = root.get("objects")) {
    builder.objects(*n);
  }
  if (const ConfigNode* n = root.get("fixtures")) {
    builder.fixtures(*n);
  }
  config->root = std::make_shared<SequentialCompositeSampler>(kRootSamplerName);
  if (const ConfigNode* n = root.get("samplers")) {
    builder.samplers(*n, *config->root, std::nullopt);
  }
  if (const ConfigNode* n = root.get("hide")) {
    builder.hide(*n);
  }
  builder.warnUnplaced();
  return config;
}

}  // namespace placement_samplers
