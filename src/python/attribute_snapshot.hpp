#pragma once

// robosuite reads an object's attributes (name, horizontal_radius, bottom_offset, top_offset,
// init_quat) at every sample() call. For an object whose attributes are plain values of its
// instance dict or class, what Python's getattr would return cannot change while neither the
// instance dict nor the class changes: CPython numbers each dict's contents (ma_version_tag)
// and each class's (tp_version_tag) anew at every change. A snapshot keeps what getattr
// returned with those numbers; a later read takes the values from it only when the numbers
// are still the same, else reads the attributes as Python does. The values themselves
// (an array that may be changed in place, a number) are read again at every use.

#include <Python.h>

#include <cstdint>

namespace placement_samplers::python {

// The dict and class version numbers are CPython's up to 3.11 (3.12 deprecates the dict's).
#if PY_VERSION_HEX < 0x030C0000
#define PLACEMENT_SAMPLERS_SNAPSHOTS 1
#else
#define PLACEMENT_SAMPLERS_SNAPSHOTS 0
#endif

/// What getattr gives for an object's five attributes, valid while current() holds. Every
/// pointer is borrowed: current() compares them with the live object's before any is used,
/// and while it holds, the object's dict and class still hold the values.
struct AttributeSnapshot {
  PyObject* object = nullptr;
  PyTypeObject* type = nullptr;
  unsigned int typeVersion = 0;
  PyObject* dict = nullptr;
  PyObject** dictSlot = nullptr;  ///< where the object keeps its dict
  std::uint64_t dictVersion = 0;
  PyObject* name = nullptr;
  PyObject* radius = nullptr;
  PyObject* bottom = nullptr;
  PyObject* top = nullptr;       ///< null: none (read as Python does, which raises)
  PyObject* initQuat = nullptr;  ///< null: the object has no init_quat

  /// True when @p object is the snapshot's and neither its dict nor its class has changed
  /// since. Runs no Python code.
  bool current(PyObject* o) const {
#if PLACEMENT_SAMPLERS_SNAPSHOTS
    // The object first: the dict slot is in it. Its dict after: a dict at the address of a
    // freed one has another version.
    return o == object && Py_TYPE(o) == type &&
           PyType_HasFeature(type, Py_TPFLAGS_VALID_VERSION_TAG) &&
           type->tp_version_tag == typeVersion && *dictSlot == dict &&
           reinterpret_cast<PyDictObject*>(dict)->ma_version_tag == dictVersion;
#else
    (void)o;
    return false;
#endif
  }
  /// Takes a snapshot of @p object's attributes; false (and no Python error) when they are
  /// not all plain values that getattr reads without running Python code (a property, a
  /// __getattr__, slots, a missing name, radius or bottom offset, a Python older or newer
  /// than the snapshot knows): the caller reads them as Python does.
  bool take(PyObject* object);
  /// Forgets it.
  void clear() { object = nullptr; }
};

/// @p object.top_offset[-1], from @p snapshot while it is current, else read as Python does.
/// @return false with a Python error set
bool readTop(PyObject* object, const AttributeSnapshot& snapshot, double& top);

}  // namespace placement_samplers::python
