// service_benchmark: calls the server's sample_placements (one scene, default sampler: a
// Lift-sized request with config/lift.yaml) and its empty ping service alternately, over
// persistent connections, and prints the latency percentiles of both and their ratio. Run with
// and without dry_run, so that the cost of broadcasting tf frames and markers shows apart.

#include <ros/ros.h>
#include <std_srvs/Empty.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "placement_samplers/SamplePlacements.h"

namespace {

using Clock = std::chrono::steady_clock;

/// The @p q quantile (0..1) of @p v [us], nearest rank.
double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const auto rank = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(rank, v.size() - 1)];
}

/// Latencies [us] of @p calls alternating calls to both services.
struct Run {
  std::vector<double> sample;
  std::vector<double> ping;
  int failures = 0;
};

Run measure(ros::ServiceClient& sampleClient, ros::ServiceClient& pingClient, int calls,
            bool dryRun) {
  Run run;
  placement_samplers::SamplePlacements srv;
  std_srvs::Empty empty;
  for (int i = 0; i < calls; ++i) {
    srv.request.seed = static_cast<std::uint64_t>(i) + 1;  // reproducible, never 0
    srv.request.num_scenes = 1;
    srv.request.dry_run = dryRun;
    srv.response = placement_samplers::SamplePlacements::Response();
    Clock::time_point start = Clock::now();
    const bool ok = sampleClient.call(srv);
    run.sample.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
    run.failures += ok && srv.response.success ? 0 : 1;

    start = Clock::now();
    run.failures += pingClient.call(empty) ? 0 : 1;
    run.ping.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
  }
  return run;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "service_benchmark", ros::init_options::AnonymousName);
  std::string server = "/placement_server";
  int calls = 2000;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--server" && i + 1 < argc) {
      server = argv[++i];
    } else if (arg == "--calls" && i + 1 < argc) {
      calls = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(
          stderr,
          "usage: service_benchmark [--server NS] [--calls N]\n"
          "Calls NS/sample_placements and NS/ping alternately, N times each (default "
          "/placement_server, 2000),\nwith dry_run false then true, and prints p50/p99.\n");
      return 2;
    }
  }
  ros::NodeHandle nh;
  const std::string sampleName = server + "/sample_placements";
  const std::string pingName = server + "/ping";
  if (!ros::service::waitForService(sampleName, ros::Duration(30.0)) ||
      !ros::service::waitForService(pingName, ros::Duration(5.0))) {
    std::fprintf(stderr, "service_benchmark: %s or %s is not available\n", sampleName.c_str(),
                 pingName.c_str());
    return 1;
  }
  // Persistent: one TCP connection each, as a client calling in a loop would keep.
  ros::ServiceClient sampleClient =
      nh.serviceClient<placement_samplers::SamplePlacements>(sampleName, true);
  ros::ServiceClient pingClient = nh.serviceClient<std_srvs::Empty>(pingName, true);

  measure(sampleClient, pingClient, 200, true);  // warm up connections, caches, allocators
  std::printf("service_benchmark: %d alternating calls of %s (1 scene) and %s\n", calls,
              sampleName.c_str(), pingName.c_str());
  std::printf("%-26s %10s %10s %10s %10s %12s\n", "", "p50 [us]", "p99 [us]", "ping p50",
              "ping p99", "p50 ratio");
  int failures = 0;
  for (const bool dryRun : {false, true}) {
    const Run run = measure(sampleClient, pingClient, calls, dryRun);
    failures += run.failures;
    const double p50 = quantile(run.sample, 0.5);
    const double ping50 = quantile(run.ping, 0.5);
    std::printf("%-26s %10.1f %10.1f %10.1f %10.1f %12.2f\n",
                dryRun ? "sample_placements dry_run" : "sample_placements", p50,
                quantile(run.sample, 0.99), ping50, quantile(run.ping, 0.99), p50 / ping50);
  }
  if (failures > 0) {
    std::fprintf(stderr, "service_benchmark: %d calls failed\n", failures);
    return 1;
  }
  return 0;
}
