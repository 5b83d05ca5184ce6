// libFuzzer target: YAML text -> configuration tree -> builder -> one scene. Any exception other
// than the library's own typed errors, any crash or sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace placement_samplers;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const SceneGenerator generator(buildSceneConfig(parseYaml(text, "fuzz.yaml")));
    SampleRequest request;
    request.maxAttempts = 50;  // keeps each input fast whatever max_attempts it sets
    const PreparedRequest prepared = generator.prepare(request);
    generator.sampleScene(prepared, 1, 0);
  } catch (const ConfigError&) {
  } catch (const RequestError&) {
  }
  return 0;
}
