#pragma once

#include <cstdint>
#include <random>

#include "placement_samplers/mt19937_64.hpp"

namespace placement_samplers {

/// The one random engine type of the library. Every scene owns one, seeded from (seed, index).
/// It gives the same numbers as std::mt19937_64 for every seed (verified against it by
/// test/unit/mt19937_64_test.cpp), so a seed gives the same scenes as with std::mt19937_64; it
/// is our own because seeding std::mt19937_64 and drawing once costs about 1.7 us, most of a
/// small scene, where Mt19937_64 computes only the state its first draws need.
using Engine = Mt19937_64;

/// A double in [0, 1) from the top 53 bits of one draw. Written out rather than taken from
/// std::uniform_real_distribution so that a seed gives the same scene with any standard library.
inline double uniform01(Engine& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }

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
