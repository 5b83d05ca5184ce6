#include "python/ordered_values.hpp"

#include <cstring>

namespace placement_samplers::python {
namespace {

/// CPython's OrderedDict (Objects/odictobject.c): a dict and a doubly linked list of its keys.
struct Node {
  PyObject* key;
  Py_hash_t hash;
  Node* next;
  Node* prev;
};
struct ODict {
  PyDictObject dict;
  Node* first;
  Node* last;
  Node** fastNodes;
  Py_ssize_t fastNodesSize;
  void* resizeSentinel;
  std::size_t state;  ///< changed whenever the list changes
  PyObject* instanceDict;
  PyObject* weakrefs;
};

bool gWalks = false;

ODict* asODict(PyObject* o) { return reinterpret_cast<ODict*>(o); }

/// True when @p od's list holds exactly the keys of list(@p od), in order.
bool listMatches(PyObject* od) {
  py::list keys = py::reinterpret_steal<py::list>(PySequence_List(od));
  if (!keys) {
    throw py::error_already_set();
  }
  const Node* previous = nullptr;
  const Node* node = asODict(od)->first;
  for (py::handle key : keys) {
    if (node == nullptr || node->key != key.ptr() || node->hash != PyObject_Hash(key.ptr()) ||
        node->prev != previous) {
      return false;
    }
    previous = node;
    node = node->next;
  }
  return node == nullptr && asODict(od)->last == previous;
}

bool layoutMatches() {
  if (PyODict_Type.tp_basicsize != static_cast<Py_ssize_t>(sizeof(ODict)) ||
      PyODict_Type.tp_dictoffset != static_cast<Py_ssize_t>(offsetof(ODict, instanceDict)) ||
      PyODict_Type.tp_weaklistoffset != static_cast<Py_ssize_t>(offsetof(ODict, weakrefs))) {
    return false;
  }
  py::object od = py::module_::import("collections").attr("OrderedDict")();
  if (!Py_IS_TYPE(od.ptr(), &PyODict_Type)) {
    return false;
  }
  for (const char* key : {"a", "b", "c", "d"}) {
    od[key] = py::int_(static_cast<int>(key[0]));
  }
  if (!listMatches(od.ptr())) {
    return false;
  }
  std::size_t state = asODict(od.ptr())->state;
  od.attr("move_to_end")("a");
  if (asODict(od.ptr())->state == state || !listMatches(od.ptr())) {
    return false;
  }
  state = asODict(od.ptr())->state;
  od.attr("pop")("c");
  if (asODict(od.ptr())->state == state || !listMatches(od.ptr())) {
    return false;
  }
  od.attr("tag") = py::int_(1);
  PyObject* instance = asODict(od.ptr())->instanceDict;
  return instance != nullptr && PyDict_CheckExact(instance) && PyDict_GET_SIZE(instance) == 1;
}

}  // namespace

void findOrderedDictLayout() {
  gWalks = false;
  try {
    gWalks = layoutMatches();
  } catch (py::error_already_set&) {
    gWalks = false;  // iterated as any mapping
  }
}

bool orderedDictWalks() { return gWalks; }

OrderedValues::OrderedValues(py::handle mapping) {
  PyObject* m = mapping.ptr();
  static PyObject* values = PyUnicode_InternFromString("values");
  // Exactly an OrderedDict whose values() is the class's (an instance may set its own).
  if (gWalks && Py_IS_TYPE(m, &PyODict_Type) &&
      (asODict(m)->instanceDict == nullptr ||
       PyDict_GetItemWithError(asODict(m)->instanceDict, values) == nullptr)) {
    if (PyErr_Occurred()) {
      throw py::error_already_set();
    }
    // As the iterator: its state, size and first key when made.
    const ODict* od = asODict(m);
    dict_ = py::reinterpret_borrow<py::object>(m);
    state_ = od->state;
    size_ = PyDict_GET_SIZE(m);
    node_ = od->first;
    if (od->first != nullptr) {
      current_ = py::reinterpret_borrow<py::object>(od->first->key);
    }
    return;
  }
  PyObject* view = PyObject_CallMethodNoArgs(m, values);
  PyObject* iterator = view != nullptr ? PyObject_GetIter(view) : nullptr;
  Py_XDECREF(view);
  if (iterator == nullptr) {
    throw py::error_already_set();
  }
  iterator_ = py::reinterpret_steal<py::object>(iterator);
}

py::object OrderedValues::next() {
  if (iterator_) {
    PyObject* item = PyIter_Next(iterator_.ptr());
    if (item == nullptr && PyErr_Occurred()) {
      throw py::error_already_set();
    }
    return py::reinterpret_steal<py::object>(item);
  }
  if (!dict_ || !current_) {
    dict_ = py::object();
    return py::object();
  }
  const ODict* od = asODict(dict_.ptr());
  // The iterator's checks, in its order, with its messages. While they pass, no key was added
  // or removed: node_ is still current_'s node.
  if (od->state != state_) {
    dict_ = py::object();
    PyErr_SetString(PyExc_RuntimeError, "OrderedDict mutated during iteration");
    throw py::error_already_set();
  }
  if (PyDict_GET_SIZE(dict_.ptr()) != size_) {
    size_ = -1;  // as sticky as the iterator's
    PyErr_SetString(PyExc_RuntimeError, "OrderedDict changed size during iteration");
    throw py::error_already_set();
  }
  py::object key = std::move(current_);
  const Node* next = static_cast<const Node*>(node_)->next;
  node_ = const_cast<Node*>(next);
  if (next != nullptr) {
    current_ = py::reinterpret_borrow<py::object>(next->key);
  }
  // The iterator's PyDict_GetItem: an error of the lookup (a key's __eq__) is dropped and the
  // key is missing. Without it, no error needs keeping aside.
  PyObject* value = PyDict_GetItemWithError(dict_.ptr(), key.ptr());  // borrowed
  if (value == nullptr) {
    PyErr_Clear();
    dict_ = py::object();
    PyErr_SetObject(PyExc_KeyError, key.ptr());
    throw py::error_already_set();
  }
  return py::reinterpret_borrow<py::object>(value);
}

}  // namespace placement_samplers::python
