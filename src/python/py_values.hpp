#pragma once

// Reading Python values as robosuite's Python code reads them: numbers (as numpy turns them
// into float64), items, unpacking with Python's messages, attribute names made once.

#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <cstddef>

namespace placement_samplers::python {

namespace py = pybind11;

/// Attribute and string names, interned once.
struct Names {
  PyObject* name = PyUnicode_InternFromString("name");
  PyObject* horizontalRadius = PyUnicode_InternFromString("horizontal_radius");
  PyObject* bottomOffset = PyUnicode_InternFromString("bottom_offset");
  PyObject* topOffset = PyUnicode_InternFromString("top_offset");
  PyObject* initQuat = PyUnicode_InternFromString("init_quat");
  PyObject* axes[3] = {PyUnicode_InternFromString("x"), PyUnicode_InternFromString("y"),
                       PyUnicode_InternFromString("z")};
};
/// numpy.float64 (set by initNames()).
extern PyTypeObject* gFloat64Type;

/// The names, made at import (initNames()).
extern const Names* gNames;
inline const Names& names() { return *gNames; }
/// Makes names() and finds numpy.float64; call once at import, with the GIL.
void initNames();

/// toDouble() for what is not a float.
bool toDoubleSlow(PyObject* value, double& out);

/// A float, numpy's float64 among them (named first: it skips the search of its bases).
inline bool isFloat(PyObject* value) {
  return Py_IS_TYPE(value, &PyFloat_Type) || Py_TYPE(value) == gFloat64Type || PyFloat_Check(value);
}

/// float(@p value) as numpy reads a scalar (PyFloat_AsDouble: a float, numpy's float64
/// among them, is its stored value). @return false with a Python error set
inline bool toDouble(PyObject* value, double& out) {
  if (isFloat(value)) {
    out = PyFloat_AS_DOUBLE(value);
    return true;
  }
  return toDoubleSlow(value, out);
}

/// @p sequence [@p index] as a double (index -1: the last item, as robosuite's `[-1]`);
/// numpy arrays, tuples and lists of floats read without a Python call.
bool itemAsDouble(PyObject* sequence, Py_ssize_t index, double& out);

/// unpack() for what is not a list or tuple of @p count items.
bool unpackSlow(PyObject* value, std::size_t count, py::object* out);

/// Python's `a, b, ... = value` into @p out, with Python's messages.
inline bool unpack(PyObject* value, std::size_t count, py::object* out) {
  if ((PyTuple_CheckExact(value) || PyList_CheckExact(value)) &&
      static_cast<std::size_t>(PySequence_Fast_GET_SIZE(value)) == count) {
    for (std::size_t i = 0; i < count; ++i) {
      out[i] = py::reinterpret_borrow<py::object>(
          PySequence_Fast_GET_ITEM(value, static_cast<Py_ssize_t>(i)));
    }
    return true;
  }
  return unpackSlow(value, count, out);
}

/// A float, or an int that a double holds exactly: what numpy reads it as.
bool plainNumber(PyObject* item, double& out);

/// A list or tuple of exactly @p count floats or ints, read without numpy, as numpy would.
bool plainNumbers(PyObject* value, std::size_t count, double* out);

/// Sets AssertionError(@p message).
void setAssertion(const py::str& message);

/// A list or tuple of two floats (numpy's float64 among them) into @p out: read as
/// `a, b = value` and float() read them, without a Python call. @return false when it is not.
bool floatPair(PyObject* value, Eigen::Vector2d& out);

/// Two exact str objects equal (their text; as == compares them).
bool sameText(PyObject* a, PyObject* b);

/// @p object.top_offset[-1]. @return false with a Python error set
bool readTop(PyObject* object, double& top);

/// What robosuite's overlap test reads of a placement (pos, quat, obj): pos as (x, y, z),
/// obj.horizontal_radius and obj.top_offset[-1].
/// @throw py::error_already_set when they cannot be read
void readEntry(py::handle value, Eigen::Vector3d& position, double& radius, double& top);

}  // namespace placement_samplers::python
