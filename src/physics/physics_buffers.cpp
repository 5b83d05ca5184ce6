#include "physics/physics_buffers.hpp"

#include <mujoco/mjxmacro.h>

#include <climits>

namespace placement_samplers::detail {

PhysicsBuffers physicsBuffers(std::uint64_t contacts, std::uint64_t dofs) {
  PhysicsBuffers b;
  b.contacts = contacts;
  b.rows = 4 * contacts;
  // A third more than measured: a scene that overflows it grows the buffers too.
  b.stack = 4 * dofs * dofs + 16 * b.rows + 4096;
  return b;
}

std::uint64_t restingContacts(std::uint64_t bodyGeoms) { return 4 * bodyGeoms + 16; }

std::uint64_t bufferBytes(const PhysicsBuffers& b, std::uint64_t dofs) {
  // efc_AR (mjtNum) and efc_AR_colind (int) are rows x rows; efc_J, efc_JT (mjtNum) and their
  // column indices (int) rows x dofs.
  return 12 * b.rows * b.rows + 24 * b.rows * dofs + sizeof(mjtNum) * b.stack +
         sizeof(mjContact) * b.contacts;
}

bool fitsMujoco(const PhysicsBuffers& b, std::uint64_t dofs) {
  const std::uint64_t withoutStack = bufferBytes(b, dofs) - sizeof(mjtNum) * b.stack;
  return b.rows <= INT_MAX && b.stack <= INT_MAX && withoutStack < INT_MAX;
}

std::uint64_t dataBytes(const mjModel& model, const PhysicsBuffers& buffers) {
  mjModel sized = model;  // a shallow copy: only its sizes are read
  sized.nconmax = static_cast<int>(buffers.contacts);
  sized.njmax = static_cast<int>(buffers.rows);
  const mjModel* m = &sized;
  std::uint64_t bytes = sizeof(mjData) + sizeof(mjtNum) * buffers.stack;
  MJDATA_POINTERS_PREAMBLE(m)
#define X(type, name, nr, nc) \
  bytes += (sizeof(type) * static_cast<std::uint64_t>(m->nr) * (nc) + 63) / 64 * 64;
  MJDATA_POINTERS
#undef X
  return bytes;
}

std::string tooLargeMessage(std::uint64_t bytes, std::uint64_t bodies, std::uint64_t geoms,
                            std::uint32_t maxMemoryMb) {
  return "physics: simulating the scene takes an estimated " + std::to_string(bytes) +
         " bytes of MuJoCo data (" + std::to_string(bodies) + " free bodies with " +
         std::to_string(geoms) +
         " geoms; MuJoCo 2.2.2 preallocates contact arrays that grow with the square of the "
         "contacts), more than physics_max_memory_mb (" +
         std::to_string(maxMemoryMb) +
         " MiB = " + std::to_string(std::uint64_t{maxMemoryMb} << 20) + " bytes)";
}

}  // namespace placement_samplers::detail
