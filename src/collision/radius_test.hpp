#pragma once

// Internal to the core library: robosuite's radius test, written once. Not installed.

namespace placement_samplers {
namespace detail {

/// The values of a candidate that robosuite's radius test reads.
struct RadiusProbe {
  double x;       ///< position x [m]
  double y;       ///< position y [m]
  double z;       ///< position z [m]
  double radius;  ///< horizontal radius [m]
  double bottom;  ///< bottom offset z [m] (negative below the origin)
};

/// The z half of robosuite's radius test: a candidate at height @p z with bottom offset
/// @p bottom reaches below the top of an entry at height @p entryZ with top offset @p entryTop
/// (one-sided, so stacking passes). Also what free_space, the packing bound and the no-room
/// proof read to know which entries can block an object at all.
inline bool radiusHeightsOverlap(double z, double bottom, double entryZ, double entryTop) {
  return z - entryZ <= entryTop - bottom;
}

/// robosuite's radius test, the one definition every path answers with: the x-y circles
/// overlap (touching counts) and the candidate's bottom is below the entry's top, i.e.
/// `z_c - z_e <= top_e - bottom_c` (one-sided, so stacking passes).
///
/// The vector kernels of radius_scan.cpp evaluate the same operations in the same order and
/// are tested against this function (radius_scan_test.cpp); the library is compiled with
/// -ffp-contract=off, so no multiply-add is fused and every path rejects the same candidates.
/// `&` rather than `&&`: both halves are cheap, and one branch less to mispredict.
///
/// @param p the candidate
/// @param x, y, z the entry's position [m]
/// @param radius the entry's horizontal radius [m]
/// @param top the entry's top offset z [m]
inline bool radiusOverlap(const RadiusProbe& p, double x, double y, double z, double radius,
                          double top) {
  const double dx = p.x - x;
  const double dy = p.y - y;
  const double reach = radius + p.radius;
  return (dx * dx + dy * dy <= reach * reach) & radiusHeightsOverlap(p.z, p.bottom, z, top);
}

}  // namespace detail
}  // namespace placement_samplers
