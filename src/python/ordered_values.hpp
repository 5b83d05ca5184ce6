#pragma once

// robosuite's composite walks `zip(self.samplers.values(), self.sample_args.values())`: two
// OrderedDicts. CPython's iterator over an OrderedDict's values looks each key up twice per
// step; OrderedValues walks the OrderedDict's own list of keys instead (CPython's layout,
// checked against the OrderedDict at import), with the iterator's checks and errors:
// the same values, the same RuntimeError when the dict changes during the walk.

#include <pybind11/pybind11.h>

#include <cstddef>

namespace placement_samplers::python {

namespace py = pybind11;

/// Checks CPython's layout of an OrderedDict against OrderedDicts made and changed here; the
/// walk is used only when it matched. Call once at import, with the GIL.
void findOrderedDictLayout();
/// True when OrderedValues walks OrderedDicts itself (the layout matched).
bool orderedDictWalks();

/// The values of a mapping in its order, as `iter(mapping.values())` gives them.
class OrderedValues {
 public:
  /// Starts on @p mapping (an OrderedDict is walked, anything else iterated through its
  /// values()). @throw py::error_already_set
  explicit OrderedValues(py::handle mapping);

  /// The next value, or a null object at the end. @throw py::error_already_set
  py::object next();

 private:
  py::object iterator_;   ///< any other mapping: iter(mapping.values())
  py::object dict_;       ///< the OrderedDict walked; null once at its end
  py::object current_;    ///< the key of the next value; null: the end
  void* node_ = nullptr;  ///< current_'s node in the OrderedDict's list
  std::size_t state_ = 0;
  Py_ssize_t size_ = 0;
};

}  // namespace placement_samplers::python
