#pragma once

// The `rng` a robosuite sampler draws from, as robosuite's rng.uniform(low, high) would use
// it: numpy Generators on PCG64 through the library's own Pcg64 (the state read from the bit
// generator and written back), on other bit generators through numpy's next_double, anything
// else by calling its uniform() from C++.

#include <pybind11/pybind11.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>

#include "placement_samplers/sampling/pcg64.hpp"
#include "placement_samplers/sampling/random.hpp"
#include "python/numpy_support.hpp"

namespace placement_samplers::python {

namespace py = pybind11;

/// What the module knows of one rng object; kept by a sampler while its `rng` stays the same.
class CallerRng {
 public:
  enum class Kind {
    Pcg64,         ///< numpy.random.Generator on PCG64: the library's Pcg64 on its state
    BitGenerator,  ///< a Generator on another bit generator: numpy's next_double
    Python         ///< anything else: its uniform(high=, low=) called
  };

  CallerRng() = default;
  /// Looks at @p rng (a Generator whose class does not override uniform, or anything else).
  explicit CallerRng(py::handle rng);

  bool is(py::handle rng) const { return rng.ptr() == rng_.ptr(); }
  Kind kind() const { return kind_; }

 private:
  friend class RngDraws;
  py::object rng_;
  Kind kind_ = Kind::Python;
  py::object bitGenerator_;
  BitGen* bitgen_ = nullptr;
  py::object acquire_;  ///< the bit generator's lock, held while drawing (as numpy does)
  py::object release_;
  py::object locked_;
  /// locked_'s C function and its lock, called directly (a builtin method without arguments).
  PyCFunction lockedFunction_ = nullptr;
  PyObject* lockedSelf_ = nullptr;
};

/// Draws from a CallerRng for one sampler run: numpy's Generator.uniform(low, high) bit for
/// bit, with its checks (OverflowError "high - low range exceeds valid bounds" for a width that
/// is not finite, ValueError "high - low < 0" for a reversed range), or the rng's own
/// uniform(). For a Generator the bit generator is kept to itself from construction to
/// finish(), so no Python code may run in between: its lock is held, or, for a PCG64 whose
/// lock is free, the GIL is (no other thread can take the lock while this one holds the GIL
/// and runs no Python code). A PCG64's state is read at construction and written back by
/// finish() (or, when an exception unwinds, by the destructor).
class RngDraws {
 public:
  explicit RngDraws(CallerRng& rng);
  ~RngDraws();
  RngDraws(const RngDraws&) = delete;
  RngDraws& operator=(const RngDraws&) = delete;

  /// One draw. @throw py::error_already_set with numpy's or the rng's exception
  double uniform(double low, double high) {
    const double range = high - low;
    if (engine_ && std::isfinite(range) && range >= 0) {
      return low + range * uniform01(*engine_);  // a PCG64's draw, inline: most of them
    }
    return uniformChecked(low, high);
  }

  /// Writes a PCG64's state back and releases the lock. @throw py::error_already_set
  void finish();

 private:
  /// uniform() with numpy's checks and the other kinds of rng.
  double uniformChecked(double low, double high);
  void lock();
  /// Releases the lock if held, the Python error being raised kept as it is.
  void releaseKeepingError();
  CallerRng& rng_;
  std::optional<Pcg64> engine_;
  bool locked_ = false;
};

}  // namespace placement_samplers::python
