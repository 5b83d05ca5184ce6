#include "python/py_values.hpp"

#include <cstring>

#include "python/numpy_support.hpp"

namespace placement_samplers::python {
namespace {

PyObject* minusOne() {
  static PyObject* value = PyLong_FromLong(-1);
  return value;
}

}  // namespace

const Names* gNames = nullptr;

PyTypeObject* gFloat64Type = nullptr;

void initNames() {
  if (gNames == nullptr) {
    gNames = new Names();  // kept for the life of the process, as the interned strings
  }
  if (gFloat64Type == nullptr) {
    py::object type = py::module_::import("numpy").attr("float64");
    gFloat64Type = reinterpret_cast<PyTypeObject*>(type.release().ptr());
  }
}

bool toDoubleSlow(PyObject* value, double& out) {
  out = PyFloat_AsDouble(value);
  return !(out == -1.0 && PyErr_Occurred());
}

/// @p sequence [@p index] as a double (index -1: the last item, as robosuite's `[-1]`).
bool itemAsDouble(PyObject* sequence, Py_ssize_t index, double& out) {
  // numpy arrays, tuples and lists of floats as their items read: without a Python call.
  if (float64ArrayItem(sequence, index, out)) {
    return true;
  }
  if (PyTuple_CheckExact(sequence) || PyList_CheckExact(sequence)) {
    const Py_ssize_t size = PySequence_Fast_GET_SIZE(sequence);
    const Py_ssize_t i = index < 0 ? index + size : index;
    if (i >= 0 && i < size && PyFloat_Check(PySequence_Fast_GET_ITEM(sequence, i))) {
      out = PyFloat_AS_DOUBLE(PySequence_Fast_GET_ITEM(sequence, i));
      return true;
    }
  }
  PyObject* key = index == -1 ? minusOne() : PyLong_FromSsize_t(index);
  if (key == nullptr) {
    return false;
  }
  PyObject* item = PyObject_GetItem(sequence, key);
  if (index != -1) {
    Py_DECREF(key);
  }
  if (item == nullptr) {
    return false;
  }
  const bool ok = toDouble(item, out);
  Py_DECREF(item);
  return ok;
}

/// Python's `a, b, ... = value` into @p out (new references), with Python's messages.
bool unpackSlow(PyObject* value, std::size_t count, py::object* out) {
  if ((PyTuple_CheckExact(value) || PyList_CheckExact(value)) &&
      static_cast<std::size_t>(PySequence_Fast_GET_SIZE(value)) == count) {
    return unpack(value, count, out);
  }
  PyObject* iterator = PyObject_GetIter(value);
  if (iterator == nullptr) {
    if (PyErr_ExceptionMatches(PyExc_TypeError)) {
      PyErr_Clear();
      PyErr_Format(PyExc_TypeError, "cannot unpack non-iterable %.200s object",
                   Py_TYPE(value)->tp_name);
    }
    return false;
  }
  py::object guard = py::reinterpret_steal<py::object>(iterator);
  for (std::size_t i = 0; i < count; ++i) {
    PyObject* item = PyIter_Next(iterator);
    if (item == nullptr) {
      if (!PyErr_Occurred()) {
        PyErr_Format(PyExc_ValueError, "not enough values to unpack (expected %zu, got %zu)", count,
                     i);
      }
      return false;
    }
    out[i] = py::reinterpret_steal<py::object>(item);
  }
  PyObject* extra = PyIter_Next(iterator);
  if (extra != nullptr) {
    Py_DECREF(extra);
    PyErr_Format(PyExc_ValueError, "too many values to unpack (expected %zu)", count);
    return false;
  }
  return !PyErr_Occurred();
}

/// A float, or an int that a double holds exactly: what numpy reads it as.
bool plainNumber(PyObject* item, double& out) {
  if (PyFloat_Check(item)) {
    out = PyFloat_AS_DOUBLE(item);
    return true;
  }
  if (!PyLong_CheckExact(item)) {
    return false;
  }
  const long long v = PyLong_AsLongLong(item);
  if ((v == -1 && PyErr_Occurred()) || v > (1LL << 53) || v < -(1LL << 53)) {
    PyErr_Clear();
    return false;
  }
  out = static_cast<double>(v);
  return true;
}

/// A list or tuple of exactly @p count floats or ints: read without numpy, as numpy would.
bool plainNumbers(PyObject* value, std::size_t count, double* out) {
  if (!PyTuple_CheckExact(value) && !PyList_CheckExact(value)) {
    return false;
  }
  if (static_cast<std::size_t>(PySequence_Fast_GET_SIZE(value)) != count) {
    return false;
  }
  for (std::size_t i = 0; i < count; ++i) {
    if (!plainNumber(PySequence_Fast_GET_ITEM(value, static_cast<Py_ssize_t>(i)), out[i])) {
      return false;
    }
  }
  return true;
}

void setAssertion(const py::str& message) { PyErr_SetObject(PyExc_AssertionError, message.ptr()); }

/// A list or tuple of two floats (numpy's float64 among them) into @p out: read as
/// `a, b = value` and float() read them, without a Python call. @return false when it is not.
bool floatPair(PyObject* value, Eigen::Vector2d& out) {
  if ((!PyList_CheckExact(value) && !PyTuple_CheckExact(value)) ||
      PySequence_Fast_GET_SIZE(value) != 2) {
    return false;
  }
  PyObject* a = PySequence_Fast_GET_ITEM(value, 0);
  PyObject* b = PySequence_Fast_GET_ITEM(value, 1);
  if (!isFloat(a) || !isFloat(b)) {
    return false;
  }
  out = Eigen::Vector2d(PyFloat_AS_DOUBLE(a), PyFloat_AS_DOUBLE(b));
  return true;
}

/// Two exact str objects equal (their text; as == compares them).
bool sameText(PyObject* a, PyObject* b) {
  if (!PyUnicode_IS_READY(a) || !PyUnicode_IS_READY(b)) {
    return PyUnicode_Compare(a, b) == 0;  // a legacy string: its text made first
  }
  const Py_ssize_t length = PyUnicode_GET_LENGTH(a);
  const int kind = PyUnicode_KIND(a);
  return length == PyUnicode_GET_LENGTH(b) && kind == PyUnicode_KIND(b) &&
         std::memcmp(PyUnicode_DATA(a), PyUnicode_DATA(b),
                     static_cast<std::size_t>(length) * static_cast<std::size_t>(kind)) == 0;
}

bool readTop(PyObject* object, double& top) {
  PyObject* offset = PyObject_GetAttr(object, names().topOffset);
  if (offset == nullptr) {
    return false;
  }
  const bool ok = itemAsDouble(offset, -1, top);
  Py_DECREF(offset);
  return ok;
}

void readEntry(py::handle value, Eigen::Vector3d& position, double& radius, double& top) {
  py::object parts[3];
  py::object xyz[3];
  if (!unpack(value.ptr(), 3, parts)) {
    throw py::error_already_set();
  }
  double plain[3];
  if (plainNumbers(parts[0].ptr(), 3, plain)) {
    position = Eigen::Vector3d(plain[0], plain[1], plain[2]);
  } else {
    if (!unpack(parts[0].ptr(), 3, xyz)) {
      throw py::error_already_set();
    }
    for (int i = 0; i < 3; ++i) {
      if (!toDouble(xyz[i].ptr(), position[i])) {
        throw py::error_already_set();
      }
    }
  }
  PyObject* radiusObject = PyObject_GetAttr(parts[2].ptr(), names().horizontalRadius);
  py::object radiusGuard = py::reinterpret_steal<py::object>(radiusObject);
  PyObject* topObject =
      radiusObject != nullptr ? PyObject_GetAttr(parts[2].ptr(), names().topOffset) : nullptr;
  py::object topGuard = py::reinterpret_steal<py::object>(topObject);
  if (topObject == nullptr || !toDouble(radiusObject, radius) ||
      !itemAsDouble(topObject, -1, top)) {
    throw py::error_already_set();
  }
}

}  // namespace placement_samplers::python
