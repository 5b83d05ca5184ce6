#include <yaml-cpp/yaml.h>

#include <cstdlib>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

#include "placement_samplers/config_node.hpp"
#include "placement_samplers/errors.hpp"

namespace placement_samplers {
namespace {

void convert(const YAML::Node& in, ConfigNode& out) {
  switch (in.Type()) {
    case YAML::NodeType::Undefined:
    case YAML::NodeType::Null:
      out.setNull();
      return;
    case YAML::NodeType::Sequence:
      out.setList();
      for (const YAML::Node& element : in) {
        convert(element, out.append());
      }
      return;
    case YAML::NodeType::Map:
      out.setMap();
      for (const auto& entry : in) {
        const std::string key = entry.first.as<std::string>();
        if (out.get(key) != nullptr) {
          out.fail("duplicate key '" + key + "'");
        }
        convert(entry.second, out.add(key));
      }
      return;
    case YAML::NodeType::Scalar:
      break;
  }
  const std::string& text = in.Scalar();
  // Quoted scalars are strings, whatever they look like.
  if (in.Tag() == "!") {
    out.setString(text);
    return;
  }
  static const std::regex integer("[-+]?[0-9]+");
  static const std::regex real("[-+]?(\\.[0-9]+|[0-9]+(\\.[0-9]*)?)([eE][-+]?[0-9]+)?");
  if (std::regex_match(text, integer)) {
    try {
      out.setInt(std::stoll(text));
    } catch (const std::out_of_range&) {
      out.setString(text);  // a seed above 2^63 stays readable through asUInt64()
    }
    return;
  }
  if (std::regex_match(text, real)) {
    // strtod, not stod: 1e999 becomes inf (refused later as "expected a finite number") and
    // 1e-400 becomes 0, where stod would throw out_of_range.
    out.setDouble(std::strtod(text.c_str(), nullptr));
    return;
  }
  static const std::regex nan("\\.(nan|NaN|NAN)");
  static const std::regex inf("([-+]?)\\.(inf|Inf|INF)");
  std::smatch match;
  if (std::regex_match(text, nan)) {
    out.setDouble(std::numeric_limits<double>::quiet_NaN());
    return;
  }
  if (std::regex_match(text, match, inf)) {
    const double v = std::numeric_limits<double>::infinity();
    out.setDouble(match[1] == "-" ? -v : v);
    return;
  }
  static const std::regex boolean("true|True|TRUE|false|False|FALSE");
  if (std::regex_match(text, boolean)) {
    out.setBool(text[0] == 't' || text[0] == 'T');
    return;
  }
  out.setString(text);
}

}  // namespace

ConfigNode parseYaml(const std::string& text, const std::string& origin) {
  YAML::Node document;
  try {
    document = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    std::ostringstream out;
    out << origin << ": invalid YAML at line " << e.mark.line + 1 << ", column "
        << e.mark.column + 1 << ": " << e.msg;
    throw ConfigError(out.str());
  }
  ConfigNode root = ConfigNode::makeRoot();
  if (document.IsNull()) {
    return root;
  }
  if (!document.IsMap()) {
    throw ConfigError(origin + ": the configuration must be a map of parameters");
  }
  try {
    convert(document, root);
  } catch (const YAML::Exception& e) {
    // For example a key that is itself a list or a map.
    throw ConfigError(origin + ": unsupported YAML at line " + std::to_string(e.mark.line + 1) +
                      ": " + e.msg);
  }
  return root;
}

ConfigNode loadYamlFile(const std::string& path) {
  std::ifstream file(path);
  if (!file) {
    throw ConfigError(path + ": cannot read the configuration file");
  }
  std::stringstream buffer;
  buffer << file.rdbuf();
  return parseYaml(buffer.str(), path);
}

}  // namespace placement_samplers
