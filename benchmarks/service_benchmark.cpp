// service_benchmark: calls the server's sample_placements (one scene, default sampler: a
// Lift-sized request with config/lift.yaml) and its empty ping service alternately, over
// persistent connections, and prints the latency percentiles of both and their ratio. Run with
// and without dry_run, so that the cost of broadcasting tf frames and markers shows apart.
// --load adds two tables: ~ping while a heavy batch uses every core, and light calls beside
// clients whose requests can never be placed.

#include <ros/ros.h>
#include <shape_msgs/SolidPrimitive.h>
#include <std_srvs/Empty.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
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

/// The request of a client whose objects can never be placed: a wall over the whole table and an
/// absurd attempt limit (robosuite's radius test; in the exact-only mode nothing proves it).
placement_samplers::SamplePlacements::Request hopelessRequest(std::uint8_t collisionCheck) {
  placement_samplers::SamplePlacements::Request r;
  r.seed = 3;
  r.max_attempts = 4000000000u;
  r.dry_run = true;
  r.collision_check = collisionCheck;
  placement_samplers::Fixture wall;
  wall.name = "wall";
  wall.shape.type = shape_msgs::SolidPrimitive::BOX;
  wall.shape.dimensions = {3.0, 3.0, 1.0};
  wall.pose.position.z = 0.8;
  wall.pose.orientation.w = 1.0;
  r.fixtures.push_back(wall);
  return r;
}

void printLatencies(const char* label, const std::vector<double>& v) {
  std::printf("%-40s %8zu %10.1f %10.1f %10.1f\n", label, v.size(), quantile(v, 0.5),
              quantile(v, 0.99), v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()));
}

/// ~ping (sequential calls, persistent) while another client keeps one heavy batch running.
void pingUnderHeavyCall(ros::NodeHandle& nh, const std::string& server, double seconds) {
  std::atomic<bool> stop{false};
  std::atomic<int> batches{0};
  std::thread heavy([&] {
    ros::ServiceClient client =
        nh.serviceClient<placement_samplers::SamplePlacements>(server + "/sample_placements", true);
    while (!stop) {
      placement_samplers::SamplePlacements srv;
      srv.request.seed = 7;
      srv.request.num_scenes = 10000;
      srv.request.dry_run = true;
      client.call(srv);
      ++batches;
    }
  });
  ros::ServiceClient ping = nh.serviceClient<std_srvs::Empty>(server + "/ping", true);
  std::vector<double> latencies;
  ros::WallDuration(0.5).sleep();  // the batch is running
  const Clock::time_point end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                   std::chrono::duration<double>(seconds));
  while (Clock::now() < end) {
    std_srvs::Empty empty;
    const Clock::time_point start = Clock::now();
    ping.call(empty);
    latencies.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  stop = true;
  heavy.join();
  std::printf("\n~ping during batches of 10000 scenes on every core (%d batches, %.0f s)\n",
              batches.load(), seconds);
  std::printf("%-40s %8s %10s %10s %10s\n", "", "calls", "p50 [us]", "p99 [us]", "max [us]");
  printLatencies("ping", latencies);
}

/// Light one-scene calls of @p light clients beside @p hopeless clients that send requests that
/// can never be placed, all in a loop on their own persistent connections.
void lightBesideHopeless(ros::NodeHandle& nh, const std::string& server, int light, int hopeless,
                         std::uint8_t mode, double seconds) {
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::vector<double> lightLatencies;
  std::vector<double> hopelessLatencies;
  std::vector<std::thread> clients;
  for (int c = 0; c < light + hopeless; ++c) {
    clients.emplace_back([&, c] {
      ros::ServiceClient client = nh.serviceClient<placement_samplers::SamplePlacements>(
          server + "/sample_placements", true);
      const bool isLight = c < light;
      std::vector<double> mine;
      for (std::uint64_t i = 1; !stop; ++i) {
        placement_samplers::SamplePlacements srv;
        if (isLight) {
          srv.request.seed = i;
          srv.request.dry_run = true;
        } else {
          srv.request = hopelessRequest(mode);
        }
        const Clock::time_point start = Clock::now();
        client.call(srv);
        mine.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
      }
      std::lock_guard<std::mutex> lock(mutex);
      auto& all = isLight ? lightLatencies : hopelessLatencies;
      all.insert(all.end(), mine.begin(), mine.end());
    });
  }
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  stop = true;
  for (std::thread& t : clients) {
    t.join();
  }
  std::printf("\n%d light clients (1 scene) beside %d hopeless ones (%s), %.0f s\n", light,
              hopeless,
              mode == placement_samplers::SamplePlacements::Request::CHECK_FCL
                  ? "exact test alone: runs to the time limit"
                  : "radius test: no room proven",
              seconds);
  std::printf("%-40s %8s %10s %10s %10s\n", "", "calls", "p50 [us]", "p99 [us]", "max [us]");
  printLatencies("light calls", lightLatencies);
  printLatencies("hopeless calls", hopelessLatencies);
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "service_benchmark", ros::init_options::AnonymousName);
  std::string server = "/placement_server";
  int calls = 2000;
  bool load = false;
  std::string floor;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--server" && i + 1 < argc) {
      server = argv[++i];
    } else if (arg == "--floor" && i + 1 < argc) {
      floor = argv[++i];
    } else if (arg == "--load") {
      load = true;
    } else if (arg == "--calls" && i + 1 < argc) {
      calls = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(
          stderr,
          "usage: service_benchmark [--server NS] [--calls N] [--floor SERVICE] [--load]\n"
          "Calls NS/sample_placements and NS/ping alternately, N times each (default "
          "/placement_server, 2000),\nwith dry_run false then true, and prints p50/p99.\n"
          "--floor: also a bare roscpp std_srvs/Empty service (test/ros/minimal_service's "
          "~ping),\nthe floor of any service's latency, alternating with NS/ping.\n"
          "--load: then ~ping during heavy batches, and light calls beside hopeless ones.\n");
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
  if (!floor.empty()) {
    if (!ros::service::waitForService(floor, ros::Duration(30.0))) {
      std::fprintf(stderr, "service_benchmark: %s is not available\n", floor.c_str());
      return 1;
    }
    ros::ServiceClient floorClient = nh.serviceClient<std_srvs::Empty>(floor, true);
    std::vector<double> bare;
    std::vector<double> ping;
    for (int i = 0; i < calls + 200; ++i) {
      for (auto* client : {&floorClient, &pingClient}) {
        std_srvs::Empty empty;
        const Clock::time_point start = Clock::now();
        failures += client->call(empty) ? 0 : 1;
        if (i >= 200) {  // the first 200 warm up
          (client == &floorClient ? bare : ping)
              .push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
        }
      }
    }
    const double bare50 = quantile(bare, 0.5);
    std::printf("%-26s %10.1f %10.1f %10.1f %10.1f %12.2f\n", "bare roscpp (floor)", bare50,
                quantile(bare, 0.99), quantile(ping, 0.5), quantile(ping, 0.99),
                bare50 / quantile(ping, 0.5));
  }
  if (load) {
    pingUnderHeavyCall(nh, server, 10.0);
    lightBesideHopeless(nh, server, 8, 8,
                        placement_samplers::SamplePlacements::Request::CHECK_RADIUS, 10.0);
    lightBesideHopeless(nh, server, 8, 8, placement_samplers::SamplePlacements::Request::CHECK_FCL,
                        10.0);
  }
  if (failures > 0) {
    std::fprintf(stderr, "service_benchmark: %d calls failed\n", failures);
    return 1;
  }
  return 0;
}
