#include "python/numpy_support.hpp"

#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#define PY_ARRAY_UNIQUE_SYMBOL placement_samplers_python_ARRAY_API
#include <numpy/arrayobject.h>
#include <numpy/random/bitgen.h>

#include <array>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

static_assert(sizeof(bitgen_t) == sizeof(placement_samplers::python::BitGen),
              "BitGen mirrors numpy's bitgen_t");

namespace placement_samplers::python {
namespace {
PyObject* gNumpy = nullptr;
PyObject* gCos = nullptr;
PyObject* gSin = nullptr;
PyObject* gGeneratorType = nullptr;
PyObject* gPcg64Type = nullptr;
bool gLoopsChecked = false;

/// numpy's ufunc_call_info (numpy >= 1.24, ufunc._get_strided_loop): the strided loop numpy
/// itself calls for given dtypes, with its context and data. numpy documents the loop's
/// signature as stable and the rest as tied to its version: every loop found is checked
/// against numpy's results (checkLoops()) before it is used.
struct UfuncCallInfo {
  int (*stridedLoop)(void* context, char* const* data, const npy_intp* dimensions,
                     const npy_intp* strides, void* auxdata);
  void* context;
  void* auxdata;
  npy_bool requiresPyapi;
  npy_bool noFloatingpointErrors;
};

/// A float64 -> float64 loop of a one-input ufunc, and the capsule that keeps it alive.
struct DoubleLoop {
  PyObject* capsule = nullptr;
  UfuncCallInfo* info = nullptr;
};

DoubleLoop gCosLoop;
DoubleLoop gSinLoop;

/// numpy's own loop of @p ufunc for float64 inputs with 8-byte strides, or none.
DoubleLoop findDoubleLoop(PyObject* ufunc) {
  DoubleLoop loop;
  PyObject* dtype = PyObject_CallMethod(gNumpy, "dtype", "s", "float64");
  PyObject* dtypes = dtype != nullptr ? PyTuple_Pack(2, dtype, dtype) : nullptr;
  PyObject* resolved =
      dtypes != nullptr ? PyObject_CallMethod(ufunc, "_resolve_dtypes_and_context", "(O)", dtypes)
                        : nullptr;
  Py_XDECREF(dtype);
  Py_XDECREF(dtypes);
  if (resolved == nullptr || !PyTuple_Check(resolved) || PyTuple_GET_SIZE(resolved) != 2) {
    Py_XDECREF(resolved);
    PyErr_Clear();
    return loop;
  }
  PyObject* capsule = PyTuple_GET_ITEM(resolved, 1);
  Py_INCREF(capsule);
  Py_DECREF(resolved);
  PyObject* method = PyObject_GetAttrString(ufunc, "_get_strided_loop");
  PyObject* args = PyTuple_Pack(1, capsule);
  PyObject* kwargs = Py_BuildValue("{s:(ii)}", "fixed_strides", 8, 8);
  PyObject* done = method != nullptr && args != nullptr && kwargs != nullptr
                       ? PyObject_Call(method, args, kwargs)
                       : nullptr;
  Py_XDECREF(method);
  Py_XDECREF(args);
  Py_XDECREF(kwargs);
  const char* name = PyCapsule_CheckExact(capsule) ? PyCapsule_GetName(capsule) : nullptr;
  const std::string text = name != nullptr ? name : "";
  const std::string suffix = "_ufunc_call_info";
  if (done == nullptr || text.rfind("numpy_", 0) != 0 || text.size() < suffix.size() ||
      text.compare(text.size() - suffix.size(), suffix.size(), suffix) != 0) {
    Py_XDECREF(done);
    Py_DECREF(capsule);
    PyErr_Clear();
    return loop;
  }
  Py_DECREF(done);
  auto* info = static_cast<UfuncCallInfo*>(PyCapsule_GetPointer(capsule, name));
  if (info == nullptr || info->stridedLoop == nullptr || info->requiresPyapi) {
    Py_DECREF(capsule);
    PyErr_Clear();
    return loop;
  }
  loop.capsule = capsule;  // kept for the life of the process
  loop.info = info;
  return loop;
}

bool callLoop(const DoubleLoop& loop, double x, double& out) {
  // Input and output a cache line apart: numpy takes its vector path only when they do not
  // overlap, and counts neighbours as overlapping (its scalar path gives other results).
  struct {
    double in;
    char gap[64];
    double out;
  } buffers{x, {}, 0.0};
  char* args[2] = {reinterpret_cast<char*>(&buffers.in), reinterpret_cast<char*>(&buffers.out)};
  const npy_intp count = 1;
  const npy_intp steps[2] = {sizeof(double), sizeof(double)};
  const bool ok =
      loop.info->stridedLoop(loop.info->context, args, &count, steps, loop.info->auxdata) == 0;
  out = buffers.out;
  return ok;
}

/// np.cos(x) or np.sin(x) called from Python.
bool callNumpy(PyObject* ufunc, double x, double& out) {
  PyObject* arg = PyFloat_FromDouble(x);
  if (arg == nullptr) {
    return false;
  }
  PyObject* result = PyObject_CallOneArg(ufunc, arg);
  Py_DECREF(arg);
  if (result == nullptr) {
    return false;
  }
  out = PyFloat_AsDouble(result);
  Py_DECREF(result);
  return !(out == -1.0 && PyErr_Occurred());
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

/// The loops against np.cos and np.sin on scalars, over angles robosuite's halves take and
/// beyond (a fixed sequence, so that import does the same work each time).
bool checkLoops() {
  std::uint64_t lcg = 0x9E3779B97F4A7C15ULL;
  for (int k = 0; k < 4000; ++k) {
    lcg = lcg * 6364136223846793005ULL + 1442695040888963407ULL;
    const double u = static_cast<double>(lcg >> 11) * 0x1.0p-53;
    const double scale = k % 4 == 0 ? 4.0 : (k % 4 == 1 ? 40.0 : (k % 4 == 2 ? 1e4 : 0.5));
    double x = (2.0 * u - 1.0) * scale * M_PI;
    if (k < 8) {
      const double specials[8] = {0.0, -0.0, M_PI, M_PI / 2, 1e-300, 5e-324, 1e300, -M_PI};
      x = specials[k];
    }
    double c = 0.0;
    double s = 0.0;
    if (!callNumpy(gCos, x, c) || !callNumpy(gSin, x, s)) {
      PyErr_Clear();
      return false;
    }
    double loopCos = 0.0;
    double loopSin = 0.0;
    if (!callLoop(gCosLoop, x, loopCos) || !callLoop(gSinLoop, x, loopSin) ||
        !sameBits(loopCos, c) || !sameBits(loopSin, s)) {
      PyErr_Clear();
      return false;
    }
  }
  return true;
}

}  // namespace

bool initNumpy() {
  if (_import_array() < 0) {
    return false;
  }
  gNumpy = PyImport_ImportModule("numpy");
  PyObject* random = PyImport_ImportModule("numpy.random");
  if (gNumpy == nullptr || random == nullptr) {
    Py_XDECREF(random);
    return false;
  }
  gCos = PyObject_GetAttrString(gNumpy, "cos");
  gSin = PyObject_GetAttrString(gNumpy, "sin");
  gGeneratorType = PyObject_GetAttrString(random, "Generator");
  gPcg64Type = PyObject_GetAttrString(random, "PCG64");
  Py_DECREF(random);
  if (gCos == nullptr || gSin == nullptr || gGeneratorType == nullptr || gPcg64Type == nullptr) {
    return false;
  }
  gCosLoop = findDoubleLoop(gCos);
  gSinLoop = findDoubleLoop(gSin);
  gLoopsChecked = gCosLoop.info != nullptr && gSinLoop.info != nullptr && checkLoops();
  findPcg64Layout();
  return true;
}

bool numpyCosSin(double x, double& cosine, double& sine, bool fixed) {
  // The last fixed angle's values and the last angle's: fixed rotations ask for the same one
  // again and again, also when drawn rotations come between.
  struct Known {
    bool valid = false;
    double x = 0.0;
    double cosine = 0.0;
    double sine = 0.0;
  };
  static Known lastFixed;
  static Known last;
  for (const Known* k : {&lastFixed, &last}) {
    if (k->valid && sameBits(x, k->x)) {
      cosine = k->cosine;
      sine = k->sine;
      return true;
    }
  }
  if (gLoopsChecked && callLoop(gCosLoop, x, cosine) && callLoop(gSinLoop, x, sine)) {
    last = Known{true, x, cosine, sine};
    if (fixed) {
      lastFixed = last;
    }
    return true;
  }
  PyErr_Clear();
  return callNumpy(gCos, x, cosine) && callNumpy(gSin, x, sine);
}

bool cosSinLoopsInUse() { return gLoopsChecked; }

bool float64ArrayItem(PyObject* value, Py_ssize_t index, double& out) {
  if (!PyArray_CheckExact(value)) {
    return false;
  }
  auto* array = reinterpret_cast<PyArrayObject*>(value);
  if (PyArray_NDIM(array) != 1 || PyArray_TYPE(array) != NPY_DOUBLE ||
      !PyArray_ISNOTSWAPPED(array)) {
    return false;
  }
  const npy_intp size = PyArray_DIM(array, 0);
  const npy_intp i = index < 0 ? index + size : index;
  if (i < 0 || i >= size) {
    return false;
  }
  std::memcpy(&out, PyArray_BYTES(array) + i * PyArray_STRIDE(array, 0), sizeof(double));
  return true;
}

bool float64ArrayItems(PyObject* value, std::size_t count, double* out) {
  if (!PyArray_CheckExact(value)) {
    return false;
  }
  auto* array = reinterpret_cast<PyArrayObject*>(value);
  if (PyArray_NDIM(array) != 1 || PyArray_TYPE(array) != NPY_DOUBLE ||
      !PyArray_ISNOTSWAPPED(array) || PyArray_DIM(array, 0) < static_cast<npy_intp>(count)) {
    return false;
  }
  const char* data = PyArray_BYTES(array);
  const npy_intp stride = PyArray_STRIDE(array, 0);
  for (std::size_t i = 0; i < count; ++i) {
    std::memcpy(&out[i], data + static_cast<npy_intp>(i) * stride, sizeof(double));
  }
  return true;
}

namespace {

/// numpy keeps no free list of small arrays: making an array and freeing it again is most of
/// the cost of a quaternion in robosuite's result. The module keeps the quaternion arrays it
/// made last; one that nothing else holds any more (the pool's is its only reference) and that
/// is still exactly as made (a 1-d array of its dtype and size, no base, no weak reference,
/// its flags) is filled anew instead of being freed and made again: nothing can tell it from a
/// new array.
class ArrayPool {
 public:
  ArrayPool(int type, std::size_t itemSize) : type_(type), itemSize_(itemSize) {}

