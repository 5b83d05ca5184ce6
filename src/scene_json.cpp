#include "placement_samplers/scene_json.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>

namespace placement_samplers {
namespace {

/// Shortest form that reads back as the same double (std::to_chars without a format).
void appendNumber(std::string& out, double v) {
  char buffer[32];
  const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof(buffer), v);
  out.append(buffer, r.ptr);
}

void appendInteger(std::string& out, std::uint64_t v) {
  char buffer[24];
  const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof(buffer), v);
  out.append(buffer, r.ptr);
}

}  // namespace

void appendJsonString(std::string& out, std::string_view text) {
  out += '"';
  // Names are plain almost always: one append when nothing needs escaping.
  const bool plain = std::all_of(text.begin(), text.end(), [](char c) {
    return static_cast<unsigned char>(c) >= 0x20 && c != '"' && c != '\\';
  });
  if (plain) {
    out.append(text);
    out += '"';
    return;
  }
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
  out += '"';
}

std::string jsonString(const std::string& text) {
  std::string out;
  appendJsonString(out, text);
  return out;
}

void appendSceneJson(std::string& out, const SceneResult& scene) {
  out += "{\"scene\": ";
  appendInteger(out, scene.index);
  out += ", \"seed\": ";
  appendInteger(out, scene.seed);
  out += scene.success ? ", \"success\": true" : ", \"success\": false";
  out += ", \"message\": ";
  appendJsonString(out, scene.message);
  out += ", \"placements\": [";
  for (std::size_t i = 0; i < scene.placements.size(); ++i) {
    const ObjectPlacement& p = scene.placements[i];
    out += i == 0 ? "{\"name\": " : ", {\"name\": ";
    appendJsonString(out, p.name);
    out += ", \"sampler\": ";
    appendJsonString(out, p.sampler);
    out += ", \"position\": [";
    for (int k = 0; k < 3; ++k) {
      if (k > 0) {
        out += ", ";
      }
      appendNumber(out, p.position[k]);
    }
    out += "], \"orientation\": [";
    const Eigen::Vector4d q = p.orientation.coeffs();  // x, y, z, w
    for (int k = 0; k < 4; ++k) {
      if (k > 0) {
        out += ", ";
      }
      appendNumber(out, q[k]);
    }
    out += "], \"attempts\": ";
    appendInteger(out, p.attempts);
    out += '}';
  }
  out += "]}";
}

std::string sceneToJson(const SceneResult& scene) {
  std::string out;
  appendSceneJson(out, scene);
  return out;
}

}  // namespace placement_samplers
