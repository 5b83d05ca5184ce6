#include "placement_samplers/config/config_builder.hpp"

#include <algorithm>
#include <iterator>
#include <limits>
#include <set>
#include <sstream>
#include <unordered_set>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/collision/make_collision_checker.hpp"
#include "placement_samplers/config/object_config.hpp"
#include "placement_samplers/text.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"

namespace placement_samplers {
namespace {

/// The keys of the configuration's top level, besides the named samplers' maps.
constexpr const char* kTopLevelKeys[] = {"frame_id",
                                         "tf_prefix",
                                         "seed",
                                         "collision_check",
                                         "collision_margin",
                                         "max_attempts",
                                         "objects",
                                         "fixtures",
                                         "samplers",
                                         "hide",
                                         "threads",
                                         "max_scenes_per_request",
                                         "max_request_seconds",
                                         "max_fixtures_per_request",
                                         "max_placements_per_request",
                                         "tf_static",
                                         "tf_rate"};

/// Refuses a tree (from rosparam or YAML) of more than limits::kConfigValues values or nested
/// more than limits::kConfigDepth levels, walking it without recursion.
void checkTreeSize(const ConfigNode& root) {
  std::vector<std::pair<const ConfigNode*, int>> stack{{&root, 1}};
  std::size_t values = 0;
  while (!stack.empty()) {
    const ConfigNode& node = *stack.back().first;
    const int depth = stack.back().second;
    stack.pop_back();
    if (++values > limits::kConfigValues) {
      root.fail("more than " + std::to_string(limits::kConfigValues) +
                " values (maps, lists and scalars)");
    }
    if (depth > limits::kConfigDepth) {
      node.fail("nested too deep (more than " + std::to_string(limits::kConfigDepth) + " levels)");
    }
    if (node.isMap()) {
      for (const auto& entry : node.entries()) {
        stack.emplace_back(&entry.second, depth + 1);
      }
    } else if (node.isList()) {
      for (const ConfigNode& element : node.elements()) {
        stack.emplace_back(&element, depth + 1);
      }
    }
  }
}

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
      config_.objects.push_back(
          std::make_shared<ObjectModel>(parseObject(entry.first, entry.second, options_, meshes_)));
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
      const SamplerItem s = resolve(item);
      SampleArgs args = sampleArgs(*s.params);
      const std::optional<Reference> effective = args.reference ? args.reference : inherited;
      const ConfigNode* typeNode = s.params->get("type") ? s.params->get("type") : s.typeNode;
      const std::string type = typeNode ? typeNode->asString() : "uniform";
      if (type == "uniform") {
        parent.appendSampler(uniform(s, effective), args);
      } else if (type == "sequential") {
        checkSamplerKeys(s, {"type", "samplers", "sample_args"});
        auto composite = std::make_shared<SequentialCompositeSampler>(samplerName(s));
        samplers(s.params->at("samplers"), *composite, effective);
        wrap(*s.params, [&] { parent.appendSampler(composite, args); });
      } else {
        typeNode->fail("expected uniform or sequential, got " + quoteText(type));
      }
    }
  }

  /// The names of samplers whose parameters live in a top-level map of their own (the list
  /// item is only the name, as costmap_2d's plugin lists): `rosparam set` can then change one
  /// parameter. Lenient: the build reports what is malformed.
  static void namedSamplers(const ConfigNode& root, const ConfigNode& list,
                            std::vector<std::string>& names) {
    std::unordered_set<std::string> seen(names.begin(), names.end());
    namedSamplers(root, list, names, seen, 0);
  }

 private:
  static void namedSamplers(const ConfigNode& root, const ConfigNode& list,
                            std::vector<std::string>& names, std::unordered_set<std::string>& seen,
                            int depth) {
    if (!list.isList() || depth > limits::kConfigDepth) {
      return;
    }
    for (const ConfigNode& item : list.elements()) {
      const std::string* name = nullptr;
      if (item.isString()) {
        name = &item.asString();
      } else if (isNameOnly(item) && item.at("name").isString()) {
        name = &item.at("name").asString();
      }
      const ConfigNode* params = name ? root.get(*name) : (item.isMap() ? &item : nullptr);
      if (name && seen.insert(*name).second) {
        names.push_back(*name);
      }
      if (params && params->isMap()) {
        if (const ConfigNode* inner = params->get("samplers")) {
          namedSamplers(root, *inner, names, seen, depth + 1);
        }
      }
    }
  }

 public:
  void hide(const ConfigNode& node) {
    std::vector<ObjectPtr> objects;
    for (const ConfigNode& n : node.elements()) {
      objects.push_back(object(n));
      config_.hidden.push_back(n.asString());
    }
    wrap(node, [&] { config_.root->hide(objects); });
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

  /// One item of a samplers list: where its parameters are read and what names it.
  struct SamplerItem {
    const ConfigNode* params;    ///< the inline map, or the top-level map of its name
    const ConfigNode* nameNode;  ///< errors about the name point here
    const ConfigNode* typeNode;  ///< `type` given in the list item of the named form, or null
    bool named;                  ///< parameters in a top-level map of its name
    std::string name;
  };

  /// A list item that only names its sampler: {name: N} or {name: N, type: T}.
  static bool isNameOnly(const ConfigNode& item) {
    if (!item.isMap() || item.get("name") == nullptr) {
      return false;
    }
    for (const auto& entry : item.entries()) {
      if (entry.first != "name" && entry.first != "type") {
        return false;
      }
    }
    return true;
  }

  SamplerItem resolve(const ConfigNode& item) {
    SamplerItem s{&item, nullptr, nullptr, false, ""};
    if (item.isString() || (isNameOnly(item) && root_.get(item.at("name").asString()))) {
      s.named = true;
      s.nameNode = item.isString() ? &item : &item.at("name");
      s.typeNode = item.isString() ? nullptr : item.get("type");
      s.name = s.nameNode->asString();
      if (isTopLevelKey(s.name)) {
        s.nameNode->fail("sampler name '" + s.name +
                         "' is a top-level key of the configuration; choose another name");
      }
      s.params = root_.get(s.name);
      if (s.params == nullptr) {
        s.nameNode->fail("sampler '" + s.name + "' has no parameters: expected a map '" + s.name +
                         "' at the top level of the configuration");
      }
      if (!s.params->isMap()) {
        s.params->fail("expected the parameters of sampler '" + s.name + "' (a map), got " +
                       ConfigNode::typeName(s.params->type()));
      }
      if (s.typeNode && s.params->get("type")) {
        s.params->at("type").fail("the type of sampler '" + s.name +
                                  "' is also given in its list item; give it once");
      }
      return s;
    }
    if (!item.isMap()) {
      item.fail(
          "expected a sampler: a map of its parameters, or its name with the parameters "
          "in a top-level map of that name");
    }
    s.nameNode = &item.at("name");
    s.name = s.nameNode->asString();
    return s;
  }

  /// Unknown keys are typos; `name` is the map's key in the named form.
  static void checkSamplerKeys(const SamplerItem& s, std::vector<std::string> allowed) {
    if (!s.named) {
      allowed.insert(allowed.begin(), "name");
    }
    s.params->checkKeys(allowed);
  }

  static bool isTopLevelKey(const std::string& key) {
    for (const char* k : kTopLevelKeys) {
      if (key == k) {
        return true;
      }
    }
    return false;
  }

  std::string samplerName(const SamplerItem& s) {
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

  std::shared_ptr<UniformRandomSampler> uniform(const SamplerItem& item,
                                                const std::optional<Reference>& reference) {
    checkSamplerKeys(item, {"type", "objects", "x_range", "y_range", "rotation", "rotation_axis",
                            "ensure_object_boundary_in_range", "ensure_valid_placement",
                            "reference_pos", "z_offset", "sample_args", "max_attempts"});
    const std::string name = samplerName(item);
    const ConfigNode& s = *item.params;
    UniformSamplerParams p;
    p.maxAttempts = config_.maxAttempts;
    if (const ConfigNode* n = s.get("x_range")) {
      p.xRange = range(*n);
    }
    if (const ConfigNode* n = s.get("y_range")) {
      p.yRange = range(*n);
    }
    if (const ConfigNode* n = s.get("rotation")) {
      if (n->type() == ConfigNode::Type::Null) {
        p.rotation = RotationSpec::full();
      } else if (n->isList()) {
        const std::vector<double> v = n->asNumbers(2);
        p.rotation = RotationSpec::range(v[0], v[1]);
      } else if (n->isNumber()) {
        p.rotation = RotationSpec::fixed(n->asDouble());
      } else {
        n->fail("expected an angle in [rad], a pair [min, max] in [rad], or nothing for U(0, 2pi)");
      }
    }
    if (const ConfigNode* n = s.get("rotation_axis")) {
      const std::string& axis = n->asString();
      if (axis != "x" && axis != "y" && axis != "z") {
        n->fail("expected x, y or z, got " + quoteText(axis));
      }
      p.rotationAxis = axis[0] - 'x';
    }
    if (const ConfigNode* n = s.get("ensure_object_boundary_in_range")) {
      p.ensureObjectBoundaryInRange = n->asBool();
    }
    if (const ConfigNode* n = s.get("ensure_valid_placement")) {
      p.ensureValidPlacement = n->asBool();
    }
    if (const ConfigNode* n = s.get("reference_pos")) {
      p.referencePos = n->asVector3();
    }
    if (const ConfigNode* n = s.get("z_offset")) {
      p.zOffset = n->asDouble();
    }
    if (const ConfigNode* n = s.get("max_attempts")) {
      p.maxAttempts =
          static_cast<std::uint32_t>(n->asInt(1, std::numeric_limits<std::uint32_t>::max()));
    }
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
    std::shared_ptr<UniformRandomSampler> sampler;
    try {
      sampler = std::make_shared<UniformRandomSampler>(name, p, objects);
    } catch (const ConfigError& e) {
      // Point at the parameter the sampler complains about when it names one.
      const std::string message = e.what();
      const ConfigNode* where = &s;
      for (const char* key :
           {"x_range", "y_range", "rotation", "reference_pos", "z_offset", "max_attempts"}) {
        if (message.find(std::string("': ") + key + " ") != std::string::npos && s.get(key)) {
          where = s.get(key);
        }
      }
      where->fail(message);
    }
    for (const ObjectPtr& o : objects) {
      available_.insert(o->name);
    }
    return sampler;
  }

  static Eigen::Vector2d range(const ConfigNode& n) {
    const std::vector<double> v = n.asNumbers(2);
    if (v[0] > v[1]) {
      std::ostringstream out;
      out << "expected [min, max] with min <= max, got [" << v[0] << ", " << v[1] << "]";
      n.fail(out.str());
    }
    return Eigen::Vector2d(v[0], v[1]);
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

 public:
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
};

}  // namespace

CollisionMode parseCollisionMode(const ConfigNode& node) {
  const std::string& mode = node.asString();
  if (mode == "radius") {
    return CollisionMode::Radius;
  }
  if (mode == "fcl") {
    return CollisionMode::Fcl;
  }
  if (mode == "radius_and_fcl") {
    return CollisionMode::RadiusAndFcl;
  }
  node.fail("expected radius, fcl or radius_and_fcl, got " + quoteText(mode));
}

std::shared_ptr<SceneConfig> buildSceneConfig(const ConfigNode& root) {
  return buildSceneConfig(root, BuildOptions());
}

std::shared_ptr<SceneConfig> buildSceneConfig(const ConfigNode& root, const BuildOptions& options) {
  checkTreeSize(root);
  std::vector<std::string> allowed(std::begin(kTopLevelKeys), std::end(kTopLevelKeys));
  if (const ConfigNode* n = root.get("samplers")) {
    Builder::namedSamplers(root, *n, allowed);
  }
  root.checkKeys(allowed);
  auto config = std::make_shared<SceneConfig>();
  if (const ConfigNode* n = root.get("frame_id")) {
    config->frameId = n->asString();
    if (config->frameId.empty()) {
      n->fail("expected a non-empty frame name");
    }
  }
  if (const ConfigNode* n = root.get("tf_prefix")) {
    config->tfPrefix = n->asString();
    if (!config->tfPrefix->empty() && config->tfPrefix->front() == '/') {
      n->fail("expected a prefix without a leading '/' (tf2 frame names have none), got '" +
              *config->tfPrefix + "'");
    }
  }
  if (const ConfigNode* n = root.get("seed")) {
    config->seed = n->asUInt64();
  }
  if (const ConfigNode* n = root.get("collision_check")) {
    config->collisionCheck = parseCollisionMode(*n);
  }
  if (const ConfigNode* n = root.get("collision_margin")) {
    config->collisionMargin = n->asDouble();
    if (config->collisionMargin < 0.0) {
      n->fail("expected a non-negative clearance in [m]");
    }
    if (config->collisionMargin > limits::kCoordinate) {
      std::ostringstream out;
      out << "expected a non-negative clearance in [m] of at most " << limits::kCoordinate
          << ", got " << config->collisionMargin;
      n->fail(out.str());
    }
  }
  if (const ConfigNode* n = root.get("max_attempts")) {
    config->maxAttempts =
        static_cast<std::uint32_t>(n->asInt(1, std::numeric_limits<std::uint32_t>::max()));
  }
  if (const ConfigNode* n = root.get("threads")) {
    config->threads = static_cast<unsigned>(n->asInt(1, 64));
  }
  if (const ConfigNode* n = root.get("max_scenes_per_request")) {
    config->maxScenesPerRequest = static_cast<std::uint32_t>(n->asInt(1, 100000000));
  }
  if (const ConfigNode* n = root.get("max_request_seconds")) {
    config->maxRequestSeconds = n->asDouble();
    // Bounded, so that now + the limit is a time point the clock can hold.
    if (config->maxRequestSeconds <= 0.0) {
      n->fail("expected a positive duration in [s]");
    }
    if (config->maxRequestSeconds > limits::kRequestSeconds) {
      std::ostringstream out;
      out << "expected a positive duration in [s] of at most " << limits::kRequestSeconds
          << ", got " << config->maxRequestSeconds;
      n->fail(out.str());
    }
  }
  if (const ConfigNode* n = root.get("max_fixtures_per_request")) {
    config->maxFixturesPerRequest = static_cast<std::uint32_t>(n->asInt(0, 1000000));
  }
  if (const ConfigNode* n = root.get("max_placements_per_request")) {
    config->maxPlacementsPerRequest = static_cast<std::uint64_t>(n->asInt(1, 1000000000));
  }
  if (const ConfigNode* n = root.get("tf_static")) {
    config->tfStatic = n->asBool();
  }
  if (const ConfigNode* n = root.get("tf_rate")) {
    config->tfRate = n->asDouble();
    if (!(config->tfRate >= 0.1 && config->tfRate <= 1000.0)) {
      n->fail("expected a rate in [0.1, 1000] [Hz]");
    }
  }
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
  // Fails now rather than on the first request.
  checkCollisionMode(config->collisionCheck, config->collisionMargin);
  return config;
}

}  // namespace placement_samplers
