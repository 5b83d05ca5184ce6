// Every configuration in config/ builds, places its scenes, and can be loaded with rosparam.
#include <gtest/gtest.h>

#include <dirent.h>

#include <string>
#include <vector>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {
namespace {

const std::string kSource = PLACEMENT_SAMPLERS_SOURCE_DIR;

std::vector<std::string> shippedConfigs() {
  std::vector<std::string> files;
  if (DIR* dir = opendir((kSource + "/config").c_str())) {
    while (const dirent* entry = readdir(dir)) {
      const std::string name = entry->d_name;
      if (name.size() > 5 && name.substr(name.size() - 5) == ".yaml") {
        files.push_back(name);
      }
    }
    closedir(dir);
  }
  return files;
}

// rosparam cannot store a YAML null, so a null would break `rosparam load` for the node.
void expectNoNull(const ConfigNode& node, const std::string& file) {
  EXPECT_NE(node.type(), ConfigNode::Type::Null) << file << ": " << node.path();
  if (node.isMap()) {
    for (const auto& entry : node.entries()) {
      expectNoNull(entry.second, file);
    }
  } else if (node.isList()) {
    for (const ConfigNode& element : node.elements()) {
      expectNoNull(element, file);
    }
  }
}

TEST(ShippedConfigs, BuildSampleAndHoldNoNull) {
  const std::vector<std::string> files = shippedConfigs();
  ASSERT_GE(files.size(), 7u);
  BuildOptions options;
  options.packageResolver = [](const std::string& package) {
    return package == "placement_samplers" ? kSource : std::string();
  };
  options.baseDirectory = kSource + "/config";
  for (const std::string& file : files) {
    const ConfigNode tree = loadYamlFile(kSource + "/config/" + file);
    expectNoNull(tree, file);
    const SceneGenerator generator(buildSceneConfig(tree, options));
    const PreparedRequest request = generator.prepare(SampleRequest());
    const std::vector<SceneResult> scenes = generator.sampleScenes(request, 1, 20, 1);
    std::size_t placed = 0;
    for (const SceneResult& scene : scenes) {
      placed += scene.success ? 1 : 0;
    }
    // long_boxes.yaml packs sticks until one does not fit: it is meant to fail.
    if (file == "long_boxes.yaml") {
      EXPECT_EQ(placed, 0u) << file;
    } else {
      EXPECT_EQ(placed, scenes.size()) << file << ": " << scenes.front().message;
    }
  }
}

}  // namespace
}  // namespace placement_samplers
