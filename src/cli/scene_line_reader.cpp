#include "cli/scene_line_reader.hpp"

#include <algorithm>
#include <array>

#include "cli/json_reader.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace {

using detail::JsonReader;

/// A list of numbers of one placement, as read: absent, a list of N numbers, or something else.
template <int N>
struct NumberList {
  enum class State { Absent, Good, Bad };
  State state = State::Absent;
  std::array<double, N> values{};

  void read(JsonReader& json) {
    if (!json.at('[')) {
      json.skip();
      state = State::Bad;
      return;
    }
    int count = 0;
    bool numbers = true;
    json.array([&](std::size_t) {
      if (!json.atNumber()) {
        json.skip();
        numbers = false;
      } else if (count < N) {
        values[static_cast<std::size_t>(count++)] = json.number();
      } else {
        json.number();
        ++count;
      }
    });
    state = numbers && count == N ? State::Good : State::Bad;
  }
};

/// The fields of one placement, in whatever order they come.
struct PlacementFields {
  bool named = false;
  std::string name;
  NumberList<3> position;
  NumberList<4> orientation;
  NumberList<3> sampledPosition;
  NumberList<4> sampledOrientation;
};

template <int N>
const NumberList<N>& checked(const NumberList<N>& list, const std::string& where, const char* key) {
  if (list.state == NumberList<N>::State::Absent) {
    throw LineError(where + ": missing field \"" + key + "\"");
  }
  if (list.state == NumberList<N>::State::Bad) {
    throw LineError(where + " " + key + ": expected a list of " + std::to_string(N) + " numbers");
  }
  return list;
}

GivenPose readPlacement(JsonReader& json, std::size_t index) {
  const std::string where = "placement " + std::to_string(index);
  if (!json.at('{')) {
    throw LineError(where + ": expected an object with a \"name\"");
  }
  PlacementFields f;
  json.object([&](const std::string& key) {
    if (key == "name" && json.at('"')) {
      f.named = true;
      f.name = json.string();
    } else if (key == "position") {
      f.position.read(json);
    } else if (key == "orientation") {
      f.orientation.read(json);
    } else if (key == "sampled_position") {
      f.sampledPosition.read(json);
    } else if (key == "sampled_orientation") {
      f.sampledOrientation.read(json);
    } else {
      json.skip();
    }
  });
  if (!f.named) {
    throw LineError(where + ": expected an object with a \"name\"");
  }
  const std::string named = where + " (" + quoteText(f.name) + ")";
  // Settled scenes (--physics settle) keep the sampled poses: those are what sampling chose.
  const bool settled = f.sampledPosition.state != NumberList<3>::State::Absent &&
                       f.sampledOrientation.state != NumberList<4>::State::Absent;
  GivenPose pose;
  pose.name = std::move(f.name);
  const NumberList<3>& p = settled ? checked(f.sampledPosition, named, "sampled_position")
                                   : checked(f.position, named, "position");
  const NumberList<4>& q = settled ? checked(f.sampledOrientation, named, "sampled_orientation")
                                   : checked(f.orientation, named, "orientation");
  pose.position = Eigen::Vector3d(p.values[0], p.values[1], p.values[2]);
  pose.orientation.coeffs() = Eigen::Vector4d(q.values[0], q.values[1], q.values[2],
                                              q.values[3]);  // x, y, z, w, as printed
  return pose;
}

}  // namespace

bool readBoundedLine(std::istream& in, std::string& line, std::size_t maxBytes) {
  line.clear();
  std::streambuf* buffer = in.rdbuf();
  bool any = false;
  for (;;) {
    const int c = buffer->sbumpc();
    if (c == std::char_traits<char>::eof()) {
      in.setstate(std::ios::eofbit);
      return any;
    }
    any = true;
    if (c == '\n') {
      return true;
    }
    if (line.size() == maxBytes) {
      throw LineError("longer than " + std::to_string(maxBytes) + " bytes (the limit of a line)");
    }
    if (line.size() == line.capacity()) {
      // Grown up to the limit, not past it as doubling would.
      line.reserve(std::min(maxBytes, std::max<std::size_t>(2 * line.capacity(), 256)));
    }
    line += static_cast<char>(c);
  }
}

std::vector<GivenPose> readSceneLine(const std::string& line, std::uint64_t fallback,
                                     std::size_t maxPlacements, std::uint64_t& scene) {
  JsonReader json(line);
  if (!json.at('{')) {
    throw LineError("expected a JSON object (one scene of sample_scenes)");
  }
  scene = fallback;
  bool listed = false;
  std::vector<GivenPose> poses;
  json.object([&](const std::string& key) {
    if (key == "scene") {
      if (!json.unsignedInteger(scene)) {
        throw LineError("\"scene\": expected a non-negative integer");
      }
    } else if (key == "placements") {
      if (!json.at('[')) {
        throw LineError(
            "\"placements\": expected a list of {\"name\", \"position\", \"orientation\"}");
      }
      listed = true;
      poses.clear();
      json.array([&](std::size_t index) {
        if (index == maxPlacements) {
          throw LineError("\"placements\": more than " + std::to_string(maxPlacements) +
                          " placements (the limit of a scene)");
        }
        poses.push_back(readPlacement(json, index));
      });
    } else {
      json.skip();
    }
  });
  if (!json.atEnd()) {
    json.fail("text after the scene's object");
  }
  if (!listed) {
    throw LineError("\"placements\": expected a list of {\"name\", \"position\", \"orientation\"}");
  }
  return poses;
}

}  // namespace placement_samplers
