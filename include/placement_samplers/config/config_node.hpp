#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace placement_samplers {

/// A configuration tree that knows where each value came from. YAML (CLI) and rosparam (node)
/// are both turned into it, so one builder validates both and every error names the full path
/// of the parameter: "samplers[0].x_range" or "/placement_server/samplers[0]/x_range".
class ConfigNode {
 public:
  enum class Type { Null, Bool, Int, Double, String, List, Map };

  /// An empty map at @p path, whose children are named path + separator + key.
  static ConfigNode makeRoot(const std::string& path = "", char separator = '.');

  ConfigNode() = default;

  Type type() const { return type_; }
  const std::string& path() const { return path_; }
  /// "a number", "a string", "a list", ... for messages.
  static const char* typeName(Type type);

  // Building (used by the YAML and XmlRpc readers).
  void setNull() { type_ = Type::Null; }
  void setBool(bool v);
  void setInt(std::int64_t v);
  void setDouble(double v);
  void setString(std::string v);
  void setList();
  void setMap();
  /// Appends an element to a list; the path gets "[i]".
  ConfigNode& append();
  /// Adds a key to a map (in order of insertion); the path gets separator + key.
  ConfigNode& add(const std::string& key);

  // Reading. Each accessor throws ConfigError "<path>: expected X, got Y".
  bool isMap() const { return type_ == Type::Map; }
  bool isList() const { return type_ == Type::List; }
  bool isNumber() const { return type_ == Type::Int || type_ == Type::Double; }
  bool isString() const { return type_ == Type::String; }
  /// The child @p key of a map, or nullptr.
  const ConfigNode* get(const std::string& key) const;
  /// The child @p key of a map.
  /// @throw ConfigError when it is missing
  const ConfigNode& at(const std::string& key) const;
  const std::vector<std::pair<std::string, ConfigNode>>& entries() const;  ///< map
  const std::vector<ConfigNode>& elements() const;                         ///< list
  bool asBool() const;
  /// A finite number; an integer is accepted.
  double asDouble() const;
  /// An integer in [min, max].
  std::int64_t asInt(std::int64_t min, std::int64_t max) const;
  std::uint64_t asUInt64() const;
  const std::string& asString() const;
  /// A list of @p n finite numbers.
  std::vector<double> asNumbers(std::size_t n) const;
  Eigen::Vector3d asVector3() const;
  /// Throws when this map holds a key outside @p allowed (a typo, most likely).
  void checkKeys(std::initializer_list<const char*> allowed) const;
  void checkKeys(const std::vector<std::string>& allowed) const;
  /// Throws "<path>: <what>".
  [[noreturn]] void fail(const std::string& what) const;

 private:
  ConfigNode(std::string path, char separator) : path_(std::move(path)), separator_(separator) {}
  [[noreturn]] void expected(const std::string& what) const;
  std::string describeValue() const;

  Type type_ = Type::Null;
  std::string path_;
  char separator_ = '.';
  bool bool_ = false;
  std::int64_t int_ = 0;
  double double_ = 0.0;
  std::string string_;
  std::vector<ConfigNode> list_;
  std::vector<std::pair<std::string, ConfigNode>> map_;
};

/// Parses YAML text into a tree.
/// @param origin the file name, for messages
/// @throw ConfigError with the line and column of a syntax error
ConfigNode parseYaml(const std::string& text, const std::string& origin);

/// Reads and parses a YAML file.
/// @throw ConfigError when the file cannot be read or parsed
ConfigNode loadYamlFile(const std::string& path);

}  // namespace placement_samplers
