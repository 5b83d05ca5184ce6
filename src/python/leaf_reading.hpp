#pragma once

// What one run of robosuite's UniformRandomSampler.sample() reads of the Python sampler and its
// objects, and where robosuite would raise if something cannot be read: an exception robosuite
// raises part-way (a name already placed, an attribute missing, a range that is not a pair)
// is raised at the same point of the draws, so that the caller's generator stands where
// robosuite leaves it.

#include <pybind11/pybind11.h>

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/sampling/uniform_source.hpp"
#include "python/attribute_snapshot.hpp"

namespace placement_samplers::python {

namespace py = pybind11;

class PyUniformSampler;

/// The point of an object's placement at which robosuite would raise, in its order.
enum class Stage {
  BeforeX,         ///< before the first x draw (name check, attributes, x_range)
  BeforeY,         ///< after the first x draw (the reference's x, y_range)
  AfterY,          ///< after the first y draw (the reference's y and z, z_offset, offsets)
  BeforeRotation,  ///< before the rotation draw (a rotation min() or max() cannot take)
  AfterRotation    ///< after it (rotation_axis, init_quat)
};

/// The first exception robosuite would raise, and where.
struct PendingError {
  std::size_t object = 0;
  Stage stage = Stage::BeforeX;
  std::optional<py::error_already_set> error;

  /// Keeps the Python error being raised now (fetched) when it comes before the one kept.
  void note(std::size_t object, Stage stage);
  bool at(std::size_t object, Stage stage) const {
    return error && this->object == object && this->stage == stage;
  }
};

/// One object as robosuite reads it.
struct ObjectReading {
  py::object object;
  py::object name;  ///< its key in the placements
  double radius = 0.0;
  double bottom = 0.0;  ///< bottom_offset[-1] [m]
  /// top_offset[-1] [m] when topKnown: read only where a test of this call reads it
  /// (SampleCall), NaN until then.
  double top = 0.0;
  bool topKnown = false;
  bool hasInitQuat = false;
  std::array<double, 4> initQuat{};  ///< init_quat as given: (x, y, z, w) in quat_multiply
  /// Its attributes as read, for reading its top later (cleared when they were not plain).
  AttributeSnapshot snapshot;
};

/// The sampler's numbers as robosuite reads them in one sample() call.
struct LeafReading {
  std::vector<ObjectReading> objects;  ///< up to the one with the pending error
  UniformSamplerParams params;         ///< unchecked inputs, rotation and ranges as read
  Eigen::Vector3d base = Eigen::Vector3d::Zero();  ///< what the ranges are around [m]
  int axis = 2;                                    ///< rotation_axis as 0, 1, 2
  /// A fixed rotation numpy must turn into a quaternion itself (not a float or small int).
  py::object fixedRotationObject;
  PendingError pending;
};

/// Reads @p sampler for a call with @p reference (None, a name in @p placed, or a point) and
/// @p onTop. Raises at once what robosuite raises before its first object (an unknown
/// reference); keeps in `pending` what it raises later.
/// @throw py::error_already_set
void readLeaf(PyUniformSampler& sampler, py::handle placed, py::handle reference, bool onTop,
              LeafReading& out);

/// robosuite's base_offset for a @p reference that is not None (a name in @p placed, or a
/// point), into @p out (reference_reading.cpp). @throw py::error_already_set where robosuite
/// raises at once; what it raises later is kept in out.pending
void readReference(py::handle placed, py::handle reference, bool onTop, LeafReading& out);

/// The numbers the core sampler is built from (objects and parameters), for CoreCache, into
/// @p key.
void cacheKey(const LeafReading& reading, std::vector<double>& key);

}  // namespace placement_samplers::python
