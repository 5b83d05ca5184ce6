#pragma once

#include <cstdint>
#include <random>

namespace placement_samplers {

/// The one random engine type of the library. Every scene owns one, seeded from (seed, index).
using Engine = std::mt19937_64;

/// A double in [0, 1) from the top 53 bits of one draw. Written out rather than taken from
/// std::uniform_real_distribution so that a seed gives the same scene with any standard library.
inline double uniform01(Engine& engine) {
  return static_cast<double>(engine() >> 11) * 0x1.0p-53;
}

/// A double in [low, high) (exactly low when low == high), from one draw.
inline double uniform(Engine& engine, double low, double high) {
  return low + (high - low) * uniform01(engine);
}

/// The seed of scene @p index of a request with seed @p requestSeed: scene i is the same scene
/// whatever the number of scenes or threads. A SplitMix64 mix of both values.
std::uint64_t sceneSeed(std::uint64_t requestSeed, std::uint64_t index);

/// A non-zero seed from std::random_device, for requests and configurations that give seed 0.
std::uint64_t randomSeed();

}  // namespace placement_samplers
