#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "placement_samplers/sampling/placement.hpp"

namespace placement_samplers {

/// The .npz file could not be created or written (cannot open, disk full, ...): the message
/// names the file and the system's reason.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// How a NpzWriter lays out its file.
struct NpzOptions {
  /// Zip64 headers even when the file stays below 4 GB (they are used anyway above it); for
  /// tests, which cannot afford 4 GB files.
  bool forceZip64 = false;
  /// With check or settle: also `stable` [K] bool, `moved` and `turned` [K, n] float64 [m],
  /// [rad] and `fallen` [K, n] bool (NaN, NaN, false where a scene was not simulated); with
  /// settle also `sampled_position` [K, n, 3] and `sampled_orientation` [K, n, 4].
  PhysicsMode physics = PhysicsMode::None;
  /// Also `rest_pose` [K, n] int16: each placement's resting pose under resting: stable (-1:
  /// as configured, or not placed).
  bool restPoses = false;
};

/// Writes scenes into numpy's .npz format (a stored zip of .npy arrays, what numpy.load reads),
/// streaming: memory does not grow with the number of scenes. With K scenes of n objects:
/// `names` [n] (unicode), `position` [K, n, 3] float64 [m], `orientation` [K, n, 4] float64
/// (x, y, z, w), `attempts` [K, n] uint32, `success` [K] bool, `scene` [K] uint64 (the scene
/// index), `seed` uint64 (a scalar). An object a scene did not place (it failed first) is NaN
/// in position and orientation, 0 in attempts.
///
/// Every member's size is known from K and n, so the zip is laid out up front: scenes go to
/// fixed offsets, each member keeps a running CRC-32, and finish() writes the CRCs and the
/// central directory. The file's bytes depend only on the scenes (fixed time stamps).
class NpzWriter {
 public:
  /// Creates (or truncates) @p path and writes everything but the scenes.
  /// @param names the objects of every scene, in their column order
  /// @param numScenes K, the number of scenes write() will be given in all
  /// @param seed the request seed, stored as `seed`
  /// @throw OutputError when the file cannot be created or written
  NpzWriter(const std::string& path, const std::vector<std::string>& names, std::uint64_t numScenes,
            std::uint64_t seed, const NpzOptions& options = {});
  /// Closes the file; removes it when finish() did not complete (a partial file is no .npz),
  /// unless it is no regular file (a device such as /dev/full, a FIFO).
  ~NpzWriter();
  NpzWriter(const NpzWriter&) = delete;
  NpzWriter& operator=(const NpzWriter&) = delete;

  /// Appends the next scenes (rows written so far .. + scenes.size() - 1), in order.
  /// @throw OutputError on a write error, or when more than numScenes scenes are given
  /// @throw std::invalid_argument when a scene places an object not in names
  void write(const std::vector<SceneResult>& scenes);

  /// Writes the CRCs and the central directory and closes the file.
  /// @throw OutputError on a write error, or when fewer than numScenes scenes were written
  void finish();

  /// The file's size once finished [bytes].
  std::uint64_t fileSize() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace placement_samplers
