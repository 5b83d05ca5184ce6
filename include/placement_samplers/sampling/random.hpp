#pragma once

#include <cstdint>

#include "placement_samplers/sampling/pcg64.hpp"

namespace placement_samplers {

/// The one random engine type of the library: numpy's PCG64. Scene i of request seed S draws
/// from sceneEngine(S, i), the generator of `numpy.random.default_rng([S, i])`, so robosuite's
/// samplers given that generator draw the same numbers (README, "robosuite semantics").
using Engine = Pcg64;

/// A double in [0, 1) from the top 53 bits of one draw: numpy's next_double.
inline double uniform01(Engine& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }

/// A double in [low, high) (low when low == high), from one draw: numpy's
/// Generator.uniform(low, high), `low + (high - low) * next_double`.
inline double uniform(Engine& engine, double low, double high) {
  return low + (high - low) * uniform01(engine);
}

/// The engine of scene @p index of a request with seed @p seed: numpy's
/// default_rng([seed, index]). Scene i is the same whatever the number of scenes or threads.
inline Engine sceneEngine(std::uint64_t seed, std::uint64_t index) {
  return Engine::forScene(seed, index);
}

/// The engine of the hidden objects of that scene, a stream apart from the scene's (robosuite's
/// hide sampler has a generator of its own): numpy's
/// default_rng(SeedSequence([seed, index]).spawn(1)[0]).
Engine hiddenEngine(std::uint64_t seed, std::uint64_t index);

/// A non-zero seed from std::random_device, for requests and configurations that give seed 0.
std::uint64_t randomSeed();

}  // namespace placement_samplers
