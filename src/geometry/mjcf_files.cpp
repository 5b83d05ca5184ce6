#include "geometry/mjcf_files.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>

namespace placement_samplers::detail {
namespace {

std::uint32_t bigEndian32(const std::string& data, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    v = (v << 8) | static_cast<unsigned char>(data[at + k]);
  }
  return v;
}

std::int32_t littleEndian32(const std::string& data, std::size_t at) {
  std::int32_t v = 0;
  std::memcpy(&v, data.data() + at, 4);
  return v;
}

/// Prints the document compactly, each element of the main file on its original line: MuJoCo's
/// messages ("Element 'geom', line 12") then point into the user's file.
class LinePreservingPrinter : public tinyxml2::XMLPrinter {
 public:
  LinePreservingPrinter() : XMLPrinter(nullptr, true) {}

  bool VisitEnter(const tinyxml2::XMLElement& element,
                  const tinyxml2::XMLAttribute* attribute) override {
    const char* text = CStr();
    const int size = CStrSize() - 1;  // without the terminating NUL
    for (; scanned_ < size; ++scanned_) {
      line_ += text[scanned_] == '\n' ? 1 : 0;
    }
    // Elements that were cloned from an included file have line 0: they stay where they are.
    for (; line_ < element.GetLineNum(); ++line_) {
      Putc('\n');  // whitespace, inside the still open tag of the parent at worst
      ++scanned_;
    }
    return XMLPrinter::VisitEnter(element, attribute);
  }

 private:
  int line_ = 1;
  int scanned_ = 0;
};

}  // namespace

std::string directoryOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

bool isAbsolute(const std::string& path) { return !path.empty() && path[0] == '/'; }

std::string fullName(const std::string& modelDir, std::string dir, const std::string& file) {
  if (isAbsolute(file)) {
    return file;
  }
  if (!dir.empty() && dir.back() != '/') {
    dir += '/';
  }
  return isAbsolute(dir) ? dir + file : modelDir + dir + file;
}

std::string extensionOf(const std::string& file) {
  const std::size_t dot = file.find_last_of('.');
  const std::size_t slash = file.find_last_of("/\\");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash) ||
      file.size() - dot > 16) {
    return "";
  }
  return file.substr(dot);
}

std::uint64_t countProduct(const std::string& text, std::uint64_t cap) {
  std::uint64_t product = 1;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t begin = text.find_first_not_of(" \t\r\n", at);
    if (begin == std::string::npos) {
      break;
    }
    const std::size_t end = std::min(text.find_first_of(" \t\r\n", begin), text.size());
    std::uint64_t value = 0;
    for (std::size_t k = begin; k < end && value <= cap; ++k) {
      const char c = text[k];
      value = c >= '0' && c <= '9' ? value * 10 + static_cast<std::uint64_t>(c - '0') : value;
    }
    product = std::min(cap + 1, product * std::min(std::max<std::uint64_t>(value, 1), cap + 1));
    at = end;
  }
  return product;
}

std::uint64_t heightFieldSamples(const std::string& data, const std::string& extension) {
  std::string lower = extension;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower == ".png") {
    return data.size() < 24 ? 0 : std::uint64_t{bigEndian32(data, 16)} * bigEndian32(data, 20);
  }
  if (data.size() < 8) {
    return 0;
  }
  const std::int64_t rows = littleEndian32(data, 0);
  const std::int64_t columns = littleEndian32(data, 4);
  return rows > 0 && columns > 0 ? static_cast<std::uint64_t>(rows * columns) : 0;
}

std::string printKeepingLines(const tinyxml2::XMLDocument& doc) {
  LinePreservingPrinter printer;
  doc.Print(&printer);
  return std::string(printer.CStr(), static_cast<std::size_t>(printer.CStrSize() - 1));
}

}  // namespace placement_samplers::detail
