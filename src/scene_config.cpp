#include "placement_samplers/scene_config.hpp"

namespace placement_samplers {

const ObjectModel* SceneConfig::findObject(const std::string& name) const {
  return findObjectPtr(name).get();
}

ObjectPtr SceneConfig::findObjectPtr(const std::string& name) const {
  for (const ObjectPtr& object : objects) {
    if (object->name == name) {
      return object;
    }
  }
  return nullptr;
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
