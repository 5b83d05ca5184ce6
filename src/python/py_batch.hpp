#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>

namespace placement_samplers::python {

namespace py = pybind11;

/// Scenes @p firstScene .. @p firstScene + @p scenes - 1 of seed @p seed (0: the
/// configuration's seed, or a random one when that is 0 too) of the configuration @p config (a
/// YAML file's path, or the same configuration as a dict) on @p threads threads (0 = every
/// core), as the arrays `sample_scenes --output FILE.npz` writes: names, position,
/// orientation, attempts, success, scene, seed (and the physics members of its mode).
/// Samples with the GIL released.
/// @throw ConfigError, RequestError (ValueError in Python)
py::dict sampleScenes(py::object config, std::uint64_t seed, std::uint64_t scenes,
                      std::uint64_t firstScene, unsigned threads);

}  // namespace placement_samplers::python
