#pragma once

#include <pybind11/pybind11.h>

#include <deque>
#include <memory>
#include <vector>

#include "placement_samplers/collision/radius_checker.hpp"
#include "placement_samplers/sampling/sample_context.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "python/leaf_reading.hpp"

namespace placement_samplers::python {

namespace py = pybind11;

/// One sample() call from Python: the placements dict it fills (robosuite's placed_objects)
/// and the core's view of it, a SampleContext whose entries are that dict's values. Kept by
/// the sampler between calls, so that a call allocates nothing once warm.
///
/// What robosuite's overlap test reads of the entries is read only when a sampler that tests
/// comes: the fixtures' pos, horizontal_radius and top_offset, and the top_offset of objects
/// placed here (robosuite reads an object's top only to test a later object against it; an
/// object's property may cost more than the sampling).
class SampleCall {
 public:
  SampleCall();

  /// Starts a call on a copy of @p fixtures (robosuite's copy(fixtures); a new dict for None).
  void start(py::handle fixtures);
  /// Forgets the call's Python objects (the result has been handed over).
  void end();

  /// Before a sampler that tests for overlaps runs with @p reading: the context holds every
  /// entry of placed() with what the test reads (read now where not yet). A value that
  /// cannot be read is raised where that sampler's first test is (reading.pending).
  void prepareTests(LeafReading& reading);
  /// After a sampler of the library placed @p reading's objects (the context's placements
  /// from @p before on): they are entries, their tops known or to be read.
  void recordPlacements(const LeafReading& reading, std::size_t before);
  /// After a sampler outside the library changed placed(): every entry is read again.
  void resync();

  py::object& placed() { return placed_; }
  SampleContext& context() { return context_; }
  /// The reading of the sampler being run (reused between runs).
  LeafReading& reading() { return reading_; }
  /// The rotation angle of each object of the current run, in order.
  std::vector<double>& angles() { return angles_; }
  /// Keeps @p sampler alive until end(): the context points into its objects.
  void keep(std::shared_ptr<UniformRandomSampler> sampler) { kept_.push_back(std::move(sampler)); }

 private:
  /// An entry placed by the library's samplers in this call.
  struct Placed {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    double radius = 0.0;
    double top = 0.0;            ///< top_offset[-1] once read
    py::object owner;            ///< the object whose top_offset is still to be read, else null
    AttributeSnapshot snapshot;  ///< owner's attributes as read
  };

  /// Makes the context's entries the fixtures (the dict's first fixtures_ values) and placed_.
  void rebuild();

  py::object placed_;
  Py_ssize_t lastSize_ = 0;  ///< how many entries the last call's dict had
  Engine unused_;            // the samplers draw from the caller's rng (UniformSource)
  RadiusChecker checker_;
  SampleContext context_;
  std::size_t fixtures_ = 0;  ///< placed()'s first values that are not in placedHere_
  bool fixturesRead_ = false;
  bool stale_ = false;  ///< the context lacks entries or tops: rebuild() before a test
  std::vector<Placed> fixtureEntries_;
  std::vector<Placed> placedHere_;
  std::deque<ObjectModel> models_;  ///< the rebuilt entries' objects (stable addresses)
  LeafReading reading_;
  std::vector<double> angles_;
  std::vector<std::shared_ptr<UniformRandomSampler>> kept_;
};

}  // namespace placement_samplers::python
