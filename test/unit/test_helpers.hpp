#pragma once

// Shared helpers for the core library's unit tests: objects, a scene context with robosuite's
// radius checker, simple statistics and YAML building.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "placement_samplers/collision/collision_checker.hpp"
#include "placement_samplers/collision/radius_checker.hpp"
#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/geometry/object_model.hpp"
#include "placement_samplers/sampling/placement.hpp"
#include "placement_samplers/sampling/random.hpp"
#include "placement_samplers/sampling/sample_context.hpp"
#include "placement_samplers/sampling/scene_config.hpp"

namespace placement_samplers {
namespace test {

inline ObjectPtr makeBox(const std::string& name, const Eigen::Vector3d& size,
                         const Eigen::Quaterniond& init = Eigen::Quaterniond::Identity()) {
  return std::make_shared<ObjectModel>(makeObject(name, {Shape::box(size)}, init));
}

inline ObjectPtr makeSphere(const std::string& name, double radius) {
  return std::make_shared<ObjectModel>(
      makeObject(name, {Shape::sphere(radius)}, Eigen::Quaterniond::Identity()));
}

inline ObjectPtr makeCylinder(const std::string& name, double radius, double length,
                              const Eigen::Quaterniond& init = Eigen::Quaterniond::Identity()) {
  return std::make_shared<ObjectModel>(makeObject(name, {Shape::cylinder(radius, length)}, init));
}

/// The message of the ConfigError that @p f throws, or "no ConfigError".
inline std::string configError(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no ConfigError";
}

/// The state of one scene, scene 0 of @p seed: its engine, robosuite's radius checker and a
/// context over both.
struct TestScene {
  explicit TestScene(std::uint64_t seed, std::uint32_t maxAttempts = 0)
      : engine(sceneEngine(seed, 0)), context(engine, checker, maxAttempts) {
    context.setScene(seed, 0);
  }

  Engine engine;
  RadiusChecker checker;
  SampleContext context;
};

/// The placement of @p name, or nullptr.
inline const ObjectPlacement* findPlacement(const std::vector<ObjectPlacement>& placements,
                                            const std::string& name) {
  for (const ObjectPlacement& p : placements) {
    if (p.name == name) {
      return &p;
    }
  }
  return nullptr;
}

/// Bit-for-bit equality of two placement lists.
inline void expectSamePlacements(const std::vector<ObjectPlacement>& a,
                                 const std::vector<ObjectPlacement>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].name, b[i].name);
    EXPECT_EQ(a[i].sampler, b[i].sampler);
    EXPECT_EQ(a[i].attempts, b[i].attempts);
    EXPECT_EQ(a[i].hidden, b[i].hidden);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(a[i].position[k], b[i].position[k]) << a[i].name << " position " << k;
    }
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(a[i].orientation.coeffs()[k], b[i].orientation.coeffs()[k])
          << a[i].name << " orientation " << k;
    }
  }
}

/// True when any position coordinate of the two lists differs.
inline bool anyPositionDiffers(const std::vector<ObjectPlacement>& a,
                               const std::vector<ObjectPlacement>& b) {
  if (a.size() != b.size()) {
    return true;
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].position != b[i].position) {
      return true;
    }
  }
  return false;
}

/// The placed entry robosuite's test sees for @p p.
inline PlacedEntry asEntry(const ObjectPlacement& p) {
  return PlacedEntry{p.name, p.object, p.position, p.orientation, false};
}

inline Candidate asCandidate(const ObjectPlacement& p) {
  return Candidate{p.object, p.position, p.orientation};
}

/// Mean and unbiased variance of @p v.
inline void meanAndVariance(const std::vector<double>& v, double& mean, double& variance) {
  mean = 0.0;
  for (double x : v) {
    mean += x;
  }
  mean /= static_cast<double>(v.size());
  variance = 0.0;
  for (double x : v) {
    variance += (x - mean) * (x - mean);
  }
  variance /= static_cast<double>(v.size() - 1);
}

/// Kolmogorov-Smirnov distance between the samples @p v and U(low, high).
inline double ksDistanceToUniform(std::vector<double> v, double low, double high) {
  std::sort(v.begin(), v.end());
  const double n = static_cast<double>(v.size());
  double d = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double f = std::min(1.0, std::max(0.0, (v[i] - low) / (high - low)));
    d = std::max(d, std::max(f - i / n, (i + 1) / n - f));
  }
  return d;
}

/// KS critical distance for n samples at significance 1e-4 (asymptotic formula).
inline double ksCritical(std::size_t n) {
  return std::sqrt(-std::log(1e-4 / 2.0) / (2.0 * static_cast<double>(n)));
}

/// Checks that @p v looks like U(low, high): mean and variance within 4 standard errors and
/// the KS distance below its 1e-4 critical value.
inline void expectUniform(const std::vector<double>& v, double low, double high) {
  const double n = static_cast<double>(v.size());
  const double width = high - low;
  double mean = 0.0;
  double variance = 0.0;
  meanAndVariance(v, mean, variance);
  // Var(mean) = w^2 / 12 / n; Var(sample variance) ~ (mu4 - sigma^4) / n = w^4 / 180 / n.
  EXPECT_NEAR(mean, 0.5 * (low + high), 4.0 * width / std::sqrt(12.0 * n));
  EXPECT_NEAR(variance, width * width / 12.0, 4.0 * width * width / std::sqrt(180.0 * n));
  EXPECT_LT(ksDistanceToUniform(v, low, high), ksCritical(v.size()));
}

/// Rotation angle of @p q about the unit @p axis, for q a rotation about it: 2 atan2(s, w), so
/// AngleAxis(a) gives back a for a in (-pi, 2pi) (w = cos(a/2), s = sin(a/2)).
inline double angleAbout(const Eigen::Quaterniond& q, const Eigen::Vector3d& axis) {
  return 2.0 * std::atan2(q.vec().dot(axis), q.w());
}

inline std::shared_ptr<SceneConfig> buildFromYaml(const std::string& yaml) {
  return buildSceneConfig(parseYaml(yaml, "test.yaml"));
}

}  // namespace test
}  // namespace placement_samplers
