#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "placement_samplers/object_model.hpp"

namespace placement_samplers {

namespace detail {
class RadiusColumns;
struct RadiusProbe;
}  // namespace detail

/// Something already in the scene: a fixture or an object placed earlier in the scene.
struct PlacedEntry {
  /// The object's or fixture's name, owned by the configuration or the request: a view, so
  /// that placing an object copies no string.
  std::string_view name;
  const ObjectModel* object = nullptr;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  bool fixture = false;
};

/// A pose under test for @p object.
struct Candidate {
  const ObjectModel* object = nullptr;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

/// Decides whether a candidate collides with what is placed. One implementation per test; the
/// samplers only see this interface. Implementations may keep acceleration structures, so a
/// checker belongs to one scene at a time (one per thread).
class CollisionChecker {
 public:
  static constexpr std::ptrdiff_t kNone = -1;

  virtual ~CollisionChecker() = default;

  /// Forget every entry (start of a scene).
  virtual void clear() = 0;
  /// Entry @p index of @p entries was just added.
  virtual void added(const std::vector<PlacedEntry>& entries, std::size_t index) = 0;
  /// @return the index of an entry that @p candidate collides with, or kNone
  virtual std::ptrdiff_t firstCollision(const std::vector<PlacedEntry>& entries,
                                        const Candidate& candidate) const = 0;
  /// True when the candidate's orientation matters (then it is drawn before the test).
  virtual bool needsOrientation() const = 0;
};

/// robosuite's test: the x-y circles overlap (touching counts) and the candidate's bottom is
/// below the other's top: `z - z_o <= top_o - bottom`. One-sided in z, so stacking passes.
///
/// Answers exactly as robosuite's scan of every entry in order: the same candidates collide
/// and the lowest colliding index comes back, from a packed copy of what the test reads. Up
/// to scanLimit entries it scans that copy (on the machines of docs/benchmarks.md the scan is
/// the faster one below about a hundred entries). Beyond, it looks only near the candidate:
/// entries go into uniform grids, one per power-of-two cell size, each into the grid whose
/// cells are 4 to 8 times its horizontal radius, listed in every cell within half a cell of
/// it, so that a candidate of the entries' size finds all it can touch in its own cell. A
/// larger candidate visits every cell within reach, or scans the grid when that would be more
/// cells than entries (a table-sized object); a grid of a few entries (a table, some plates)
/// is scanned; entries with a non-finite position or a radius of 1e150 m or more are always
/// scanned. The grids wrap around (cell (i, j) uses bucket (i mod 32, j mod 32)), so objects
/// at negative coordinates, far outside the work area or hidden 20 m away need no bounds:
/// the exact test sorts out what shares a bucket.
///
/// The scan compares blocks of 8 (AVX-512) or 4 (AVX2) entries at once where the CPU has
/// them, with the same operations as the scalar test, so the answers do not depend on the CPU.
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
                                const Candidate& candidate) const override;
  bool needsOrientation() const override { return false; }

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

/// Collision modes of the configuration and of requests.
enum class CollisionMode { Radius, Fcl, RadiusAndFcl };

/// "radius", "fcl" or "radius_and_fcl".
const char* collisionModeName(CollisionMode mode);

/// A checker for @p mode with clearance @p margin [m] in the exact modes.
/// @throw ConfigError when the mode is not available in this build
std::unique_ptr<CollisionChecker> makeCollisionChecker(CollisionMode mode, double margin);

}  // namespace placement_samplers
