#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "placement_samplers/object_model.hpp"

namespace placement_samplers {

/// Something already in the scene: a fixture or an object placed earlier in the scene.
struct PlacedEntry {
  std::string name;
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
/// Answers exactly as a scan of every entry in order would (the same entries collide, and the
/// lowest colliding index is returned), but looks only near the candidate: entries are kept in
/// uniform grids, one per power-of-two cell size, each entry in the grid whose cells are at
/// least four times its horizontal radius. A query visits, per grid in use, the cells within
/// reach of the candidate; a grid with few entries, or a candidate so large that it would cover
/// more cells than the grid has entries (a table-sized object), is scanned instead. Entries
/// with a non-finite position or radius are always scanned. The grids wrap around (cell (i, j)
/// uses bucket (i mod 32, j mod 32)), so objects far outside the work area, at negative
/// coordinates or hidden 20 m away, need no bounds; the exact test sorts out what shares a
/// bucket.
///
/// Entries must be announced with added() in index order, after clear(), as SampleContext does;
/// with any other entry vector the checker falls back to the full scan. Buffers grow to the
/// largest scene seen and are kept: no allocation per attempt, none per scene once warm.
class RadiusChecker : public CollisionChecker {
 public:
  RadiusChecker();
  ~RadiusChecker() override;

  void clear() override;
  void added(const std::vector<PlacedEntry>& entries, std::size_t index) override;
  std::ptrdiff_t firstCollision(const std::vector<PlacedEntry>& entries,
                                const Candidate& candidate) const override;
  bool needsOrientation() const override { return false; }

 private:
  /// What the test reads of an entry, packed: position [m], horizontal radius [m], top offset
  /// z [m], and the next entry in the same bucket (-1 = none).
  struct Item {
    double x;
    double y;
    double z;
    double radius;
    double top;
    std::int32_t next;
  };
  struct Grid;

  /// Lowest colliding index among @p indices below @p best (ascending list), or @p best.
  std::int32_t scanList(const std::vector<std::int32_t>& indices, const Candidate& candidate,
                        std::int32_t best) const;
  std::int32_t queryGrid(const Grid& grid, const Candidate& candidate, std::int32_t best) const;
  void insert(Grid& grid, std::int32_t index);

  std::vector<Item> items_;              ///< one per entry, by entry index
  std::vector<std::int32_t> unbounded_;  ///< entries with a non-finite position or radius
  std::vector<std::unique_ptr<Grid>> grids_;  ///< every grid ever used; kept for their buffers
  std::vector<Grid*> active_;            ///< grids holding entries of the current scene
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
