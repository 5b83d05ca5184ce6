#pragma once
// MuJoCo's global error handling and its compiler, shared by the MJCF object loader
// (mjcf_geometry.cpp) and the physics model (physics/physics_model.cpp). Private to the core.

#include <mujoco/mujoco.h>

#include <memory>
#include <string>

namespace placement_samplers::detail {

struct MujocoModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
using MujocoModelPtr = std::unique_ptr<mjModel, MujocoModelDeleter>;

struct MujocoDataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using MujocoDataPtr = std::unique_ptr<mjData, MujocoDataDeleter>;

struct MujocoVfsDeleter {
  void operator()(mjVFS* vfs) const {
    mj_deleteVFS(vfs);
    delete vfs;
  }
};
using MujocoVfsPtr = std::unique_ptr<mjVFS, MujocoVfsDeleter>;

/// An empty virtual file system.
MujocoVfsPtr makeVfs();

/// Adds a file called @p name holding @p data to @p vfs.
/// @throw std::runtime_error when the file system is full or the name is taken
void addVfsFile(mjVFS& vfs, const std::string& name, const std::string& data);

/// Installs, once per process and for good, MuJoCo handlers that turn an error into a
/// std::runtime_error (MuJoCo's own would end the process) and drop warnings (MuJoCo's own
/// print them on stdout, which is the CLI's output). Thread-safe; called by compileMjcf and
/// before the first simulation. Warnings stay counted in mjData::warning.
void installMujocoHandlers();

/// Compiles the MJCF document @p file (a path, or a name in @p vfs, which MuJoCo looks up
/// first) under a process-wide lock: MuJoCo's compiler keeps global state.
/// @throw std::runtime_error with MuJoCo's reason, on one line
MujocoModelPtr compileMjcf(const std::string& file, const mjVFS* vfs);

}  // namespace placement_samplers::detail
