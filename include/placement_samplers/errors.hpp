#pragma once

#include <stdexcept>
#include <string>

namespace placement_samplers {

/// An invalid configuration: the message names the parameter, object or sampler and what was
/// expected. Thrown while building, never while sampling.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An invalid request (unknown sampler, reference or fixture object, duplicate names, ...).
class RequestError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace placement_samplers
