#pragma once
// placement_benchmark --only physics: MuJoCo's model build and settling.

#include <string>

namespace placement_samplers::benchmark {

/// Prints the model build time, the settle time per PickPlace scene (its four objects, 1 s
/// simulated) on one thread, and a batch on 1 and 2 threads. @p configDir holds
/// pick_place.yaml; @p repetitions timed runs per figure (the median is printed).
void benchPhysics(const std::string& configDir, int repetitions);

}  // namespace placement_samplers::benchmark
