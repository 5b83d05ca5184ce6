#pragma once
// The sizes of MuJoCo's preallocated buffers for a simulated scene, and what they take.
// MuJoCo 2.2.2 allocates rows x rows constraint arrays per simulation (mjData), so they are
// sized by what the scene touches and grown when a scene needs more. Private to the core.

#include <mujoco/mujoco.h>

#include <cstdint>
#include <string>

namespace placement_samplers::detail {

/// MuJoCo's preallocated buffers of one simulation (<size> of the model, mjData's arrays).
struct PhysicsBuffers {
  std::uint64_t contacts = 0;  ///< nconmax
  std::uint64_t rows = 0;      ///< njmax, constraint rows
  std::uint64_t stack = 0;     ///< nstack [mjtNum]
};

/// The buffers for @p contacts contacts of a scene with @p dofs degrees of freedom: four
/// constraint rows per contact (pyramidal friction cones, condim 3), and a stack for the
/// solver (MuJoCo 2.2.2 takes about 3 dofs^2 + 11 rows of it).
PhysicsBuffers physicsBuffers(std::uint64_t contacts, std::uint64_t dofs);

/// The contacts of the first buffers of a scene whose free bodies have @p bodyGeoms geoms:
/// four each (a box resting on a plane has four) and a few more. Fixtures add none: they
/// touch nothing but the bodies.
std::uint64_t restingContacts(std::uint64_t bodyGeoms);

/// Bytes of MuJoCo's data that grow with the buffers, known before a model is compiled (the
/// arrays of rows x rows and rows x dofs, the contacts, the stack): a lower bound of its size.
std::uint64_t bufferBytes(const PhysicsBuffers& buffers, std::uint64_t dofs);

/// True when MuJoCo 2.2.2 can allocate @p buffers: it counts them, and its data's bytes without
/// the stack, in ints.
bool fitsMujoco(const PhysicsBuffers& buffers, std::uint64_t dofs);

/// Bytes of the mjData that mj_makeData makes for @p model with @p buffers instead of its own:
/// its arrays as MuJoCo 2.2.2 lays them out (an upper bound, by at most 64 bytes each) and its
/// stack.
std::uint64_t dataBytes(const mjModel& model, const PhysicsBuffers& buffers);

/// "physics: simulating the scene takes an estimated N bytes ..., more than
/// physics_max_memory_mb (M MiB)": the refusal of a request whose simulation does not fit.
std::string tooLargeMessage(std::uint64_t bytes, std::uint64_t bodies, std::uint64_t geoms,
                            std::uint32_t maxMemoryMb);

}  // namespace placement_samplers::detail
