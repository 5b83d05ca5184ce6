#include "bench_support.hpp"

#include "placement_samplers/geometry/mesh_loader.hpp"

#ifndef PLACEMENT_SAMPLERS_CONFIG_DIR
#define PLACEMENT_SAMPLERS_CONFIG_DIR "config"
#endif

namespace bench {

/// The package's config/ as ROS_PACKAGE_PATH finds it (the install space's share directory
/// once installed, the source tree in a devel space), else the source tree it was built from.
std::string defaultConfigDir() {
  const std::string package = ps::findPackageInRosPackagePath("placement_samplers");
  if (!package.empty() && std::filesystem::is_directory(package + "/config")) {
    return package + "/config";
  }
  return PLACEMENT_SAMPLERS_CONFIG_DIR;
}

volatile double gSink = 0.0;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

SceneStats collectStats(SceneLoop& loop, std::uint64_t scenes) {
  SceneStats stats;
  for (std::uint64_t i = 0; i < scenes; ++i) {
    loop.seedScene(i);
    const bool ok = loop.scene();
    ++stats.scenes;
    for (const ps::ObjectPlacement& p : loop.context().placements()) {
      ++stats.objects;
      stats.attempts += p.attempts;
      stats.checksum += p.position.x() + p.position.y() + p.position.z();
    }
    if (!ok) {
      ++stats.failed;
      if (loop.context().failure()) {
        ++stats.objects;
        stats.attempts += loop.context().failure()->attempts;
      }
    }
  }
  return stats;
}

Setup makeSetup(const ps::ConfigNode& tree, std::optional<ps::CollisionMode> mode) {
  Setup setup;
  setup.generator = std::make_unique<ps::SceneGenerator>(ps::buildSceneConfig(tree));
  ps::SampleRequest request;
  request.collisionCheck = mode;
  setup.request = setup.generator->prepare(request);
  return setup;
}

double batchNs(const Options& options, const Setup& setup, unsigned threads) {
  return nsPerOp(options, [&](std::uint64_t n) {
    sampleInBlocks(setup, n, threads, [](const std::vector<ps::SceneResult>& results) {
      gSink = gSink + static_cast<double>(results.back().placements.size());
    });
  });
}

bool fclAvailable() {
  try {
    ps::makeCollisionChecker(ps::CollisionMode::Fcl, 0.0);
    return true;
  } catch (const ps::ConfigError&) {
    return false;
  }
}

double logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]);
    const double ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

std::string fmt(const char* format, double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, v);
  return buffer;
}

void rule() { std::printf("%s\n", std::string(100, '-').c_str()); }

}  // namespace bench
