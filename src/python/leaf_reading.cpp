#include "python/leaf_reading.hpp"

#include <limits>
#include <string>

#include "python/attribute_snapshot.hpp"
#include "python/numpy_support.hpp"
#include "python/py_samplers.hpp"
#include "python/py_values.hpp"

namespace placement_samplers::python {
namespace {

bool truth(const py::object& value) {
  if (value.ptr() == Py_True || value.ptr() == Py_False) {
    return value.ptr() == Py_True;
  }
  const int v = PyObject_IsTrue(value.ptr());
  if (v < 0) {
    throw py::error_already_set();
  }
  return v == 1;
}

/// Whether @p name equals one of the names of the objects before @p k, as a set of them tells:
/// str names compared as they are, any other in @p seen (made when first needed; the caller
/// adds each name that passes). @return 1, 0, or -1 with a Python error set
int amongEarlier(const LeafReading& out, std::size_t k, PyObject* name, py::object& seen) {
  if (!seen && PyUnicode_CheckExact(name)) {
    std::size_t j = 0;
    for (; j < k && PyUnicode_CheckExact(out.objects[j].name.ptr()); ++j) {
      PyObject* other = out.objects[j].name.ptr();
      if (other == name || sameText(other, name)) {
        return 1;
      }
    }
    if (j == k) {
      return 0;
    }
  }
  if (!seen) {
    seen = py::reinterpret_steal<py::object>(PySet_New(nullptr));
    for (std::size_t j = 0; seen && j < k; ++j) {
      if (PySet_Add(seen.ptr(), out.objects[j].name.ptr()) < 0) {
        return -1;
      }
    }
    if (!seen) {
      return -1;
    }
  }
  return PySet_Contains(seen.ptr(), name);
}

/// Object @p k as robosuite reads it; its exception kept with where it is raised. Its
/// attributes come from @p snapshot while it is current (taken anew when it is not).
void readObject(std::size_t k, py::handle object, py::handle placed, py::object& seen,
                AttributeSnapshot& snapshot, LeafReading& out) {
  UniformSamplerParams& p = out.params;
  out.objects.emplace_back();
  ObjectReading& o = out.objects.back();
  o.object = py::reinterpret_borrow<py::object>(object);
  const bool snapped = snapshot.current(object.ptr()) || snapshot.take(object.ptr());
  o.snapshot = snapshot;
  PyObject* name = nullptr;
  if (snapped) {
    name = snapshot.name;
    Py_INCREF(name);
  } else {
    name = PyObject_GetAttr(object.ptr(), names().name);
    if (name == nullptr) {
      return out.pending.note(k, Stage::BeforeX);
    }
  }
  o.name = py::reinterpret_steal<py::object>(name);
  int known = 0;
  if (PyDict_Check(placed.ptr())) {
    // A str's hash is kept in it: looked up with it, as PyDict_Contains would.
    const Py_hash_t hash =
        PyUnicode_CheckExact(name) ? reinterpret_cast<PyASCIIObject*>(name)->hash : -1;
    known = hash != -1 ? _PyDict_Contains_KnownHash(placed.ptr(), name, hash)
                       : PyDict_Contains(placed.ptr(), name);
  } else {
    known = PySequence_Contains(placed.ptr(), name);
  }
  if (known == 0 && k > 0) {
    // The objects before it in this sampler are placed by now: their names count too.
    known = amongEarlier(out, k, name, seen);
  }
  if (known != 0) {
    if (known == 1) {
      setAssertion(py::str("Object '{}' has already been sampled!").format(o.name));
    }
    return out.pending.note(k, Stage::BeforeX);
  }
  if (seen && PySet_Add(seen.ptr(), name) < 0) {
    throw py::error_already_set();
  }
  // A name's __eq__ may have run Python code: the snapshot holds only while current.
  const bool plain = snapped && snapshot.current(object.ptr());
  py::object radiusGuard;
  py::object bottomGuard;
  PyObject* radius = nullptr;
  PyObject* bottom = nullptr;
  if (plain) {
    radius = snapshot.radius;
    bottom = snapshot.bottom;
  } else {
    o.snapshot.clear();
    radius = PyObject_GetAttr(object.ptr(), names().horizontalRadius);
    radiusGuard = py::reinterpret_steal<py::object>(radius);
    bottom = radius != nullptr ? PyObject_GetAttr(object.ptr(), names().bottomOffset) : nullptr;
    bottomGuard = py::reinterpret_steal<py::object>(bottom);
    if (bottom == nullptr) {
      return out.pending.note(k, Stage::BeforeX);
    }
  }
  if (!toDouble(radius, o.radius)) {
    // Used by the boundary shrink (before the x draw) and by the overlap test.
    if (p.ensureObjectBoundaryInRange) {
      return out.pending.note(k, Stage::BeforeX);
    }
    if (p.ensureValidPlacement) {
      return out.pending.note(k, Stage::AfterY);
    }
    PyErr_Clear();
    o.radius = 0.0;
  }
  o.top = std::numeric_limits<double>::quiet_NaN();
  if (!itemAsDouble(bottom, -1, o.bottom)) {
    return out.pending.note(k, Stage::AfterY);
  }
  PyObject* initQuat = nullptr;
  py::object initQuatGuard;
  // The numbers read so far may have run Python code (a __float__, a __getitem__).
  if (plain && snapshot.current(object.ptr())) {
    initQuat = snapshot.initQuat;
  } else {
    o.snapshot.clear();
    if (_PyObject_LookupAttr(object.ptr(), names().initQuat, &initQuat) < 0) {
      return out.pending.note(k, Stage::AfterRotation);
    }
    initQuatGuard = py::reinterpret_steal<py::object>(initQuat);
  }
  if (initQuat != nullptr) {
    py::object parts[4];
    o.hasInitQuat = true;
    if (!unpack(initQuat, 4, parts)) {
      return out.pending.note(k, Stage::AfterRotation);
    }
    for (int i = 0; i < 4; ++i) {
      if (!toDouble(parts[i].ptr(), o.initQuat[i])) {
        return out.pending.note(k, Stage::AfterRotation);
      }
    }
  }
}

/// The sampler's own attributes, read with its first object (robosuite reads them there).
void readParams(PyUniformSampler& s, bool defaultReference, LeafReading& out) {
  UniformSamplerParams& p = out.params;
  py::object pair[2];
  if (!floatPair(s.xRange.ptr(), p.xRange) &&
      (!unpack(s.xRange.ptr(), 2, pair) || !toDouble(pair[0].ptr(), p.xRange[0]) ||
       !toDouble(pair[1].ptr(), p.xRange[1]))) {
    out.pending.note(0, Stage::BeforeX);
  }
  // A float64 array of three or more, read at once (reading it runs no Python code).
  const bool referenceRead =
      defaultReference && float64ArrayItems(s.referencePos.ptr(), 3, out.base.data());
  if (defaultReference && !referenceRead && !itemAsDouble(s.referencePos.ptr(), 0, out.base[0])) {
    out.pending.note(0, Stage::BeforeY);
  }
  if (!floatPair(s.yRange.ptr(), p.yRange) &&
      (!unpack(s.yRange.ptr(), 2, pair) || !toDouble(pair[0].ptr(), p.yRange[0]) ||
       !toDouble(pair[1].ptr(), p.yRange[1]))) {
    out.pending.note(0, Stage::BeforeY);
  }
  for (Py_ssize_t i = 1; i < 3 && defaultReference && !referenceRead; ++i) {
    if (!itemAsDouble(s.referencePos.ptr(), i, out.base[i])) {
      out.pending.note(0, Stage::AfterY);
    }
  }
  if (!toDouble(s.zOffset.ptr(), p.zOffset)) {
    out.pending.note(0, Stage::AfterY);
  }
  static PyObject* iterable =
      py::object(py::module_::import("collections.abc").attr("Iterable")).release().ptr();
  PyObject* rotation = s.rotation.ptr();
  // isinstance(rotation, Iterable), without asking the ABC for the usual types.
  int isIterable = 0;
  if (PyTuple_CheckExact(rotation) || PyList_CheckExact(rotation)) {
    isIterable = 1;
  } else if (rotation != Py_None && !PyFloat_CheckExact(rotation) && !PyLong_CheckExact(rotation)) {
    isIterable = PyObject_IsInstance(rotation, iterable);
  }
  if (isIterable < 0) {
    throw py::error_already_set();
  }
  if (rotation == Py_None) {
    p.rotation = RotationSpec::full();
  } else if (isIterable == 1) {
    // rng.uniform(high=max(rotation), low=min(rotation)): max first.
    p.rotation.kind = RotationSpec::Kind::Range;
    static PyObject* maxFunction =
        py::object(py::module_::import("builtins").attr("max")).release().ptr();
    static PyObject* minFunction =
        py::object(py::module_::import("builtins").attr("min")).release().ptr();
    PyObject* high = PyObject_CallOneArg(maxFunction, rotation);
    py::object highGuard = py::reinterpret_steal<py::object>(high);
    PyObject* low = high != nullptr ? PyObject_CallOneArg(minFunction, rotation) : nullptr;
    py::object lowGuard = py::reinterpret_steal<py::object>(low);
    if (low == nullptr || !toDouble(high, p.rotation.high) || !toDouble(low, p.rotation.low)) {
      out.pending.note(0, Stage::BeforeRotation);
    }
  } else {
    p.rotation.kind = RotationSpec::Kind::Fixed;
    double angle = 0.0;
    if (plainNumber(rotation, angle)) {
      p.rotation.low = p.rotation.high = angle;
    } else {
      out.fixedRotationObject = s.rotation;  // numpy computes its quaternion
    }
  }
  out.axis = -1;
  for (int a = 0; a < 3; ++a) {
    if (s.rotationAxis.ptr() == names().axes[a]) {  // the interned literals "x", "y", "z"
      out.axis = a;
    }
  }
  for (int a = 0; a < 3 && out.axis < 0; ++a) {
    const int same = PyObject_RichCompareBool(s.rotationAxis.ptr(), names().axes[a], Py_EQ);
    if (same < 0) {
      out.pending.note(0, Stage::AfterRotation);
      break;
    }
    out.axis = same == 1 ? a : -1;
  }
  if (out.axis < 0 && !PyErr_Occurred()) {
    PyErr_SetObject(PyExc_ValueError,
                    py::str("Invalid rotation axis specified. Must be 'x', 'y', or 'z'. Got: {}")
                        .format(s.rotationAxis)
                        .ptr());
    out.pending.note(0, Stage::AfterRotation);
  }
  p.rotationAxis = out.axis < 0 ? 2 : out.axis;
}

}  // namespace

void PendingError::note(std::size_t k, Stage s) {
  py::error_already_set fetched;
  if (error && (object < k || (object == k && stage <= s))) {
    return;
  }
  object = k;
  stage = s;
  error = std::move(fetched);
}

void readLeaf(PyUniformSampler& s, py::handle placed, py::handle reference, bool onTop,
              LeafReading& out) {
  out.objects.clear();
  out.pending = PendingError();
  out.fixedRotationObject = py::object();
  out.base = Eigen::Vector3d::Zero();
  out.axis = 2;
  UniformSamplerParams& p = out.params;
  // What readParams() and readObject() read; every other parameter keeps its default (the
  // reading is made once and reused: making the whole set anew costs more than a small run).
  p.xRange = Eigen::Vector2d::Zero();
  p.yRange = Eigen::Vector2d::Zero();
  p.rotation = RotationSpec();
  p.rotationAxis = 2;
  p.zOffset = 0.0;
  p.checkInputs = false;
  p.maxAttempts = 5000;  // robosuite's range(5000)
  const bool defaultReference = reference.is_none();
  if (!defaultReference) {
    readReference(placed, reference, onTop, out);
  }
  p.ensureObjectBoundaryInRange = truth(s.ensureObjectBoundaryInRange);
  p.ensureValidPlacement = truth(s.ensureValidPlacement);
  py::object seen;
  py::object objects = s.mujocoObjects;  // held: reading may replace the attribute
  auto read = [&](std::size_t k, PyObject* object) {
    if (k == s.snapshots.size()) {
      s.snapshots.emplace_back();
    }
    readObject(k, object, placed, seen, s.snapshots[k], out);
    if (k == 0) {
      readParams(s, defaultReference, out);
    }
    return !out.pending.error;  // robosuite raises before it reaches the next object
  };
  if (PyList_CheckExact(objects.ptr())) {
    for (Py_ssize_t k = 0; k < PyList_GET_SIZE(objects.ptr()); ++k) {
      py::object object = py::reinterpret_borrow<py::object>(PyList_GET_ITEM(objects.ptr(), k));
      if (!read(static_cast<std::size_t>(k), object.ptr())) {
        break;
      }
    }
  } else {
    std::size_t k = 0;
    for (py::handle object : objects) {
      if (!read(k++, object.ptr())) {
        break;
      }
    }
  }
  if (out.objects.empty()) {
    out.pending = PendingError();  // robosuite reads nothing without objects
  }
  if (p.ensureValidPlacement) {
    // Each object but the last is tested against by the ones after it: their tops now.
    for (std::size_t j = 0; j + 1 < out.objects.size(); ++j) {
      ObjectReading& o = out.objects[j];
      if (!readTop(o.object.ptr(), o.snapshot, o.top)) {
        out.pending.note(j + 1, Stage::AfterY);
        break;
      }
      o.topKnown = true;
    }
  }
}

void cacheKey(const LeafReading& r, std::vector<double>& key) {
  const UniformSamplerParams& p = r.params;
  const std::size_t n = r.objects.size();
  key.resize(12 + 3 * n);
  double* k = key.data();
  k[0] = p.xRange[0];
  k[1] = p.xRange[1];
  k[2] = p.yRange[0];
  k[3] = p.yRange[1];
  k[4] = static_cast<double>(p.rotation.kind);
  k[5] = p.rotation.low;
  k[6] = p.rotation.high;
  k[7] = static_cast<double>(p.rotationAxis);
  k[8] = p.ensureObjectBoundaryInRange ? 1.0 : 0.0;
  k[9] = p.ensureValidPlacement ? 1.0 : 0.0;
  k[10] = p.zOffset;
  k[11] = static_cast<double>(n);
  for (std::size_t i = 0; i < n; ++i) {
    const ObjectReading& o = r.objects[i];
    k[12 + 3 * i] = o.radius;
    k[13 + 3 * i] = o.bottom;
    k[14 + 3 * i] = o.top;
  }
}

}  // namespace placement_samplers::python
