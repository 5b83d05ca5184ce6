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
class SampleCall {
 public:
  SampleCall();

  /// Starts a call on a copy of @p fixtures (robosuite's copy(fixtures); a new dict for None).
  void start(py::handle fixtures);
  /// Forgets the call's Python objects (the result has been handed over).
  void end();

  /// Makes every value of placed() an entry of the context ((pos, quat, obj): pos and the
  /// object's horizontal_radius and top_offset[-1]), once per call until resync().
  void loadEntries();
  /// After a sampler outside the library changed placed(): the context is read again.
  void resync();

  py::object& placed() { return placed_; }
  SampleContext& context() { return context_; }
  /// The reading of the sampler being run (reused between runs).
  LeafReading& reading() { return reading_; }
  /// Room for a CoreCache key.
  std::vector<double>& key() { return key_; }
  /// The rotation angle of each object of the current run, in order.
  std::vector<double>& angles() { return angles_; }
  /// Keeps @p sampler alive until end(): the context points into its objects.
  void keep(std::shared_ptr<UniformRandomSampler> sampler) { kept_.push_back(std::move(sampler)); }

 private:
  py::object placed_;
  Engine unused_;  // the samplers draw from the caller's rng (UniformSource)
  RadiusChecker checker_;
  SampleContext context_;
  bool loaded_ = false;
  std::deque<ObjectModel> models_;  ///< the loaded entries' objects (stable addresses)
  LeafReading reading_;
  std::vector<double> angles_;
  std::vector<double> key_;
  std::vector<std::shared_ptr<UniformRandomSampler>> kept_;
};

}  // namespace placement_samplers::python