  PyObject* take(const void* values, std::size_t count) {
    PyObject*& slot = slots_[next_];
    next_ = (next_ + 1) % slots_.size();
    const std::size_t bytes = count * itemSize_;
    if (slot != nullptr && Py_REFCNT(slot) == 1 && unchanged(slot, count)) {
      std::memcpy(PyArray_DATA(reinterpret_cast<PyArrayObject*>(slot)), values, bytes);
      Py_INCREF(slot);
      return slot;
    }
    npy_intp dims[1] = {static_cast<npy_intp>(count)};
    PyObject* array = PyArray_SimpleNew(1, dims, type_);
    if (array == nullptr) {
      return nullptr;
    }
    auto* a = reinterpret_cast<PyArrayObject*>(array);
    std::memcpy(PyArray_DATA(a), values, bytes);
    if (descr_ == nullptr) {
      descr_ = PyArray_DESCR(a);  // numpy's own, kept for the life of the process
      Py_INCREF(descr_);
      flags_ = PyArray_FLAGS(a);
    }
    Py_XSETREF(slot, array);
    Py_INCREF(array);
    return array;
  }

 private:
  bool unchanged(PyObject* slot, std::size_t count) const {
    auto* a = reinterpret_cast<PyArrayObject*>(slot);
    return Py_IS_TYPE(slot, &PyArray_Type) && PyArray_NDIM(a) == 1 &&
           PyArray_DIM(a, 0) == static_cast<npy_intp>(count) && PyArray_DESCR(a) == descr_ &&
           PyArray_STRIDE(a, 0) == descr_->elsize && PyArray_FLAGS(a) == flags_ &&
           PyArray_BASE(a) == nullptr &&
           reinterpret_cast<PyArrayObject_fields*>(a)->weakreflist == nullptr;
  }

