#pragma once

// robosuite's UniformRandomSampler and SequentialCompositeSampler as Python classes: their
// attributes are robosuite's (plain Python objects, read at every sample() as robosuite reads
// them), their sampling runs in the core library (py_sampling.cpp).

#include <pybind11/pybind11.h>

#include <deque>
#include <memory>
#include <vector>

#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "python/attribute_snapshot.hpp"
#include "python/caller_rng.hpp"

namespace placement_samplers::python {

namespace py = pybind11;

class SampleCall;

/// The core sampler built from one reading of a Python sampler's attributes, kept while they
/// read the same (py_sampling.cpp).
struct CoreCache {
  std::vector<double> key;      ///< the numbers it was built from, bit for bit
  std::vector<double> reading;  ///< this call's numbers (kept: no allocation per call)
  std::shared_ptr<UniformRandomSampler> sampler;
};

/// Whatever sample() needs between calls: the call's buffers, and whether they are in use
/// (a sampler reached again from inside its own call gets buffers of its own).
struct CallSlot {
  std::unique_ptr<SampleCall> call;
  bool busy = false;
  CallSlot();
  ~CallSlot();
};

/// robosuite's UniformRandomSampler.
class PyUniformSampler {
 public:
  py::object name;
  py::object mujocoObjects;
  py::object xRange;
  py::object yRange;
  py::object rotation;
  py::object rotationAxis;
  py::object ensureObjectBoundaryInRange;
  py::object ensureValidPlacement;
  py::object referencePos;
  py::object zOffset;
  py::object rng;

  CoreCache core;
  /// The attributes of mujoco_objects[k] as last read (attribute_snapshot.hpp); a deque: a
  /// nested call may add to it while a reading holds one.
  std::deque<AttributeSnapshot> snapshots;
  CallerRng rngInfo;  ///< what `rng` is, while it stays the same object
  CallSlot slot;
};

/// robosuite's SequentialCompositeSampler.
class PyCompositeSampler {
 public:
  py::object name;
  py::object mujocoObjects;
  py::object samplers;    ///< OrderedDict name -> sampler
  py::object sampleArgs;  ///< OrderedDict name -> dict or None
  py::object rng;

  CallSlot slot;
};

/// The C++ object of a Python sampler of class T (or of a Python subclass of it).
template <class T>
T& native(py::handle sampler) {
  auto* instance = reinterpret_cast<py::detail::instance*>(sampler.ptr());
  if (instance->simple_layout && instance->simple_value_holder[0] != nullptr) {
    return *static_cast<T*>(instance->simple_value_holder[0]);
  }
  return sampler.cast<T&>();  // raises when it was never initialised
}

/// Registers both classes, RandomizationError and their methods in @p module.
void bindSamplers(py::module_& module);

/// The exception of a sample() that runs out of attempts: robosuite's own
/// robosuite.utils.RandomizationError when robosuite was imported first, else the module's.
py::handle randomizationError();

/// sample() of each class (py_sampling.cpp).
py::object sampleUniform(PyUniformSampler& self, py::handle fixtures, py::handle reference,
                         py::handle onTop);
py::object sampleComposite(PyCompositeSampler& self, py::handle fixtures, py::handle reference,
                           py::handle onTop);

/// The type objects of the two classes, for telling native samplers in a composite (set by
/// bindSamplers()).
PyTypeObject* uniformType();
PyTypeObject* compositeType();

}  // namespace placement_samplers::python
