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
    // Room for as many as the last call placed: the dict does not grow entry by entry.
    placed_ = py::reinterpret_steal<py::object>(_PyDict_NewPresized(lastSize_));
    if (!placed_) {
      throw py::error_already_set();
    }
  } else if (PyDict_CheckExact(fixtures.ptr())) {
    placed_ = py::reinterpret_steal<py::object>(PyDict_Copy(fixtures.ptr()));
    if (!placed_) {
      throw py::error_already_set();
    }
  } else {
    placed_ = py::module_::import("copy").attr("copy")(fixtures);
  }
  context_.clear();
  placedHere_.clear();
  kept_.clear();
  resync();
  stale_ = false;  // the context is empty, and so is what it mirrors but the fixtures
}

void SampleCall::end() {
  if (placed_ && PyDict_Check(placed_.ptr())) {
    lastSize_ = PyDict_GET_SIZE(placed_.ptr());
  }
  placed_ = py::object();
  for (Placed& p : placedHere_) {
    p.owner = py::object();
  }
  fixtureEntries_.clear();
  kept_.clear();
}

void SampleCall::resync() {
  const Py_ssize_t size = PyObject_Size(placed_.ptr());
  if (size < 0) {
    throw py::error_already_set();
  }
  fixtures_ = static_cast<std::size_t>(size);
  fixturesRead_ = fixtures_ == 0;
  fixtureEntries_.clear();
  placedHere_.clear();
  stale_ = true;
}

void SampleCall::prepareTests(LeafReading& reading) {
  if (fixturesRead_ && !stale_) {
    return;
  }
  for (Placed& p : placedHere_) {
    if (p.owner && !readTop(p.owner.ptr(), p.snapshot, p.top)) {
      return reading.pending.note(0, Stage::AfterY);  // where the first test reads it
    }
    p.owner = py::object();
  }
  if (!fixturesRead_) {
    // The values there before this call's own placements: the first fixtures_ of the dict.
    auto add = [&](py::handle value) {
      Placed entry{Eigen::Vector3d::Zero(), 0.0, 0.0, py::object(), AttributeSnapshot()};
      readEntry(value, entry.position, entry.radius, entry.top);
      fixtureEntries_.push_back(entry);
    };
    try {
      if (PyDict_Check(placed_.ptr())) {
        Py_ssize_t at = 0;
        PyObject* key = nullptr;
        PyObject* value = nullptr;
        while (fixtureEntries_.size() < fixtures_ &&
               PyDict_Next(placed_.ptr(), &at, &key, &value)) {
          add(value);
        }
      } else {
        for (py::handle value : placed_.attr("values")()) {
          if (fixtureEntries_.size() == fixtures_) {
            break;
          }
          add(value);
        }
      }
    } catch (py::error_already_set& e) {
      e.restore();
      return reading.pending.note(0, Stage::AfterY);
    }
    fixturesRead_ = true;
  }
  rebuild();
}

void SampleCall::rebuild() {
  context_.clear();
  std::size_t used = 0;
  auto add = [&](const Placed& entry) {
    if (used == models_.size()) {
      models_.emplace_back();
    }
    ObjectModel& model = models_[used++];
    model.horizontalRadius = entry.radius;
    model.topOffset = Eigen::Vector3d(0.0, 0.0, entry.top);
    context_.addFixture(kEntryName, &model, entry.position, Eigen::Quaterniond::Identity());
  };
  for (const Placed& entry : fixtureEntries_) {
    add(entry);
  }
  for (const Placed& entry : placedHere_) {
    add(entry);
  }
  stale_ = false;
}

void SampleCall::recordPlacements(const LeafReading& reading, std::size_t before) {
  const std::vector<ObjectPlacement>& placements = context_.placements();
  for (std::size_t i = 0; i < reading.objects.size(); ++i) {
    const ObjectReading& o = reading.objects[i];
    Placed& placed = placedHere_.emplace_back();
    placed.position = placements[before + i].position;
    placed.radius = o.radius;
    placed.top = o.top;
    if (!o.topKnown) {
      placed.owner = o.object;
      placed.snapshot = o.snapshot;
    }
    // Its entry in the context has no top yet.
    stale_ = stale_ || !o.topKnown;
  }
}

CallSlot::CallSlot() : call(std::make_unique<SampleCall>()) {}
CallSlot::~CallSlot() = default;

}  // namespace placement_samplers::python
