#pragma once
// sample_scenes --validate's input: one scene of the tool's JSON lines, read without building
// a document (a document of a large scene costs about 50 bytes per byte of the line).

#include <cstddef>
#include <cstdint>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

#include "placement_samplers/validation/scene_validator.hpp"

namespace placement_samplers {

/// What is wrong with one input line (the caller adds the line number).
struct LineError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Bytes of one input line of --validate, at most (a scene of every object of the largest
/// configuration, with the longest names, takes a few MB).
constexpr std::size_t kMaxSceneLineBytes = std::size_t{32} << 20;

/// Reads one line without its '\n' into @p line. @return false at the end of the input (a last
/// line without '\n' is still read)
/// @throw LineError when the line is longer than @p maxBytes (the rest of it is not read)
bool readBoundedLine(std::istream& in, std::string& line, std::size_t maxBytes);

/// The poses of one line of sample_scenes' output: "placements" (each "name", "position",
/// "orientation", or "sampled_position" and "sampled_orientation" when both are present) and
/// "scene" (or @p fallback); other keys are skipped. At most @p maxPlacements placements.
/// @throw LineError naming the key, placement and what was expected
std::vector<GivenPose> readSceneLine(const std::string& line, std::uint64_t fallback,
                                     std::size_t maxPlacements, std::uint64_t& scene);

}  // namespace placement_samplers
