#include "placement_samplers/input_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "placement_samplers/errors.hpp"

namespace placement_samplers {
namespace {

std::string bytesText(std::size_t bytes) {
  std::string text = std::to_string(bytes) + " bytes";
  if (bytes >= (std::size_t{1} << 20) && bytes % (std::size_t{1} << 20) == 0) {
    text += " (" + std::to_string(bytes >> 20) + " MiB)";
  }
  return text;
}

/// Closes a file descriptor on every path out.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) {
      ::close(fd_);
    }
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

bool startsWith(std::string_view text, std::size_t at, std::string_view prefix) {
  return text.compare(at, prefix.size(), prefix) == 0;
}

std::string readBounded(const std::string& path, std::size_t maxBytes, const char* what,
                        bool regularOnly) {
  const std::string cannot = std::string("cannot read ") + what + ": ";
  if (path.find('\0') != std::string::npos) {
    throw ConfigError(cannot + "the path contains a NUL byte");
  }
  // O_NONBLOCK: opening a FIFO that no one writes to returns at once instead of waiting.
  const Descriptor fd(
      ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | (regularOnly ? O_NONBLOCK : 0)));
  if (fd.get() < 0) {
    const int error = errno;
    throw ConfigError(cannot +
                      (error == ENOENT ? std::string("file not found") : std::strerror(error)));
  }
  struct stat status {};
  if (::fstat(fd.get(), &status) != 0) {
    throw ConfigError(cannot + std::strerror(errno));
  }
  if (S_ISDIR(status.st_mode)) {
    throw ConfigError(cannot + "it is a directory");
  }
  if (regularOnly && !S_ISREG(status.st_mode)) {
    throw ConfigError(cannot + "not a regular file");
  }
  const std::string tooLarge =
      std::string(what) + " is larger than the limit of " + bytesText(maxBytes);
  if (S_ISREG(status.st_mode) && static_cast<std::uint64_t>(status.st_size) > maxBytes) {
    throw ConfigError(tooLarge + ": it has " + std::to_string(status.st_size) + " bytes");
  }
  // Devices and pipes have no size: read at most one byte beyond the limit.
  std::string text;
  std::size_t used = 0;
  while (used <= maxBytes) {
    const std::size_t want = std::min<std::size_t>(maxBytes + 1 - used, std::size_t{1} << 16);
    if (text.size() < used + want) {
      text.resize(used + want);
    }
    const ssize_t got = ::read(fd.get(), &text[used], want);
    if (got < 0) {
      if (errno == EINTR) {
        continue;
      }
      throw ConfigError(cannot + std::strerror(errno));
    }
    if (got == 0) {
      break;
    }
    used += static_cast<std::size_t>(got);
  }
  if (used > maxBytes) {
    throw ConfigError(tooLarge);
  }
  text.resize(used);
  return text;
}

}  // namespace

std::string readFileBounded(const std::string& path, std::size_t maxBytes, const char* what) {
  return readBounded(path, maxBytes, what, false);
}

std::string readRegularFileBounded(const std::string& path, std::size_t maxBytes,
                                   const char* what) {
  return readBounded(path, maxBytes, what, true);
}

int xmlNestingDepth(std::string_view text, int stopAbove) {
  const std::size_t n = text.size();
  int depth = 0;
  int deepest = 0;
  std::size_t i = 0;
  // Skips to just after @p end, found from @p from; the end of the text when it is missing.
  const auto skipPast = [&](std::size_t from, std::string_view end) {
    const std::size_t at = text.find(end, from);
    return at == std::string_view::npos ? n : at + end.size();
  };
  // The first '>' from @p from outside quotes (and, with @p brackets, outside [...]); n when
  // there is none.
  const auto tagEnd = [&](std::size_t from, bool brackets) {
    int level = 0;
    char quote = 0;
    for (std::size_t j = from; j < n; ++j) {
      const char c = text[j];
      if (quote != 0) {
        quote = c == quote ? 0 : quote;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (brackets && c == '[') {
        ++level;
      } else if (brackets && c == ']') {
        --level;
      } else if (c == '>' && level <= 0) {
        return j;
      }
    }
    return n;
  };
  while (i < n) {
    const std::size_t open = text.find('<', i);
    if (open == std::string_view::npos || open + 1 >= n) {
      break;
    }
    if (startsWith(text, open, "<!--")) {
      i = skipPast(open + 4, "-->");
    } else if (startsWith(text, open, "<![CDATA[")) {
      i = skipPast(open + 9, "]]>");
    } else if (text[open + 1] == '?') {
      i = skipPast(open + 2, "?>");
    } else if (text[open + 1] == '!') {
      // <!DOCTYPE ... [ internal subset ] >: ends at the first '>' outside quotes and brackets.
      i = tagEnd(open + 2, true) + 1;
    } else if (text[open + 1] == '/') {
      depth = std::max(0, depth - 1);
      i = skipPast(open + 2, ">");
    } else {
      // A start tag: its end is the first '>' outside quoted attribute values.
      const std::size_t j = tagEnd(open + 1, false);
      if (j >= n) {
        break;  // unterminated: the parser refuses it
      }
      if (text[j - 1] != '/') {
        deepest = std::max(deepest, ++depth);
        if (deepest > stopAbove) {
          return deepest;
        }
      }
      i = j + 1;
    }
  }
  return deepest;
}

}  // namespace placement_samplers
