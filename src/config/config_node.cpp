#include "placement_samplers/config/config_node.hpp"

#include <algorithm>

#include <cmath>
#include <sstream>
#include <string_view>
#include <unordered_set>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {

ConfigNode ConfigNode::makeRoot(const std::string& path, char separator) {
  ConfigNode root(path, separator);
  root.setMap();
  return root;
}

const char* ConfigNode::typeName(Type type) {
  switch (type) {
    case Type::Null:
      return "nothing";
    case Type::Bool:
      return "a boolean";
    case Type::Int:
      return "an integer";
    case Type::Double:
      return "a number";
    case Type::String:
      return "a string";
    case Type::List:
      return "a list";
    case Type::Map:
      return "a map";
  }
  return "unknown";
}

void ConfigNode::setBool(bool v) {
  type_ = Type::Bool;
  bool_ = v;
}

void ConfigNode::setInt(std::int64_t v) {
  type_ = Type::Int;
  int_ = v;
}

void ConfigNode::setDouble(double v) {
  type_ = Type::Double;
  double_ = v;
}

void ConfigNode::setString(std::string v) {
  type_ = Type::String;
  string_ = std::move(v);
}

void ConfigNode::setList() {
  type_ = Type::List;
  list_.clear();
}

void ConfigNode::setMap() {
  type_ = Type::Map;
  map_.clear();
}

ConfigNode& ConfigNode::append() {
  list_.push_back(ConfigNode(path_ + "[" + std::to_string(list_.size()) + "]", separator_));
  return list_.back();
}

ConfigNode& ConfigNode::add(const std::string& key) {
  // Paths appear in messages only: a key with control characters shows escaped.
  const std::string shown = escapeText(key);
  const std::string path = path_.empty() ? shown : path_ + separator_ + shown;
  map_.emplace_back(key, ConfigNode(path, separator_));
  return map_.back().second;
}

void ConfigNode::fail(const std::string& what) const {
  throw ConfigError((path_.empty() ? std::string("configuration") : path_) + ": " + what);
}

std::string ConfigNode::describeValue() const {
  std::ostringstream out;
  out << typeName(type_);
  switch (type_) {
    case Type::Bool:
      out << " (" << (bool_ ? "true" : "false") << ")";
      break;
    case Type::Int:
      out << " (" << int_ << ")";
      break;
    case Type::Double:
      out << " (" << double_ << ")";
      break;
    case Type::String:
      out << " (" << quoteText(string_) << ")";
      break;
    case Type::List:
      out << " of " << list_.size() << " element" << (list_.size() == 1 ? "" : "s");
      break;
    default:
      break;
  }
  return out.str();
}

void ConfigNode::expected(const std::string& what) const {
  fail("expected " + what + ", got " + describeValue());
}

const ConfigNode* ConfigNode::get(const std::string& key) const {
  if (type_ != Type::Map) {
    expected("a map");
  }
  for (const auto& entry : map_) {
    if (entry.first == key) {
      return &entry.second;
    }
  }
  return nullptr;
}

const ConfigNode& ConfigNode::at(const std::string& key) const {
  const ConfigNode* child = get(key);
  if (child == nullptr) {
    fail("missing required key " + quoteText(key));
  }
  return *child;
}

const std::vector<std::pair<std::string, ConfigNode>>& ConfigNode::entries() const {
  if (type_ != Type::Map) {
    expected("a map");
  }
  return map_;
}

const std::vector<ConfigNode>& ConfigNode::elements() const {
  if (type_ != Type::List) {
    expected("a list");
  }
  return list_;
}

bool ConfigNode::asBool() const {
  if (type_ != Type::Bool) {
    expected("true or false");
  }
  return bool_;
}

double ConfigNode::asDouble() const {
  if (type_ == Type::Int) {
    return static_cast<double>(int_);
  }
  if (type_ != Type::Double) {
    expected("a number");
  }
  if (!std::isfinite(double_)) {
    expected("a finite number");
  }
  return double_;
}

std::int64_t ConfigNode::asInt(std::int64_t min, std::int64_t max) const {
  if (type_ != Type::Int) {
    expected("an integer");
  }
  if (int_ < min || int_ > max) {
    std::ostringstream out;
    out << "an integer in [" << min << ", " << max << "]";
    expected(out.str());
  }
  return int_;
}

std::uint64_t ConfigNode::asUInt64() const {
  if (type_ == Type::Int && int_ >= 0) {
    return static_cast<std::uint64_t>(int_);
  }
  // Seeds above 2^63 only fit as strings of digits in YAML and rosparam.
  if (type_ == Type::String && !string_.empty() &&
      string_.find_first_not_of("0123456789") == std::string::npos && string_.size() <= 20) {
    try {
      return std::stoull(string_);
    } catch (const std::exception&) {
    }
  }
  expected("a non-negative integer");
}

const std::string& ConfigNode::asString() const {
  if (type_ != Type::String) {
    expected("a string");
  }
  return string_;
}

std::vector<double> ConfigNode::asNumbers(std::size_t n) const {
  const std::string what = "a list of " + countText(n, "number");
  if (type_ != Type::List || list_.size() != n) {
    expected(what);
  }
  std::vector<double> out;
  out.reserve(n);
  for (const ConfigNode& e : list_) {
    out.push_back(e.asDouble());
  }
  return out;
}

Eigen::Vector3d ConfigNode::asVector3() const {
  const std::vector<double> v = asNumbers(3);
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

void ConfigNode::checkKeys(std::initializer_list<const char*> allowed) const {
  checkKeys(std::vector<std::string>(allowed.begin(), allowed.end()));
}

void ConfigNode::checkKeys(const std::vector<std::string>& allowed) const {
  // A set: the top level allows every named sampler, and their number is the user's.
  const std::unordered_set<std::string_view> known(allowed.begin(), allowed.end());
  for (const auto& entry : entries()) {
    if (known.count(entry.first) == 0) {
      std::string list;
      for (const std::string& key : allowed) {
        list += (list.empty() ? "" : ", ") + key;
      }
      fail("unknown key " + quoteText(entry.first) + " (expected one of: " + list + ")");
    }
  }
}

}  // namespace placement_samplers
