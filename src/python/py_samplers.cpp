// The Python classes: robosuite's constructors, attributes and bookkeeping methods, with
// robosuite's assertions and messages. Sampling is py_sampling.cpp's.

#include "python/py_samplers.hpp"

#include "python/sample_call.hpp"

#include <cstring>

namespace placement_samplers::python {
namespace {

py::object gRandomizationError;
PyTypeObject* gUniformType = nullptr;
PyTypeObject* gCompositeType = nullptr;

py::list intList(int a, int b) {
  py::list list;
  list.append(a);
  list.append(b);
  return list;
}

py::object defaultRng() { return py::module_::import("numpy.random").attr("default_rng")(); }

/// One object rather than a collection of them: robosuite's isinstance(x, MujocoObject),
/// for any object (MujocoObjects are not iterable).
bool isSingleObject(py::handle objects) {
  PyObject* iterator = PyObject_GetIter(objects.ptr());
  if (iterator == nullptr) {
    PyErr_Clear();
    return true;
  }
  Py_DECREF(iterator);
  return false;
}

/// robosuite's mujoco_objects argument: [] for None, [obj] for one, else a shallow copy.
py::object objectList(py::handle objects) {
  if (objects.is_none()) {
    return py::list();
  }
  if (isSingleObject(objects)) {
    py::list list;
    list.append(objects);
    return std::move(list);
  }
  return py::module_::import("copy").attr("copy")(objects);
}

/// [obj] for one object, else the collection as given.
py::object objectsGiven(py::handle objects) {
  if (isSingleObject(objects)) {
    py::list list;
    list.append(objects);
    return std::move(list);
  }
  return py::reinterpret_borrow<py::object>(objects);
}

bool contains(py::handle container, py::handle item) {
  const int found = PySequence_Contains(container.ptr(), item.ptr());
  if (found < 0) {
    throw py::error_already_set();
  }
  return found == 1;
}

[[noreturn]] void assertionError(const py::str& message) {
  PyErr_SetObject(PyExc_AssertionError, message.ptr());
  throw py::error_already_set();
}

/// Appends @p objects to @p list, each checked as not there yet.
void appendObjects(py::handle list, py::handle objects, const char* message) {
  for (py::handle object : objects) {
    if (contains(list, object)) {
      assertionError(py::str(message).format(object.attr("name")));
    }
    list.attr("append")(object);
  }
}

/// sample(fixtures=None, reference=None, on_top=True) called the way Python calls a method
/// of its own (vectorcall): the call's overhead counts in a call of a few microseconds.
template <class T, py::object (*Sample)(T&, py::handle, py::handle, py::handle)>
PyObject* fastSample(PyObject* self, PyObject* const* args, Py_ssize_t count, PyObject* names) {
  static const char* const kNames[3] = {"fixtures", "reference", "on_top"};
  PyObject* values[3] = {Py_None, Py_None, Py_True};
  bool given[3] = {false, false, false};
  const Py_ssize_t positional = PyVectorcall_NARGS(count);
  // The class's own name, as Python's messages give a method's qualified name.
  auto typeName = [self]() {
    const char* dot = std::strrchr(Py_TYPE(self)->tp_name, '.');
    return dot != nullptr ? dot + 1 : Py_TYPE(self)->tp_name;
  };
  if (positional > 3) {
    const char* type = typeName();
    PyErr_Format(PyExc_TypeError,
                 "%s.sample() takes from 1 to 4 positional arguments but %zd were given", type,
                 positional + 1);
    return nullptr;
  }
  for (Py_ssize_t i = 0; i < positional; ++i) {
    values[i] = args[i];
    given[i] = true;
  }
  const Py_ssize_t keywords = names != nullptr ? PyTuple_GET_SIZE(names) : 0;
  for (Py_ssize_t k = 0; k < keywords; ++k) {
    PyObject* name = PyTuple_GET_ITEM(names, k);
    int i = 0;
    while (i < 3 && PyUnicode_CompareWithASCIIString(name, kNames[i]) != 0) {
      ++i;
    }
    if (i == 3) {
      const char* type = typeName();
      PyErr_Format(PyExc_TypeError, "%s.sample() got an unexpected keyword argument '%U'", type,
                   name);
      return nullptr;
    }
    if (given[i]) {
      const char* type = typeName();
      PyErr_Format(PyExc_TypeError, "%s.sample() got multiple values for argument '%s'", type,
                   kNames[i]);
      return nullptr;
    }
    values[i] = args[positional + k];
    given[i] = true;
  }
  try {
    return Sample(native<T>(self), values[0], values[1], values[2]).release().ptr();
  } catch (py::error_already_set& e) {
    e.restore();
  } catch (const py::builtin_exception& e) {
    e.set_error();
  } catch (const std::exception& e) {
    PyErr_SetString(PyExc_RuntimeError, e.what());
  }
  return nullptr;
}

/// Puts @p method on the class @p c as Python's own methods are.
template <class C>
void addMethod(C& c, PyMethodDef& method) {
  auto* type = reinterpret_cast<PyTypeObject*>(c.ptr());
  py::object descriptor = py::reinterpret_steal<py::object>(PyDescr_NewMethod(type, &method));
  if (!descriptor || PyObject_SetAttrString(c.ptr(), method.ml_name, descriptor.ptr()) < 0) {
    throw py::error_already_set();
  }
}

void bindUniform(py::module_& m) {
  py::class_<PyUniformSampler> c(m, "UniformRandomSampler", py::dynamic_attr(), R"doc(
robosuite's UniformRandomSampler (robosuite/utils/placement_samplers.py): the same arguments,
attributes, results and exceptions, sampled by placement_samplers' C++ core. Objects are any
Python objects with name, horizontal_radius, bottom_offset, top_offset (and optionally
init_quat); rng is the numpy Generator (or any object with uniform()) drawn from, left where
robosuite's code would leave it.)doc");
  c.def(py::init([](py::object name, py::object mujocoObjects, py::object xRange, py::object yRange,
                    py::object rotation, py::object rotationAxis, py::object boundary,
                    py::object valid, py::object referencePos, py::object zOffset, py::object rng) {
          auto s = std::make_unique<PyUniformSampler>();
          s->xRange = xRange;
          s->yRange = yRange;
          s->rotation = rotation;
          s->rotationAxis = rotationAxis;
          s->rng = rng.is_none() ? defaultRng() : rng;
          s->name = name;
          s->mujocoObjects = objectList(mujocoObjects);
          s->ensureObjectBoundaryInRange = boundary;
          s->ensureValidPlacement = valid;
          s->referencePos = referencePos;
          s->zOffset = zOffset;
          return s;
        }),
        py::arg("name"), py::arg("mujoco_objects") = py::none(),
        py::arg("x_range") = py::make_tuple(0, 0), py::arg("y_range") = py::make_tuple(0, 0),
        py::arg("rotation") = py::none(), py::arg("rotation_axis") = "z",
        py::arg("ensure_object_boundary_in_range") = true, py::arg("ensure_valid_placement") = true,
        py::arg("reference_pos") = py::make_tuple(0, 0, 0), py::arg("z_offset") = 0.0,
        py::arg("rng") = py::none());
  c.def_readwrite("name", &PyUniformSampler::name);
  c.def_readwrite("mujoco_objects", &PyUniformSampler::mujocoObjects);
  c.def_readwrite("x_range", &PyUniformSampler::xRange);
  c.def_readwrite("y_range", &PyUniformSampler::yRange);
  c.def_readwrite("rotation", &PyUniformSampler::rotation);
  c.def_readwrite("rotation_axis", &PyUniformSampler::rotationAxis);
  c.def_readwrite("ensure_object_boundary_in_range",
                  &PyUniformSampler::ensureObjectBoundaryInRange);
  c.def_readwrite("ensure_valid_placement", &PyUniformSampler::ensureValidPlacement);
  c.def_readwrite("reference_pos", &PyUniformSampler::referencePos);
  c.def_readwrite("z_offset", &PyUniformSampler::zOffset);
  c.def_readwrite("rng", &PyUniformSampler::rng);
  c.def(
      "add_objects",
      [](PyUniformSampler& self, py::object objects) {
        appendObjects(self.mujocoObjects, objectsGiven(objects), "Object '{}' already in sampler!");
      },
      py::arg("mujoco_objects"));
  c.def("reset", [](PyUniformSampler& self) { self.mujocoObjects = py::list(); });
  static PyMethodDef sample = {
      "sample",
      reinterpret_cast<PyCFunction>(
          reinterpret_cast<void (*)()>(&fastSample<PyUniformSampler, sampleUniform>)),
      METH_FASTCALL | METH_KEYWORDS,
      "sample($self, fixtures=None, reference=None, on_top=True)\n--\n\nPlaces every object: a "
      "dict "
      "name -> (pos, quat (w, x, y, z), obj), fixtures included.\nRaises RandomizationError "
      "when an object finds no place in 5000 attempts."};
  addMethod(c, sample);
  gUniformType = reinterpret_cast<PyTypeObject*>(c.ptr());
}

void bindComposite(py::module_& m) {
  py::class_<PyCompositeSampler> c(m, "SequentialCompositeSampler", py::dynamic_attr(), R"doc(
robosuite's SequentialCompositeSampler: samplers appended with their sample_args run in order,
each seeing what the ones before placed. Any sampler with robosuite's sample() may be
appended; UniformRandomSampler and SequentialCompositeSampler of this module run in C++.)doc");
  c.def(py::init([](py::object name) {
          auto s = std::make_unique<PyCompositeSampler>();
          py::object ordered = py::module_::import("collections").attr("OrderedDict");
          s->samplers = ordered();
          s->sampleArgs = ordered();
          s->rng = defaultRng();
          s->name = name;
          s->mujocoObjects = py::list();
          return s;
        }),
        py::arg("name"));
  c.def_readwrite("name", &PyCompositeSampler::name);
  c.def_readwrite("mujoco_objects", &PyCompositeSampler::mujocoObjects);
  c.def_readwrite("samplers", &PyCompositeSampler::samplers);
  c.def_readwrite("sample_args", &PyCompositeSampler::sampleArgs);
  c.def_readwrite("rng", &PyCompositeSampler::rng);
  c.def(
      "append_sampler",
      [](PyCompositeSampler& self, py::object sampler, py::object sampleArgs) {
        appendObjects(self.mujocoObjects, sampler.attr("mujoco_objects"),
                      "Object '{}' already has sampler associated with it!");
        self.samplers[sampler.attr("name")] = sampler;
        self.sampleArgs[sampler.attr("name")] = sampleArgs;
      },
      py::arg("sampler"), py::arg("sample_args") = py::none());
  c.def(
      "hide",
      [](py::object self, py::object objects) {
        // robosuite's hide sampler: a reversed range, which numpy's Generator refuses when it
        // is sampled (ValueError), as robosuite's own does.
        py::object type =
            py::reinterpret_borrow<py::object>(reinterpret_cast<PyObject*>(gUniformType));
        py::object hider =
            type(py::arg("name") = "HideSampler", py::arg("mujoco_objects") = objects,
                 py::arg("x_range") = intList(-10, -20), py::arg("y_range") = intList(-10, -20),
                 py::arg("rotation") = intList(0, 0), py::arg("rotation_axis") = "z",
                 py::arg("z_offset") = 10, py::arg("ensure_object_boundary_in_range") = false,
                 py::arg("ensure_valid_placement") = false);
        self.attr("append_sampler")(py::arg("sampler") = hider);
      },
      py::arg("mujoco_objects"));
  c.def(
      "add_objects",
      [](PyCompositeSampler&, py::object) {
        PyErr_SetString(PyExc_AttributeError,
                        "add_objects() should not be called for SequentialCompsiteSamplers!");
        throw py::error_already_set();
      },
      py::arg("mujoco_objects"));
  c.def(
      "add_objects_to_sampler",
      [](PyCompositeSampler& self, py::object samplerName, py::object objects) {
        py::object given = objectsGiven(objects);
        appendObjects(self.mujocoObjects, given,
                      "Object '{}' already has sampler associated with it!");
        py::object names = self.samplers.attr("keys")();
        if (!contains(names, samplerName)) {
          assertionError(
              py::str("Invalid sub-sampler specified, valid options are: {}, requested: {}")
                  .format(names, samplerName));
        }
        self.samplers[samplerName].attr("add_objects")(given);
      },
      py::arg("sampler_name"), py::arg("mujoco_objects"));
  c.def("reset", [](PyCompositeSampler& self) {
    self.mujocoObjects = py::list();
    for (py::handle sampler : self.samplers.attr("values")()) {
      sampler.attr("reset")();
    }
  });
  static PyMethodDef sample = {
      "sample",
      reinterpret_cast<PyCFunction>(
          reinterpret_cast<void (*)()>(&fastSample<PyCompositeSampler, sampleComposite>)),
      METH_FASTCALL | METH_KEYWORDS,
      "sample($self, fixtures=None, reference=None, on_top=True)\n--\n\nRuns the samplers in "
      "order: a "
      "dict name -> (pos, quat (w, x, y, z), obj), fixtures included.\nreference and on_top "
      "fill in what a sampler's sample_args leave out."};
  addMethod(c, sample);
  gCompositeType = reinterpret_cast<PyTypeObject*>(c.ptr());
}

}  // namespace

void bindSamplers(py::module_& module) {
  // robosuite's own exception class when robosuite is already imported: `except` clauses
  // written for robosuite keep working.
  py::object modules = py::module_::import("sys").attr("modules");
  py::object utils = modules.attr("get")("robosuite.utils");
  if (!utils.is_none() && py::hasattr(utils, "RandomizationError")) {
    gRandomizationError = utils.attr("RandomizationError");
  } else {
    gRandomizationError = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
        "placement_samplers.robosuite.RandomizationError",
        "A sampler could not place all objects (robosuite's RandomizationError).", nullptr,
        nullptr));
  }
  module.attr("RandomizationError") = gRandomizationError;
  bindUniform(module);
  bindComposite(module);
}

py::handle randomizationError() { return gRandomizationError; }
PyTypeObject* uniformType() { return gUniformType; }
PyTypeObject* compositeType() { return gCompositeType; }

}  // namespace placement_samplers::python
