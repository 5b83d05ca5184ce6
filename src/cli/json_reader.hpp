#pragma once
// A pull reader of JSON text for sample_scenes --validate (scene_line_reader.cpp): each value is
// read where it stands, nothing is kept but what the caller takes. Private to the CLI.

#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>

#include "cli/scene_line_reader.hpp"

namespace placement_samplers::detail {

/// Nesting levels of a skipped value, at most.
constexpr int kMaxJsonDepth = 100;

/// A JSON reader over one line; errors are LineErrors "not JSON: ... at byte N".
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
    if (depth > kMaxJsonDepth) {
      fail("nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
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

}  // namespace placement_samplers::detail
