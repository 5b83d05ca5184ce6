#include "placement_samplers/sampling/scene_config.hpp"

namespace placement_samplers {

const ObjectModel* SceneConfig::findObject(std::string_view name) const {
  return findObjectPtr(name).get();
}

ObjectPtr SceneConfig::findObjectPtr(std::string_view name) const {
  // The index is used only while it matches the objects.
  if (!objectIndex_.empty() && objectIndex_.size() == objects.size()) {
    const auto it = objectIndex_.find(std::string(name));
    if (it == objectIndex_.end()) {
      return nullptr;
    }
    const ObjectPtr& object = objects[it->second];
    if (object->name == name) {
      return object;
    }
    // Out of date: fall through to the scan.
  }
  for (const ObjectPtr& object : objects) {
    if (object->name == name) {
      return object;
    }
  }
  return nullptr;
}

void SceneConfig::indexObjects() {
  objectIndex_.clear();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    objectIndex_.emplace(objects[i]->name, i);
  }
}

bool isValidName(const std::string& name) {
  if (name.empty()) {
    return false;
  }
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    if (!ok) {
      return false;
    }
  }
  return true;
}

}  // namespace placement_samplers
