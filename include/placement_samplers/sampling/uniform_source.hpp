#pragma once

namespace placement_samplers {

/// Where a uniform sampler's draws come from instead of the scene's engine: a caller's own
/// random generator, e.g. the numpy Generator a Python caller gives robosuite's samplers
/// (SampleContext::setUniformSource). The rejection loop asks it for every draw, in robosuite's
/// order: per attempt x, then y; after the accepted attempt the rotation (when drawn). An
/// implementation may throw (numpy's Generator refuses a reversed range); the sampling then
/// stops with that exception, the draws before it made.
///
/// Only rectangular rejection sampling draws through a source (no region shape, keep-out zone,
/// surface region or other strategy).
class UniformSource {
 public:
  /// What a draw is for.
  enum class Draw { X, Y, Rotation };

  virtual ~UniformSource() = default;

  /// numpy's uniform(low, high): `low + (high - low) * u`, u in [0, 1), for @p what.
  virtual double uniform(double low, double high, Draw what) = 0;

  /// The rotation angle of the accepted attempt [rad], drawn or fixed: once per placed
  /// object, after its last draw and before the placement is recorded.
  virtual void rotation(double angle) = 0;
};

}  // namespace placement_samplers
