#include "python/sample_call.hpp"

#include <string_view>

#include "python/py_samplers.hpp"
#include "python/py_values.hpp"

namespace placement_samplers::python {
namespace {

/// The name of every entry made from the placements dict (only messages would show it).
constexpr std::string_view kEntryName = "placed object";

}  // namespace

SampleCall::SampleCall() : context_(unused_, checker_) {}

void SampleCall::start(py::handle fixtures) {
  if (fixtures.is_none()) {
    placed_ = py::dict();
  } else if (PyDict_CheckExact(fixtures.ptr())) {
    placed_ = py::reinterpret_steal<py::object>(PyDict_Copy(fixtures.ptr()));
    if (!placed_) {
      throw py::error_already_set();
    }
  } else {
    placed_ = py::module_::import("copy").attr("copy")(fixtures);
  }
  context_.clear();
  loaded_ = false;
  kept_.clear();
}

void SampleCall::end() {
  placed_ = py::object();
  kept_.clear();
}

void SampleCall::resync() { loaded_ = false; }

void SampleCall::loadEntries() {
  if (loaded_) {
    return;
  }
  context_.clear();
  loaded_ = true;
  std::size_t used = 0;
  auto add = [&](py::handle value) {
    Eigen::Vector3d position;
    double radius = 0.0;
    double top = 0.0;
    readEntry(value, position, radius, top);
    if (used == models_.size()) {
      models_.emplace_back();
    }
    ObjectModel& model = models_[used++];
    model.horizontalRadius = radius;
    model.topOffset = Eigen::Vector3d(0.0, 0.0, top);
    context_.addFixture(kEntryName, &model, position, Eigen::Quaterniond::Identity());
  };
  if (PyDict_Check(placed_.ptr())) {
    // Any order: the overlap test asks whether some entry overlaps.
    Py_ssize_t at = 0;
    PyObject* key = nullptr;
    PyObject* value = nullptr;
    while (PyDict_Next(placed_.ptr(), &at, &key, &value)) {
      add(value);
    }
    return;
  }
  for (py::handle value : placed_.attr("values")()) {
    add(value);
  }
}

CallSlot::CallSlot() : call(std::make_unique<SampleCall>()) {}
CallSlot::~CallSlot() = default;

}  // namespace placement_samplers::python
