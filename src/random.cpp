#include "placement_samplers/random.hpp"

namespace placement_samplers {
namespace {

std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace

std::uint64_t sceneSeed(std::uint64_t requestSeed, std::uint64_t index) {
  return splitMix64(splitMix64(requestSeed) ^ index);
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
