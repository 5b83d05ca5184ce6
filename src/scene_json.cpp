#include "placement_samplers/scene_json.hpp"

#include <cstdio>

namespace placement_samplers {
namespace {

void appendNumber(std::string& out, double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.17g", v);
  out += buffer;
}

}  // namespace

std::string jsonString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
          out += buffer;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string sceneToJson(const SceneResult& scene) {
  std::string out = "{\"scene\": " + std::to_string(scene.index) +
                    ", \"seed\": " + std::to_string(scene.seed) +
                    ", \"success\": " + (scene.success ? "true" : "false") +
                    ", \"message\": " + jsonString(scene.message) + ", \"placements\": [";
  for (std::size_t i = 0; i < scene.placements.size(); ++i) {
    const ObjectPlacement& p = scene.placements[i];
    out += i == 0 ? "{" : ", {";
    out += "\"name\": " + jsonString(p.name) + ", \"sampler\": " + jsonString(p.sampler) +
           ", \"position\": [";
    for (int k = 0; k < 3; ++k) {
      if (k > 0) out += ", ";
      appendNumber(out, p.position[k]);
    }
    out += "], \"orientation\": [";
    const Eigen::Vector4d q = p.orientation.coeffs();  // x, y, z, w
    for (int k = 0; k < 4; ++k) {
      if (k > 0) out += ", ";
      appendNumber(out, q[k]);
    }
    out += "], \"attempts\": " + std::to_string(p.attempts) + "}";
  }
  return out + "]}";
}

}  // namespace placement_samplers
