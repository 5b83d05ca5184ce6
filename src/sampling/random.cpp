#include "placement_samplers/sampling/random.hpp"

#include <random>

namespace placement_samplers {

Engine hiddenEngine(std::uint64_t seed, std::uint64_t index) {
  const std::uint64_t entropy[2] = {seed, index};
  const std::uint64_t spawnKey[1] = {0};
  return Engine(SeedSequence(entropy, 2, spawnKey, 1));
}

std::uint64_t randomSeed() {
  std::random_device device;
  std::uint64_t seed = 0;
  while (seed == 0) {
    seed = (static_cast<std::uint64_t>(device()) << 32) ^ device();
  }
  return seed;
}

}  // namespace placement_samplers
