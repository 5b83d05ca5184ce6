// libFuzzer target: MJCF text -> our document reader (includes, asset files, limits) ->
// MuJoCo's compiler -> sites and collision shapes -> bounds. The text goes through a file of its
// own, in a directory without meshes, so asset references exercise the error paths.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/geometry/mjcf_geometry.hpp"
#include "placement_samplers/geometry/object_model.hpp"

namespace {

std::string scratchFile() {
  char directory[] = "/tmp/mjcf_fuzzer.XXXXXX";
  const char* made = mkdtemp(directory);
  return std::string(made != nullptr ? made : "/tmp") + "/object.xml";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace placement_samplers;
  static const std::string path = scratchFile();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    MjcfObject object = loadMjcfObject(path, 10000);
    makeObject("fuzz", std::move(object.shapes), Eigen::Quaterniond::Identity());
  } catch (const ConfigError&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
