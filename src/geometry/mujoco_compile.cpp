#include "geometry/mujoco_compile.hpp"

#include <array>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <stdexcept>

namespace placement_samplers::detail {
namespace {

[[noreturn]] void throwMujocoError(const char* message) { throw std::runtime_error(message); }
void ignoreMujocoWarning(const char*) {}

}  // namespace

MujocoVfsPtr makeVfs() {
  MujocoVfsPtr vfs(new mjVFS);
  mj_defaultVFS(vfs.get());
  return vfs;
}

void addVfsFile(mjVFS& vfs, const std::string& name, const std::string& data) {
  if (mj_makeEmptyFileVFS(&vfs, name.c_str(), static_cast<int>(data.size())) != 0) {
    throw std::runtime_error("cannot add " + name + " to MuJoCo's virtual file system");
  }
  std::memcpy(vfs.filedata[mj_findFileVFS(&vfs, name.c_str())], data.data(), data.size());
}

void installMujocoHandlers() {
  // For good, not around each call: simulations run on several threads at once, and a
  // handler swapped back and forth would race with them.
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = throwMujocoError;
    mju_user_warning = ignoreMujocoWarning;
    // Box on box by the general convex collider (MPR with multiccd, as box on mesh): MuJoCo
    // 2.2.2's own box-box contacts toppled a standing box in about 1 % of scenes (a 5 x 5 x
    // 16 cm carton on a bin's floor, wherever it stood; 0 of 2000 after this change).
    mjCOLLISIONFUNC[mjGEOM_BOX][mjGEOM_BOX] = mjCOLLISIONFUNC[mjGEOM_BOX][mjGEOM_MESH];
  });
}

MujocoModelPtr compileMjcf(const std::string& file, const mjVFS* vfs) {
  installMujocoHandlers();
  static std::mutex compilerMutex;
  std::array<char, 1024> error{};
  MujocoModelPtr model;
  {
    std::lock_guard<std::mutex> lock(compilerMutex);
    try {
      model.reset(mj_loadXML(file.c_str(), vfs, error.data(), static_cast<int>(error.size())));
    } catch (const std::exception& e) {
      std::snprintf(error.data(), error.size(), "%s", e.what());
    }
  }
  if (!model) {
    std::string reason = error.data();
    while (!reason.empty() && (reason.back() == '\n' || reason.back() == ' ')) {
      reason.pop_back();
    }
    // MuJoCo's message has lines: "Error: ... \nObject name = ..., line = ...".
    for (std::size_t at = reason.find('\n'); at != std::string::npos; at = reason.find('\n')) {
      reason.replace(at, 1, "; ");
    }
    throw std::runtime_error(reason);
  }
  return model;
}

}  // namespace placement_samplers::detail
