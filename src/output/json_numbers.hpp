#pragma once
// Numbers in JSON output (scene_json.cpp, surface_json.cpp). Private to the core.

#include <charconv>
#include <cstdint>
#include <string>

namespace placement_samplers::detail {

/// Shortest form that reads back as the same double (std::to_chars without a format).
inline void appendNumber(std::string& out, double v) {
  char buffer[32];
  const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof(buffer), v);
  out.append(buffer, r.ptr);
}

inline void appendInteger(std::string& out, std::uint64_t v) {
  char buffer[24];
  const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof(buffer), v);
  out.append(buffer, r.ptr);
}

inline void appendVector(std::string& out, const double* values, int count) {
  out += '[';
  for (int k = 0; k < count; ++k) {
    if (k > 0) {
      out += ", ";
    }
    appendNumber(out, values[k]);
  }
  out += ']';
}

}  // namespace placement_samplers::detail
