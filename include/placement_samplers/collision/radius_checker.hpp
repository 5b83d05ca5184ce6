#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "placement_samplers/collision/collision_checker.hpp"

namespace placement_samplers {

namespace detail {
class RadiusColumns;
struct RadiusProbe;
}  // namespace detail

/// robosuite's test: the x-y circles overlap (touching counts) and the candidate's bottom is
/// below the other's top: `z - z_o <= top_o - bottom`. One-sided in z, so stacking passes.
///
/// Answers exactly as robosuite's scan of every entry in order: the same candidates collide
/// and the lowest colliding index comes back. Up to scanLimit entries it scans a packed copy
/// of what the test reads, 8 (AVX-512) or 4 (AVX2) entries at once where the CPU has them,
/// with the same operations as the scalar test; beyond, it looks only near the candidate,
/// through uniform grids (how they work: radius_checker.cpp). The answers do not depend on
/// the CPU or on the path taken.
///
/// Entries must be announced with added() in index order after clear(), as SampleContext does;
/// with another entry vector the checker scans that vector. Buffers grow to the largest scene
/// seen and are kept: no allocation per attempt, none per scene once warm.
class RadiusChecker : public CollisionChecker {
 public:
  /// Scenes up to this many entries are scanned: below about 100 entries the scan measured
  /// faster than the grids (docs/benchmarks.md).
  static constexpr std::size_t kDefaultScanLimit = 96;

  /// @param scanLimit scenes with at most this many entries are scanned, larger ones use the
  /// grids (0 = always the grids, as tests do)
  explicit RadiusChecker(std::size_t scanLimit = kDefaultScanLimit);
  ~RadiusChecker() override;

  void clear() override;
  void added(const std::vector<PlacedEntry>& entries, std::size_t index) override;
  std::ptrdiff_t firstCollision(const std::vector<PlacedEntry>& entries,
                                const Candidate& candidate) override;
  bool needsOrientation() const override { return false; }
  bool includesRadiusTest() const override { return true; }

 private:
  struct Item;
  struct Grid;

  /// Puts entry @p index into its grid, or into the always-scanned list.
  void indexEntry(std::size_t index);
  /// Entry @p index as the grids store it.
  Item itemOf(std::size_t index) const;

  std::size_t scanLimit_;
  std::unique_ptr<detail::RadiusColumns> columns_;  ///< scanned copy of the items
  std::size_t (*firstOverlap_)(const detail::RadiusColumns&, const detail::RadiusProbe&);
  bool gridMode_ = false;                ///< more than scanLimit_ entries: the grids are in use
  std::vector<Item> items_;              ///< one per entry, by entry index, in grid mode only
  std::vector<std::int32_t> unbounded_;  ///< entries no cell can hold, ascending
  std::vector<std::unique_ptr<Grid>> grids_;  ///< every grid ever used, kept for their buffers
  std::vector<Grid*> active_;                 ///< grids holding entries of the current scene
  Grid* lastGrid_ = nullptr;                  ///< the grid of the latest entry
};

/// True when robosuite's test says @p candidate overlaps @p other.
bool radiusOverlap(const PlacedEntry& other, const Candidate& candidate);

}  // namespace placement_samplers
