#include <unordered_set>

#include "config/builder_parts.hpp"
#include "placement_samplers/limits.hpp"

namespace placement_samplers::detail {
namespace {

/// A list item that only names its sampler: {name: N} or {name: N, type: T}.
bool isNameOnly(const ConfigNode& item) {
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

void collectNamedSamplers(const ConfigNode& root, const ConfigNode& list,
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
        collectNamedSamplers(root, *inner, names, seen, depth + 1);
      }
    }
  }
}

}  // namespace

/// The names of samplers whose parameters live in a top-level map of their own (the list
/// item is only the name, as costmap_2d's plugin lists): `rosparam set` can then change one
/// parameter. Lenient: the build reports what is malformed.
void collectNamedSamplers(const ConfigNode& root, const ConfigNode& list,
                          std::vector<std::string>& names) {
  std::unordered_set<std::string> seen(names.begin(), names.end());
  collectNamedSamplers(root, list, names, seen, 0);
}

SamplerItem resolveSamplerItem(const ConfigNode& root, const ConfigNode& item) {
  SamplerItem s{&item, nullptr, nullptr, false, ""};
  if (item.isString() || (isNameOnly(item) && root.get(item.at("name").asString()))) {
    s.named = true;
    s.nameNode = item.isString() ? &item : &item.at("name");
    s.typeNode = item.isString() ? nullptr : item.get("type");
    s.name = s.nameNode->asString();
    if (isTopLevelKey(s.name)) {
      s.nameNode->fail("sampler name '" + s.name +
                       "' is a top-level key of the configuration; choose another name");
    }
    s.params = root.get(s.name);
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
void checkSamplerKeys(const SamplerItem& s, std::vector<std::string> allowed) {
  if (!s.named) {
    allowed.insert(allowed.begin(), "name");
  }
  s.params->checkKeys(allowed);
}

}  // namespace placement_samplers::detail
