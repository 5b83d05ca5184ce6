#include "cli/validate_scenes.hpp"

#include <charconv>
#include <new>

#include "cli/scene_line_reader.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/output/scene_json.hpp"
#include "placement_samplers/process/malloc_tuning.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace {

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
  const std::string shown = source == "-" ? "<stdin>" : escapeText(source);
  bool allValid = true;
  std::uint64_t lineNumber = 0;
  std::uint64_t scenes = 0;
  std::string text;
  std::string line;
  for (;;) {
    ++lineNumber;
    try {
      if (!readBoundedLine(in, line, kMaxSceneLineBytes)) {
        break;
      }
      if (line.find_first_not_of(" \t\r") == std::string::npos) {
        continue;
      }
      std::uint64_t scene = 0;
      const std::vector<GivenPose> poses =
          readSceneLine(line, scenes, limits::kValidatedPlacements, scene);
      ++scenes;
      const SceneVerdict verdict = validateScene(generator, request, poses, options);
      allValid = allValid && verdict.valid;
      text.clear();
      appendVerdict(text, scene, verdict);
      out << text;
    } catch (const LineError& e) {
      out.flush();
      err << "sample_scenes: --validate " << shown << ": line " << lineNumber << ": "
          << escapeText(e.what()) << "\n";
      return 2;
    } catch (const RequestError& e) {
      out.flush();
      err << "sample_scenes: --validate " << shown << ": line " << lineNumber << ": "
          << escapeText(e.what()) << "\n";
      return 2;
    }
    if (line.size() >= kTrimAfterInputBytes) {
      // A large line's memory goes back to the kernel: a long stream keeps no peak's memory.
      const std::size_t bytes = line.size();
      line = std::string();
      text = std::string();
      trimAfterInput(bytes);
    }
  }
  if (in.bad()) {
    err << "sample_scenes: --validate " << shown << ": read error\n";
    return 2;
  }
  out.flush();
  return allValid ? 0 : 1;
}

}  // namespace placement_samplers
