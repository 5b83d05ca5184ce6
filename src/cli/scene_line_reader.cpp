#include "cli/scene_line_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <limits>

#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace {

/// Nesting levels of a skipped value, at most.
constexpr int kMaxDepth = 100;

/// A JSON reader over one line: each value is read where it stands, nothing is kept but what
/// the caller takes.
class JsonReader {
 public:
  explicit JsonReader(const std::string& text) : text_(text) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw LineError("not JSON: " + what + " at byte " + std::to_string(at_ + 1));
  }
  /// The next character after white space, or '\0' at the end.
  char peek() {
    while (at_ < text_.size() &&
           (text_[at_] == ' ' || text_[at_] == '\t' || text_[at_] == '\r' || text_[at_] == '\n')) {
      ++at_;
    }
    return at_ < text_.size() ? text_[at_] : '\0';
  }
  bool atEnd() { return peek() == '\0' && at_ == text_.size(); }
  void expect(char c) {
    if (peek() != c) {
      fail(std::string("expected '") + c + "'");
    }
    ++at_;
  }

  /// Calls @p onKey(key) for each key of an object (at '{'); it must read the value.
  template <typename F>
  void object(const F& onKey) {
    expect('{');
    if (peek() == '}') {
      ++at_;
      return;
    }
    for (;;) {
      if (peek() != '"') {
        fail("expected a key in double quotes");
      }
      const std::string key = string();
      expect(':');
      onKey(key);
      if (peek() == ',') {
        ++at_;
        continue;
      }
      expect('}');
      return;
    }
  }

  /// Calls @p onItem(index) for each item of an array (at '['); it must read the item.
  template <typename F>
  void array(const F& onItem) {
    expect('[');
    if (peek() == ']') {
      ++at_;
      return;
    }
    for (std::size_t index = 0;; ++index) {
      onItem(index);
      if (peek() == ',') {
        ++at_;
        continue;
      }
      expect(']');
      return;
    }
  }

  /// A string (at '"'), escapes decoded.
  std::string string() {
    expect('"');
    std::string out;
    for (;;) {
      if (at_ >= text_.size()) {
        fail("unterminated string");
      }
      const char c = text_[at_++];
      if (c == '"') {
        return out;
      }
      if (static_cast<unsigned char>(c) < 0x20) {
        fail("control character in a string");
      }
      if (c != '\\') {
        out += c;
        continue;
      }
      if (at_ >= text_.size()) {
        fail("unterminated string");
      }
      const char e = text_[at_++];
      switch (e) {
        case '"':
        case '\\':
        case '/':
          out += e;
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u':
          appendCodePoint(out);
          break;
        default:
          fail("unknown escape in a string");
      }
    }
  }

  /// True when a number (or NaN, Infinity, -Infinity) starts here.
  bool atNumber() {
    const char c = peek();
    return c == '-' || (c >= '0' && c <= '9') || c == 'N' || c == 'I';
  }
  /// A number, read as strtod reads it (bit for bit what sample_scenes printed).
  double number() {
    peek();
    const std::size_t start = at_;
    while (at_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[at_])) ||
                                  text_[at_] == '-' || text_[at_] == '+' || text_[at_] == '.')) {
      ++at_;
    }
    token_.assign(text_, start, at_ - start);
    if (token_ == "NaN" || token_ == "Infinity" || token_ == "-Infinity") {
      return token_ == "NaN"    ? std::numeric_limits<double>::quiet_NaN()
             : token_[0] == '-' ? -std::numeric_limits<double>::infinity()
                                : std::numeric_limits<double>::infinity();
    }
    char* end = nullptr;
    const double v = std::strtod(token_.c_str(), &end);
    if (token_.empty() || end != token_.c_str() + token_.size() ||
        token_.find_first_of("xXnN") != std::string::npos) {
      at_ = start;
      fail("bad number");
    }
    return v;
  }
  /// A non-negative integer; false (nothing read) when the value is not one.
  bool unsignedInteger(std::uint64_t& value) {
    const char c = peek();
    if (c < '0' || c > '9') {
      return false;
    }
    const std::size_t start = at_;
    value = 0;
    while (at_ < text_.size() && text_[at_] >= '0' && text_[at_] <= '9') {
      const std::uint64_t digit = static_cast<std::uint64_t>(text_[at_] - '0');
      if (value > (std::numeric_limits<std::uint64_t>::max() - digit) / 10) {
        at_ = start;
        return false;
      }
      value = value * 10 + digit;
      ++at_;
    }
    if (at_ < text_.size() && (text_[at_] == '.' || text_[at_] == 'e' || text_[at_] == 'E')) {
      at_ = start;
      return false;
    }
    return true;
  }

  /// Reads any value and drops it.
  void skip(int depth = 0) {
    if (depth > kMaxDepth) {
      fail("nested deeper than " + std::to_string(kMaxDepth) + " levels");
    }
    const char c = peek();
    if (c == '{') {
      object([&](const std::string&) { skip(depth + 1); });
    } else if (c == '[') {
      array([&](std::size_t) { skip(depth + 1); });
    } else if (c == '"') {
      string();
    } else if (atNumber()) {
      number();
    } else if (!literal("true") && !literal("false") && !literal("null")) {
      fail("expected a value");
    }
  }

  /// Whether the value here is of the kind @p c starts ('{', '[', '"').
  bool at(char c) { return peek() == c; }

 private:
  bool literal(const char* word) {
    const std::string w(word);
    if (text_.compare(at_, w.size(), w) != 0) {
      return false;
    }
    at_ += w.size();
    return true;
  }

  unsigned hex4() {
    if (at_ + 4 > text_.size()) {
      fail("bad \\u escape");
    }
    unsigned v = 0;
    for (int k = 0; k < 4; ++k) {
      const char h = text_[at_++];
      v <<= 4;
      if (h >= '0' && h <= '9') {
        v |= static_cast<unsigned>(h - '0');
      } else if (h >= 'a' && h <= 'f') {
        v |= static_cast<unsigned>(h - 'a' + 10);
      } else if (h >= 'A' && h <= 'F') {
        v |= static_cast<unsigned>(h - 'A' + 10);
      } else {
        fail("bad \\u escape");
      }
    }
    return v;
  }

  /// After "\u": the code point (a surrogate pair joined; a lone surrogate becomes U+FFFD) in
  /// UTF-8.
  void appendCodePoint(std::string& out) {
    unsigned cp = hex4();
    if (cp >= 0xd800 && cp <= 0xdbff && text_.compare(at_, 2, "\\u") == 0) {
      const std::size_t back = at_;
      at_ += 2;
      const unsigned low = hex4();
      if (low >= 0xdc00 && low <= 0xdfff) {
        cp = 0x10000 + ((cp - 0xd800) << 10) + (low - 0xdc00);
      } else {
        at_ = back;
      }
    }
    if (cp >= 0xd800 && cp <= 0xdfff) {
      cp = 0xfffd;
    }
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xc0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xe0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    } else {
      out += static_cast<char>(0xf0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3f));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    }
  }

  const std::string& text_;
  std::size_t at_ = 0;
  std::string token_;  ///< scratch of number()
};

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
