// robosuite's base_offset for a call's reference (a name among the placements, or a point),
// read as robosuite's UniformRandomSampler.sample() reads it.

#include "python/leaf_reading.hpp"
#include "python/py_values.hpp"

namespace placement_samplers::python {
namespace {

/// True when the list or tuple @p value holds floats only.
bool allFloats(PyObject* value) {
  for (Py_ssize_t i = 0; i < PySequence_Fast_GET_SIZE(value); ++i) {
    if (!PyFloat_Check(PySequence_Fast_GET_ITEM(value, i))) {
      return false;
    }
  }
  return true;
}

/// base_offset[0], [1], [2] of a numpy array or sequence, raised where robosuite reads them.
void readBase(PyObject* base, LeafReading& out) {
  const Stage stages[3] = {Stage::BeforeY, Stage::AfterY, Stage::AfterY};
  for (Py_ssize_t i = 0; i < 3; ++i) {
    if (!itemAsDouble(base, i, out.base[i])) {
      out.pending.note(0, stages[i]);
    }
  }
}

}  // namespace

void readReference(py::handle placed, py::handle reference, bool onTop, LeafReading& out) {
  if (Py_IS_TYPE(reference.ptr(), &PyUnicode_Type)) {
    const int known = PySequence_Contains(placed.ptr(), reference.ptr());
    if (known < 0) {
      throw py::error_already_set();
    }
    if (known == 0) {
      setAssertion(py::str("Invalid reference received. Current options are: {}, requested: {}")
                       .format(placed.attr("keys")(), reference));
      throw py::error_already_set();
    }
    py::object parts[3];
    if (!unpack(py::object(placed[reference]).ptr(), 3, parts)) {
      throw py::error_already_set();
    }
    double xyz[3];
    // Floats only: np.array of integers refuses the float top added in place (numpy says so).
    if (plainNumbers(parts[0].ptr(), 3, xyz) && (!onTop || allFloats(parts[0].ptr()))) {
      out.base = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
      if (onTop) {
        double top = 0.0;
        if (!itemAsDouble(parts[2].attr("top_offset").ptr(), -1, top)) {
          throw py::error_already_set();
        }
        // np.array(ref_pos) + (0, 0, top), component by component.
        out.base = Eigen::Vector3d(xyz[0] + 0.0, xyz[1] + 0.0, xyz[2] + top);
      }
      return;
    }
    py::module_ numpy = py::module_::import("numpy");
    py::object base = numpy.attr("array")(parts[0]);
    if (onTop) {
      py::object addend =
          numpy.attr("array")(py::make_tuple(0, 0, parts[2].attr("top_offset")[py::int_(-1)]));
      PyObject* sum = PyNumber_InPlaceAdd(base.ptr(), addend.ptr());
      if (sum == nullptr) {
        throw py::error_already_set();
      }
      base = py::reinterpret_steal<py::object>(sum);
    }
    readBase(base.ptr(), out);
    return;
  }
  double xyz[3];
  if (plainNumbers(reference.ptr(), 3, xyz)) {
    out.base = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
    return;
  }
  py::object base = py::module_::import("numpy").attr("array")(reference);
  py::tuple shape = base.attr("shape");
  if (shape.empty()) {
    PyErr_SetString(PyExc_IndexError, "tuple index out of range");
    throw py::error_already_set();
  }
  if (!py::object(shape[0]).equal(py::int_(3))) {
    setAssertion(
        py::str("Invalid reference received. Should be (x,y,z) 3-tuple, but got: {}").format(base));
    throw py::error_already_set();
  }
  readBase(base.ptr(), out);
}

}  // namespace placement_samplers::python
