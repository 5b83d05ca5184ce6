// placement_samplers.robosuite: robosuite's samplers on the C++ core, and batches of scenes
// as numpy arrays (README, "From robosuite").

#include <pybind11/pybind11.h>

#include "placement_samplers/errors.hpp"
#include "python/numpy_support.hpp"
#include "python/ordered_values.hpp"
#include "python/py_values.hpp"
#include "python/py_batch.hpp"
#include "python/py_samplers.hpp"

namespace py = pybind11;
using namespace placement_samplers;
using namespace placement_samplers::python;

PYBIND11_MODULE(robosuite, m) {
  m.doc() =
      "robosuite's placement samplers (robosuite/utils/placement_samplers.py) on "
      "placement_samplers' C++ core: replace\n"
      "    from robosuite.utils.placement_samplers import UniformRandomSampler, "
      "SequentialCompositeSampler\n"
      "with\n"
      "    from placement_samplers.robosuite import UniformRandomSampler, "
      "SequentialCompositeSampler\n"
      "for the same placements, exceptions and numpy Generator states; and sample_scenes() for "
      "data sets.";
  if (!initNumpy()) {
    throw py::error_already_set();
  }
  initNames();
  findOrderedDictLayout();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) {
        std::rethrow_exception(p);
      }
    } catch (const ConfigError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const RequestError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  bindSamplers(m);
  m.def("sample_scenes", &sampleScenes, py::arg("config"), py::arg("seed"), py::arg("scenes"),
        py::arg("first_scene") = 0, py::arg("threads") = 0,
        R"doc(Scenes first_scene .. first_scene + scenes - 1 of a configuration (a YAML file's
path, or the same configuration as a dict) as numpy arrays, the layout of
`sample_scenes --output FILE.npz`: names [n], position [K, n, 3], orientation [K, n, 4]
(x, y, z, w), attempts [K, n], success [K], scene [K], seed (and stable, moved, turned,
fallen, sampled_position, sampled_orientation under physics). Scene i is numpy's
default_rng([seed, i]) through robosuite's samplers. seed 0: the configuration's seed, or a
random one (returned in 'seed'). threads 0: every core. The GIL is released while sampling.)doc");
  // What the module found at import, for tests and for users who want to know.
  m.def("_numpy_loops_in_use", &cosSinLoopsInUse,
        "True when quaternions use numpy's own float64 cos and sin loops (checked at import); "
        "else numpy is called for each.");
  m.def("_ordered_dict_walks", &orderedDictWalks,
        "True when a composite walks its OrderedDicts' lists of keys itself (their layout "
        "checked at import); else through their values() iterators.");
  m.def(
      "_pcg64_state_access",
      []() { return pcg64StateAccess() == Pcg64StateAccess::Memory ? "memory" : "dict"; },
      "How a PCG64's state is read and written: 'memory' (its layout checked at import) or "
      "'dict' (bit_generator.state).");
  m.def(
      "_set_pcg64_state_access",
      [](const std::string& access) {
        if (access != "memory" && access != "dict") {
          throw py::value_error("expected 'memory' or 'dict', got '" + access + "'");
        }
        if (!setPcg64StateAccess(access == "dict") && access == "memory") {
          throw py::value_error("PCG64's memory layout did not check out at import");
        }
      },
      py::arg("access"), "For tests: read and write PCG64 states through 'dict' or 'memory'.");
}
