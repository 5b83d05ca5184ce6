#pragma once

// Internal to the core library: how the validator words and records a violation. Not installed.

#include <sstream>
#include <string>
#include <utility>

#include "placement_samplers/validation/scene_validator.hpp"

namespace placement_samplers {
namespace detail {

/// "@p v m", as the violation messages give lengths.
inline std::string metres(double v) {
  std::ostringstream out;
  out << v << " m";
  return out.str();
}

/// Records a violation of @p verdict's object, which is then not valid.
inline void addViolation(ObjectVerdict& verdict, Violation::Kind kind, const std::string& sampler,
                         const std::string& other, double distance, std::string message) {
  Violation v;
  v.kind = kind;
  v.sampler = sampler;
  v.other = other;
  v.distance = distance;
  v.message = std::move(message);
  verdict.valid = false;
  verdict.reasons.push_back(std::move(v));
}

}  // namespace detail
}  // namespace placement_samplers
