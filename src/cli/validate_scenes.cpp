#include "cli/validate_scenes.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <stdexcept>

#include "placement_samplers/output/scene_json.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace {

struct LineError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

template <int N>
Eigen::Matrix<double, N, 1> readVector(const YAML::Node& node, const std::string& what) {
  if (!node.IsSequence() || node.size() != N) {
    throw LineError(what + ": expected a list of " + std::to_string(N) + " numbers");
  }
  Eigen::Matrix<double, N, 1> v;
  for (int k = 0; k < N; ++k) {
    try {
      v[k] = node[k].as<double>();
    } catch (const YAML::Exception&) {
      throw LineError(what + ": expected a list of " + std::to_string(N) + " numbers");
    }
  }
  return v;
}

/// One line of sample_scenes' output: the poses, and the scene index (or @p fallback).
std::vector<GivenPose> readScene(const std::string& line, std::uint64_t fallback,
                                 std::uint64_t& scene) {
  // JSON is YAML: yaml-cpp reads the line (its doubles exactly, as strtod does).
  YAML::Node root;
  try {
    root = YAML::Load(line);
  } catch (const YAML::Exception& e) {
    throw LineError("not JSON: " + std::string(e.what()));
  }
  if (!root.IsMap()) {
    throw LineError("expected a JSON object (one scene of sample_scenes)");
  }
  scene = fallback;
  if (const YAML::Node index = root["scene"]) {
    try {
      scene = index.as<std::uint64_t>();
    } catch (const YAML::Exception&) {
      throw LineError("\"scene\": expected a non-negative integer");
    }
  }
  const YAML::Node placements = root["placements"];
  if (!placements || !placements.IsSequence()) {
    throw LineError("\"placements\": expected a list of {\"name\", \"position\", \"orientation\"}");
  }
  std::vector<GivenPose> poses;
  for (std::size_t i = 0; i < placements.size(); ++i) {
    const YAML::Node p = placements[i];
    const std::string where = "placement " + std::to_string(i);
    if (!p.IsMap() || !p["name"] || !p["name"].IsScalar()) {
      throw LineError(where + ": expected an object with a \"name\"");
    }
    GivenPose pose;
    pose.name = p["name"].as<std::string>();
    // Settled scenes (--physics settle) keep the sampled poses: those are what sampling chose.
    const bool settled = p["sampled_position"] && p["sampled_orientation"];
    const char* position = settled ? "sampled_position" : "position";
    const char* orientation = settled ? "sampled_orientation" : "orientation";
    pose.position =
        readVector<3>(p[position], where + " (" + quoteText(pose.name) + ") " + position);
    const Eigen::Vector4d q =
        readVector<4>(p[orientation], where + " (" + quoteText(pose.name) + ") " + orientation);
    pose.orientation.coeffs() = q;  // x, y, z, w, as printed
    poses.push_back(std::move(pose));
  }
  return poses;
}

void appendNumber(std::string& out, double v) {
  char buffer[32];
  const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof(buffer), v);
  out.append(buffer, r.ptr);
}

void appendVerdict(std::string& out, std::uint64_t scene, const SceneVerdict& verdict) {
  out += "{\"scene\": " + std::to_string(scene);
  out += verdict.valid ? ", \"valid\": true, \"objects\": [" : ", \"valid\": false, \"objects\": [";
  for (std::size_t i = 0; i < verdict.objects.size(); ++i) {
    const ObjectVerdict& o = verdict.objects[i];
    out += i == 0 ? "{\"name\": " : ", {\"name\": ";
    appendJsonString(out, o.name);
    out += o.valid ? ", \"valid\": true, \"reasons\": [" : ", \"valid\": false, \"reasons\": [";
    for (std::size_t k = 0; k < o.reasons.size(); ++k) {
      const Violation& v = o.reasons[k];
      out += k == 0 ? "{\"kind\": \"" : ", {\"kind\": \"";
      out += violationKindName(v.kind);
      out += "\", \"sampler\": ";
      appendJsonString(out, v.sampler);
      out += ", \"other\": ";
      appendJsonString(out, v.other);
      out += ", \"check\": ";
      appendJsonString(out, v.check);
      out += ", \"distance\": ";
      appendNumber(out, v.distance);
      out += ", \"message\": ";
      appendJsonString(out, v.message);
      out += '}';
    }
    out += "]}";
  }
  out += "]}\n";
}

}  // namespace

int validateSceneLines(const SceneGenerator& generator, const PreparedRequest& request,
                       const ValidationOptions& options, std::istream& in,
                       const std::string& source, std::ostream& out, std::ostream& err) {
  bool allValid = true;
  std::uint64_t lineNumber = 0;
  std::uint64_t scenes = 0;
  std::string text;
  for (std::string line; std::getline(in, line);) {
    ++lineNumber;
    if (line.find_first_not_of(" \t\r") == std::string::npos) {
      continue;
    }
    std::uint64_t scene = 0;
    std::vector<GivenPose> poses;
    try {
      poses = readScene(line, scenes, scene);
    } catch (const LineError& e) {
      out.flush();
      err << "sample_scenes: --validate " << escapeText(source) << ": line " << lineNumber << ": "
          << escapeText(e.what()) << "\n";
      return 2;
    }
    ++scenes;
    const SceneVerdict verdict = validateScene(generator, request, poses, options);
    allValid = allValid && verdict.valid;
    text.clear();
    appendVerdict(text, scene, verdict);
    out << text;
  }
  if (in.bad()) {
    err << "sample_scenes: --validate " << escapeText(source) << ": read error\n";
    return 2;
  }
  out.flush();
  return allValid ? 0 : 1;
}

}  // namespace placement_samplers
