#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <cstdlib>
#include <limits>
#include <sstream>
#include <unordered_set>

#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/input_files.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }

/// Digits from @p i on; @return the index after them.
std::size_t skipDigits(const std::string& text, std::size_t i) {
  while (i < text.size() && isDigit(text[i])) {
    ++i;
  }
  return i;
}

std::size_t skipSign(const std::string& text) {
  return !text.empty() && (text[0] == '-' || text[0] == '+') ? 1 : 0;
}

/// [-+]?[0-9]+
bool isInteger(const std::string& text) {
  const std::size_t start = skipSign(text);
  return start < text.size() && skipDigits(text, start) == text.size();
}

/// [-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?
bool isReal(const std::string& text) {
  std::size_t i = skipSign(text);
  const std::size_t integral = skipDigits(text, i);
  if (integral > i) {
    i = integral;
    if (i < text.size() && text[i] == '.') {
      i = skipDigits(text, i + 1);
    }
  } else {
    if (i >= text.size() || text[i] != '.') {
      return false;
    }
    const std::size_t fraction = skipDigits(text, i + 1);
    if (fraction == i + 1) {
      return false;
    }
    i = fraction;
  }
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    std::size_t e = i + 1;
    if (e < text.size() && (text[e] == '-' || text[e] == '+')) {
      ++e;
    }
    const std::size_t exponent = skipDigits(text, e);
    if (exponent == e) {
      return false;
    }
    i = exponent;
  }
  return i == text.size();
}

std::string depthMessage(const std::string& origin, const YAML::Mark& mark) {
  std::ostringstream out;
  out << origin << ": nested too deep at line " << mark.line + 1 << ", column " << mark.column + 1
      << " (more than " << limits::kConfigDepth << " levels)";
  return out.str();
}

/// Turns yaml-cpp's tree into ours, expanding aliases, within limits::kConfigValues values and
/// limits::kConfigDepth levels: a few hundred bytes of nested aliases expand to billions.
class Converter {
 public:
  explicit Converter(const std::string& origin) : origin_(origin) {}

  void convert(const YAML::Node& in, ConfigNode& out, int depth) {
    if (++values_ > limits::kConfigValues) {
      throw ConfigError(origin_ + ": more than " + std::to_string(limits::kConfigValues) +
                        " values (maps, lists and scalars, each use of a YAML alias counted)");
    }
    if (depth > limits::kConfigDepth) {
      throw ConfigError(depthMessage(origin_, in.Mark()));
    }
    switch (in.Type()) {
      case YAML::NodeType::Undefined:
      case YAML::NodeType::Null:
        out.setNull();
        return;
      case YAML::NodeType::Sequence:
        out.setList();
        for (const YAML::Node& element : in) {
          convert(element, out.append(), depth + 1);
        }
        return;
      case YAML::NodeType::Map: {
        out.setMap();
        std::unordered_set<std::string> keys;
        for (const auto& entry : in) {
          std::string key = entry.first.as<std::string>();
          if (!keys.insert(key).second) {
            out.fail("duplicate key " + quoteText(key));
          }
          convert(entry.second, out.add(key), depth + 1);
        }
        return;
      }
      case YAML::NodeType::Scalar:
        break;
    }
    scalar(in, out);
  }

 private:
  static void scalar(const YAML::Node& in, ConfigNode& out);

  const std::string& origin_;
  std::size_t values_ = 0;
};

void Converter::scalar(const YAML::Node& in, ConfigNode& out) {
  const std::string& text = in.Scalar();
  // Quoted scalars are strings, whatever they look like.
  if (in.Tag() == "!") {
    out.setString(text);
    return;
  }
  // Matched by hand, not with std::regex: libstdc++'s matcher recurses once per character, and
  // a long scalar (a megabyte of digits) overflowed the stack.
  if (isInteger(text)) {
    try {
      out.setInt(std::stoll(text));
    } catch (const std::out_of_range&) {
      out.setString(text);  // a seed above 2^63 stays readable through asUInt64()
    }
    return;
  }
  if (isReal(text)) {
    // strtod, not stod: 1e999 becomes inf (refused later as "expected a finite number") and
    // 1e-400 becomes 0, where stod would throw out_of_range.
    out.setDouble(std::strtod(text.c_str(), nullptr));
    return;
  }
  if (text == ".nan" || text == ".NaN" || text == ".NAN") {
    out.setDouble(std::numeric_limits<double>::quiet_NaN());
    return;
  }
  const bool negative = !text.empty() && text[0] == '-';
  const std::string magnitude =
      !text.empty() && (text[0] == '-' || text[0] == '+') ? text.substr(1) : text;
  if (magnitude == ".inf" || magnitude == ".Inf" || magnitude == ".INF") {
    const double v = std::numeric_limits<double>::infinity();
    out.setDouble(negative ? -v : v);
    return;
  }
  if (text == "true" || text == "True" || text == "TRUE") {
    out.setBool(true);
    return;
  }
  if (text == "false" || text == "False" || text == "FALSE") {
    out.setBool(false);
    return;
  }
  out.setString(text);
}

}  // namespace

ConfigNode parseYaml(const std::string& text, const std::string& origin) {
  YAML::Node document;
  try {
    document = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    throw ConfigError(depthMessage(origin, e.mark));
  } catch (const YAML::Exception& e) {
    std::ostringstream out;
    out << origin << ": invalid YAML at line " << e.mark.line + 1 << ", column "
        << e.mark.column + 1 << ": " << e.msg;
    throw ConfigError(out.str());
  }
  ConfigNode root = ConfigNode::makeRoot();
  if (document.IsNull()) {
    // As the node, which refuses a namespace without parameters.
    throw ConfigError(origin + ": the configuration file is empty (expected a map of parameters)");
  }
  if (!document.IsMap()) {
    throw ConfigError(origin + ": the configuration must be a map of parameters");
  }
  if (document.size() == 0) {
    throw ConfigError(origin + ": the configuration is an empty map (expected parameters)");
  }
  try {
    Converter(origin).convert(document, root, 1);
  } catch (const YAML::Exception& e) {
    // For example a key that is itself a list or a map.
    throw ConfigError(origin + ": unsupported YAML at line " + std::to_string(e.mark.line + 1) +
                      ": " + e.msg);
  }
  return root;
}

ConfigNode loadYamlFile(const std::string& path) {
  const std::string origin = escapeText(path);
  std::string text;
  try {
    text = readFileBounded(path, limits::kConfigBytes, "the configuration file");
  } catch (const ConfigError& e) {
    throw ConfigError(origin + ": " + e.what());
  }
  return parseYaml(text, origin);
}

}  // namespace placement_samplers