  int type_;
  std::size_t itemSize_;
  PyArray_Descr* descr_ = nullptr;
  int flags_ = 0;
  std::array<PyObject*, 64> slots_{};
  std::size_t next_ = 0;
};

}  // namespace

PyObject* newFloat64Array(const double* values, std::size_t count) {
  static ArrayPool* pool =
      new ArrayPool(NPY_DOUBLE, sizeof(double));  // kept for the life of the process
  return pool->take(values, count);
}

PyObject* newFloat32Array(const float* values, std::size_t count) {
  static ArrayPool* pool = new ArrayPool(NPY_FLOAT, sizeof(float));
  return pool->take(values, count);
}

PyObject* newArray(const char* dtype, const std::vector<std::int64_t>& shape, void** data) {
  int type = NPY_DOUBLE;
  if (std::strcmp(dtype, "int16") == 0) {
    type = NPY_INT16;
  } else if (std::strcmp(dtype, "uint32") == 0) {
    type = NPY_UINT32;
  } else if (std::strcmp(dtype, "uint64") == 0) {
    type = NPY_UINT64;
  } else if (std::strcmp(dtype, "bool") == 0) {
    type = NPY_BOOL;
  } else if (std::strcmp(dtype, "float64") != 0) {
    throw std::invalid_argument(std::string("newArray: no numpy type for ") + dtype);
  }
  std::vector<npy_intp> dims(shape.begin(), shape.end());
  PyObject* array = PyArray_ZEROS(static_cast<int>(dims.size()), dims.data(), type, 0);
  if (array != nullptr) {
    *data = PyArray_DATA(reinterpret_cast<PyArrayObject*>(array));
  }
  return array;
}

PyObject* generatorType() { return gGeneratorType; }
PyObject* pcg64Type() { return gPcg64Type; }

}  // namespace placement_samplers::python
