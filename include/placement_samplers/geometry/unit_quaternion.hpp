#pragma once

#include <Eigen/Geometry>
#include <cmath>

namespace placement_samplers {

/// Largest |norm - 1| of a quaternion accepted as a rotation, in a configuration and in a
/// request; accepted quaternions are normalised.
constexpr double kUnitQuaternionTolerance = 1e-3;

/// True when @p q is finite and its norm within kUnitQuaternionTolerance of 1: the one test of
/// the configuration, of request fixtures and of the node's messages.
inline bool isUnitQuaternion(const Eigen::Quaterniond& q) {
  return q.coeffs().allFinite() && std::abs(q.norm() - 1.0) <= kUnitQuaternionTolerance;
}

}  // namespace placement_samplers
