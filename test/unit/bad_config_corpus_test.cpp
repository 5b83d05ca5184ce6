// Every file in test/data/bad/config is an invalid configuration whose first line says the exact
// error expected: "# expect: <message>". New cases need no code, only a file.
#include <gtest/gtest.h>

#include <dirent.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/errors.hpp"

namespace placement_samplers {
namespace {

const std::string kDir = std::string(PLACEMENT_SAMPLERS_SOURCE_DIR) + "/test/data/bad/config";

std::vector<std::string> corpus() {
  std::vector<std::string> files;
  if (DIR* dir = opendir(kDir.c_str())) {
    while (const dirent* entry = readdir(dir)) {
      const std::string name = entry->d_name;
      if (name.size() > 5 && name.substr(name.size() - 5) == ".yaml") {
        files.push_back(name);
      }
    }
    closedir(dir);
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(BadConfigCorpus, EveryCaseFailsWithItsExactMessage) {
  const std::vector<std::string> files = corpus();
  ASSERT_GE(files.size(), 30u) << "corpus not found in " << kDir;
  for (const std::string& name : files) {
    std::ifstream in(kDir + "/" + name);
    std::string first;
    std::getline(in, first);
    const std::string prefix = "# expect: ";
    ASSERT_EQ(first.rfind(prefix, 0), 0u) << name << " lacks its '# expect: ' line";
    const std::string expected = first.substr(prefix.size());
    std::stringstream rest;
    rest << in.rdbuf();
    try {
      buildSceneConfig(parseYaml(first + "\n" + rest.str(), name));
      ADD_FAILURE() << name << ": accepted, expected: " << expected;
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()), expected) << name;
    }
  }
}

}  // namespace
}  // namespace placement_samplers
