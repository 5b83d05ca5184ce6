#pragma once

// A fresh directory for a test's files, removed with everything in it at the end.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace placement_samplers::test {

class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "placement_samplers_test") {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            (prefix + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  /// Writes @p text into the file @p name; returns its path.
  std::string file(const std::string& name, const std::string& text) const {
    const std::string p = path(name);
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  std::string path(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace placement_samplers::test
