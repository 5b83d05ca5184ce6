#include "python/attribute_snapshot.hpp"

#include "python/py_values.hpp"

namespace placement_samplers::python {

namespace {

#if PLACEMENT_SAMPLERS_SNAPSHOTS
/// What getattr(object, @p name) returns without running Python code, found in @p dict or
/// @p type. @return false when it would run code or cannot be told; @p value null: missing
bool plainAttribute(PyTypeObject* type, PyObject* dict, PyObject* name, PyObject*& value) {
  PyObject* inType = _PyType_Lookup(type, name);
  if (inType != nullptr && Py_TYPE(inType)->tp_descr_get != nullptr) {
    return false;  // a property, a method, a slot: getattr calls it
  }
  value = PyDict_GetItemWithError(dict, name);
  if (value == nullptr) {
    if (PyErr_Occurred()) {
      PyErr_Clear();
      return false;
    }
    value = inType;  // a plain class attribute, or missing
  }
  return true;
}
#endif

}  // namespace

bool AttributeSnapshot::take(PyObject* o) {
  clear();
#if PLACEMENT_SAMPLERS_SNAPSHOTS
  PyTypeObject* t = Py_TYPE(o);
  if (t->tp_getattro != PyObject_GenericGetAttr) {
    return false;  // __getattr__ or __getattribute__
  }
  // Finds the dict (CPython makes it from the object's inline values the first time: from
  // then on every change of an attribute is a change of the dict).
  PyObject** dictPointer = _PyObject_GetDictPtr(o);
  if (dictPointer == nullptr || *dictPointer == nullptr || !PyDict_Check(*dictPointer)) {
    PyErr_Clear();
    return false;
  }
  PyObject* d = *dictPointer;
  const Names& n = names();
  if (!plainAttribute(t, d, n.name, name) || name == nullptr ||
      !plainAttribute(t, d, n.horizontalRadius, radius) || radius == nullptr ||
      !plainAttribute(t, d, n.bottomOffset, bottom) || bottom == nullptr ||
      !plainAttribute(t, d, n.topOffset, top) || !plainAttribute(t, d, n.initQuat, initQuat)) {
    return false;
  }
  // _PyType_Lookup gave the class a version number unless they ran out.
  if (!PyType_HasFeature(t, Py_TPFLAGS_VALID_VERSION_TAG)) {
    return false;
  }
  type = t;
  typeVersion = t->tp_version_tag;
  dict = d;
  dictSlot = dictPointer;  // the object keeps its dict there from now on
  dictVersion = reinterpret_cast<PyDictObject*>(d)->ma_version_tag;
  object = o;
  return true;
#else
  (void)o;
  return false;
#endif
}

bool readTop(PyObject* object, const AttributeSnapshot& snapshot, double& top) {
  if (snapshot.top != nullptr && snapshot.current(object)) {
    return itemAsDouble(snapshot.top, -1, top);
  }
  return readTop(object, top);
}

}  // namespace placement_samplers::python
