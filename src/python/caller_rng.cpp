#include "python/caller_rng.hpp"

#include <cmath>

#include "placement_samplers/sampling/random.hpp"

namespace placement_samplers::python {
namespace {

/// True when @p rng's class takes uniform() from numpy's Generator (a subclass that overrides
/// it is called as any other rng).
bool generatorsUniform(py::handle rng) {
  PyObject* type = generatorType();
  if (type == nullptr || PyObject_IsInstance(rng.ptr(), type) != 1) {
    PyErr_Clear();
    return false;
  }
  static PyObject* name = PyUnicode_InternFromString("uniform");
  return _PyType_Lookup(Py_TYPE(rng.ptr()), name) ==
         _PyType_Lookup(reinterpret_cast<PyTypeObject*>(type), name);
}

[[noreturn]] void raise(PyObject* type, const char* message) {
  PyErr_SetString(type, message);
  throw py::error_already_set();
}

}  // namespace

CallerRng::CallerRng(py::handle rng) : rng_(py::reinterpret_borrow<py::object>(rng)) {
  if (!generatorsUniform(rng)) {
    return;
  }
  try {
    bitGenerator_ = rng_.attr("bit_generator");
    bitgen_ = bitGenOf(bitGenerator_.ptr());
    if (bitgen_ == nullptr) {
      throw py::error_already_set();
    }
    py::object lock = bitGenerator_.attr("lock");
    acquire_ = lock.attr("__enter__");  // acquire(): tries, then waits without the GIL
    release_ = lock.attr("release");
    locked_ = lock.attr("locked");
    if (PyCFunction_Check(locked_.ptr()) && PyCFunction_GET_FLAGS(locked_.ptr()) == METH_NOARGS) {
      lockedFunction_ = PyCFunction_GET_FUNCTION(locked_.ptr());
      lockedSelf_ = PyCFunction_GET_SELF(locked_.ptr());  // held by locked_
    }
    const int pcg = PyObject_IsInstance(bitGenerator_.ptr(), pcg64Type());
    if (pcg < 0) {
      throw py::error_already_set();
    }
    kind_ = pcg == 1 ? Kind::Pcg64 : Kind::BitGenerator;
  } catch (const py::error_already_set&) {
    // Not a Generator as numpy makes them: drawn through its own uniform().
    kind_ = Kind::Python;
  }
}

RngDraws::RngDraws(CallerRng& rng) : rng_(rng) {
  if (rng_.kind_ == CallerRng::Kind::Python) {
    return;
  }
  if (rng_.kind_ == CallerRng::Kind::Pcg64) {
    // numpy's PCG64 draws in C: while this thread holds the GIL and runs no Python code, a
    // free lock stays free. Another thread's draw in progress (GIL released) holds it.
    PyObject* held = rng_.lockedFunction_ != nullptr
                         ? rng_.lockedFunction_(rng_.lockedSelf_, nullptr)
                         : PyObject_CallNoArgs(rng_.locked_.ptr());
    if (held == nullptr) {
      throw py::error_already_set();
    }
    Py_DECREF(held);
    if (held != Py_False) {
      lock();
    }
  } else {
    lock();  // another bit generator may call back into Python
  }
  if (rng_.kind_ == CallerRng::Kind::Pcg64) {
    std::array<std::uint64_t, 4> words{};
    if (!readPcg64State(rng_.bitGenerator_.ptr(), rng_.bitgen_, words)) {
      releaseKeepingError();
      throw py::error_already_set();
    }
    engine_ = Pcg64::fromState(words[0], words[1], words[2], words[3]);
  }
}

RngDraws::~RngDraws() {
  if (!engine_ && !locked_) {
    return;
  }
  // Unwinding: the state still goes back, whatever else fails now.
  PyObject* type = nullptr;
  PyObject* value = nullptr;
  PyObject* traceback = nullptr;
  PyErr_Fetch(&type, &value, &traceback);
  if (engine_) {
    writePcg64State(rng_.bitGenerator_.ptr(), rng_.bitgen_, engine_->stateWords());
  }
  if (locked_) {
    PyObject* done = PyObject_CallNoArgs(rng_.release_.ptr());
    Py_XDECREF(done);
  }
  PyErr_Restore(type, value, traceback);
}

void RngDraws::releaseKeepingError() {
  if (!locked_) {
    return;
  }
  locked_ = false;
  PyObject* type = nullptr;
  PyObject* value = nullptr;
  PyObject* traceback = nullptr;
  PyErr_Fetch(&type, &value, &traceback);
  PyObject* done = PyObject_CallNoArgs(rng_.release_.ptr());
  Py_XDECREF(done);
  PyErr_Restore(type, value, traceback);
}

void RngDraws::lock() {
  // As numpy's own draws do; waiting for it lets other threads run (the GIL is released).
  PyObject* got = PyObject_CallNoArgs(rng_.acquire_.ptr());
  if (got == nullptr) {
    throw py::error_already_set();
  }
  Py_DECREF(got);
  locked_ = true;
}

double RngDraws::uniformChecked(double low, double high) {
  if (rng_.kind_ == CallerRng::Kind::Python) {
    py::object value = rng_.rng_.attr("uniform")(py::arg("high") = high, py::arg("low") = low);
    const double v = PyFloat_AsDouble(value.ptr());
    if (v == -1.0 && PyErr_Occurred()) {
      throw py::error_already_set();
    }
    return v;
  }
  // numpy's Generator.uniform for scalars: the width checked, then low + width * next_double.
  const double range = high - low;
  if (!std::isfinite(range)) {
    raise(PyExc_OverflowError, "high - low range exceeds valid bounds");
  }
  if (range < 0) {
    raise(PyExc_ValueError, "high - low < 0");
  }
  if (engine_) {
    return low + range * uniform01(*engine_);
  }
  return low + range * rng_.bitgen_->nextDouble(rng_.bitgen_->state);
}

void RngDraws::finish() {
  if (engine_) {
    const std::array<std::uint64_t, 4> words = engine_->stateWords();
    engine_.reset();
    if (!writePcg64State(rng_.bitGenerator_.ptr(), rng_.bitgen_, words)) {
      releaseKeepingError();
      throw py::error_already_set();
    }
  }
  if (locked_) {
    locked_ = false;
    rng_.release_();
  }
}

}  // namespace placement_samplers::python
