#include "placement_samplers/output/scene_arrays.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {

bool drawsRestPoses(const PreparedRequest& request) {
  bool stable = false;
  request.sampler->forEachUniform(request.reference, request.onTop,
                                  [&](const UniformRandomSampler& sampler, const Reference&, bool) {
                                    stable = stable || sampler.params().resting ==
                                                           UniformSamplerParams::Resting::Stable;
                                  });
  return stable;
}

SceneColumns::SceneColumns(std::vector<std::string> names, PhysicsMode physics)
    : names_(std::move(names)), physics_(physics) {
  for (std::size_t i = 0; i < names_.size(); ++i) {
    columns_.emplace(names_[i], i);
  }
}

std::size_t SceneColumns::column(const ObjectPlacement& p, std::size_t i) const {
  // Placements come in sampling order, the order of names: a lookup only if not.
  if (i < names_.size() && names_[i] == p.name) {
    return i;
  }
  const auto found = columns_.find(std::string(p.name));
  if (found == columns_.end()) {
    throw std::invalid_argument("scene places " + quoteText(std::string(p.name)) +
                                ", which is not among the names given");
  }
  return found->second;
}

void SceneColumns::fill(const std::vector<SceneResult>& scenes, const SceneArrayRows& rows) const {
  const std::size_t k = scenes.size();
  const std::size_t n = names_.size();
  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  std::fill_n(rows.position, k * n * 3, kNan);
  std::fill_n(rows.orientation, k * n * 4, kNan);
  std::fill_n(rows.attempts, k * n, 0u);
  if (rows.restPose != nullptr) {
    std::fill_n(rows.restPose, k * n, ObjectPlacement::kUpright);
  }
  const bool physics = physics_ != PhysicsMode::None;
  const bool settle = physics_ == PhysicsMode::Settle;
  if (physics) {
    std::fill_n(rows.stable, k, 0);
    std::fill_n(rows.moved, k * n, kNan);
    std::fill_n(rows.turned, k * n, kNan);
    std::fill_n(rows.fallen, k * n, 0);
  }
  if (settle) {
    std::fill_n(rows.sampledPosition, k * n * 3, kNan);
    std::fill_n(rows.sampledOrientation, k * n * 4, kNan);
  }
  for (std::size_t s = 0; s < k; ++s) {
    const SceneResult& result = scenes[s];
    rows.success[s] = result.success ? 1 : 0;
    rows.scene[s] = result.index;
    if (physics) {
      rows.stable[s] = result.stable ? 1 : 0;
      const std::size_t simulated = result.simulated ? result.physics.size() : 0;
      for (std::size_t i = 0; i < simulated && i < result.placements.size(); ++i) {
        const PhysicsOutcome& o = result.physics[i];
        const std::size_t c = s * n + column(result.placements[i], i);
        rows.moved[c] = o.moved;
        rows.turned[c] = o.turned;
        rows.fallen[c] = o.fallen ? 1 : 0;
        if (settle) {
          std::memcpy(&rows.sampledPosition[c * 3], o.sampledPosition.data(), 3 * sizeof(double));
          std::memcpy(&rows.sampledOrientation[c * 4], o.sampledOrientation.coeffs().data(),
                      4 * sizeof(double));
        }
      }
    }
    for (std::size_t i = 0; i < result.placements.size(); ++i) {
      const ObjectPlacement& p = result.placements[i];
      const std::size_t c = s * n + column(p, i);
      std::memcpy(&rows.position[c * 3], p.position.data(), 3 * sizeof(double));
      std::memcpy(&rows.orientation[c * 4], p.orientation.coeffs().data(), 4 * sizeof(double));
      rows.attempts[c] = p.attempts;
      if (rows.restPose != nullptr) {
        rows.restPose[c] = p.restPose;
      }
    }
  }
}

}  // namespace placement_samplers
