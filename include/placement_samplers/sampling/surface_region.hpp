#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "placement_samplers/geometry/object_model.hpp"
#include "placement_samplers/geometry/support_surfaces.hpp"
#include "placement_samplers/sampling/random.hpp"

namespace placement_samplers {

/// A uniform sampler's `region: {shape: surface, of: NAME, ...}`: it draws on the support
/// surfaces of a fixture or of an object placed earlier in the scene (README, "Support surfaces").
struct SurfaceRegion {
  std::string of;  ///< the fixture or earlier object whose surfaces hold the sampler's objects
  enum class Select { All, Top, Indices };
  Select select = Select::All;       ///< Top: the surfaces at the highest z (within 1 mm)
  std::vector<std::size_t> indices;  ///< Select::Indices: as --describe lists them
  double minArea = 0.0025;           ///< smaller surfaces are ignored [m^2]
  double normalTolerance = 0.1;      ///< facets within this of +z [rad]
  double margin = 0.0;  ///< eroded from every edge, on top of the horizontal radius [m]

  SurfaceOptions options() const;
};

/// "all", "top" or the indices, as a configuration writes them ("[1, 2]").
std::string selectText(const SurfaceRegion& region);

/// The indices of the surfaces @p region selects of @p found (found with region.options()),
/// in the order of `select`.
/// @throw ConfigError as selectSurfaces()
std::vector<std::size_t> selectIndices(const SurfaceRegion& region, const SurfaceSearch& found);

/// The surfaces @p region selects of @p found (found with region.options()).
/// @throw ConfigError "region.of 'shelf' has no support surface of at least 0.0025 m^2 (the
///        largest is 0.001 m^2)", or naming an index past the last surface
std::vector<SupportSurface> selectSurfaces(const SurfaceRegion& region, const SurfaceSearch& found);

/// The support surfaces of @p object at @p position and @p orientation, selected by @p region.
/// @throw ConfigError as selectSurfaces()
std::vector<SupportSurface> surfacesOf(const SurfaceRegion& region, const ObjectModel& object,
                                       const Eigen::Vector3d& position,
                                       const Eigen::Quaterniond& orientation);

/// Uniform draws over the surfaces an object fits on, each inset by a margin: one piece per
/// surface. A convex surface without holes is inset exactly; any other is drawn whole (exact
/// triangles around its holes) and accepts() rejects the draws nearer than the margin to an
/// edge, so the accepted points are uniform over the inset surfaces together.
class SurfaceDraw {
 public:
  /// Why make() found no surface for an object.
  struct NoFit {
    bool tooTall = false;           ///< taller than every clearance (else no room after the inset)
    double largestClearance = 0.0;  ///< [m]
  };

  /// @param surfaces the selected surfaces, in one frame
  /// @param inset the margin kept from every edge [m], >= 0
  /// @param height the object's height (top offset - bottom offset) [m]: surfaces whose
  ///        clearance is smaller are left out
  /// @return nothing (and @p why) when no surface takes the object
  static std::optional<SurfaceDraw> make(const std::vector<SupportSurface>& surfaces, double inset,
                                         double height, NoFit* why = nullptr);

  /// One candidate (draw order: README, "Support surfaces"): a triangle by area (one U(0, 1)),
  /// then a point in it (two) [m]; @p surface receives the index of its surface.
  Eigen::Vector2d draw(Engine& engine, std::size_t& surface) const;
  /// False for a draw of a non-convex or holed surface nearer than the inset to an edge.
  bool accepts(const Eigen::Vector2d& p, std::size_t surface) const;
  /// The height of surface @p surface [m].
  double z(std::size_t surface) const { return pieces_[surface].z; }
  /// The area draw() covers [m^2].
  double drawnArea() const { return area_; }
  /// The surfaces, in the order make() was given them (those the object does not fit on too).
  std::size_t surfaceCount() const { return pieces_.size(); }
  /// The bounds of what draw() covers on surface @p surface [m]; false when it covers nothing
  /// there.
  bool drawnBounds(std::size_t surface, Eigen::Vector2d& lo, Eigen::Vector2d& hi) const;
  /// How deep @p p lies in surface @p surface inset by the margin [m]: >= 0 where draws are
  /// kept, < 0 elsewhere; it changes by at most the distance @p p moves (strategy free_space's
  /// cells).
  double insetDepth(const Eigen::Vector2d& p, std::size_t surface) const;

 private:
  struct Piece {
    double z = 0.0;
    bool rejects = false;  ///< accepts() tests the inset (a non-convex or holed surface)
    std::vector<Eigen::Vector2d> outer;  ///< counter-clockwise; empty: the object does not fit
    std::vector<std::vector<Eigen::Vector2d>> holes;
  };
  std::vector<Piece> pieces_;
  std::vector<Eigen::Vector2d> triangles_;  // three corners each
  std::vector<double> cumulative_;          // running sums of the triangles' areas
  std::vector<std::uint32_t> owner_;        // the piece of each triangle
  double inset_ = 0.0;
  double area_ = 0.0;
};

/// The surfaces of request fixtures that surface regions stand on, found once per request by
/// SceneGenerator::prepare(): for each such sampler, its selected surfaces in the world.
struct TargetSurfaces {
  const void* sampler = nullptr;  ///< the UniformRandomSampler
  std::shared_ptr<const std::vector<SupportSurface>> surfaces;
  std::vector<std::size_t> indices;  ///< theirs among all the fixture's surfaces (--describe)
};
using RequestSurfaces = std::vector<TargetSurfaces>;

/// A thread's draws on targets that are known only in a scene (request fixtures, placed
/// objects): the last one made for each sampler and object, kept while its target stays where
/// it was.
class SurfaceDrawCache {
 public:
  struct Key {
    const void* sampler = nullptr;
    const ObjectModel* object = nullptr;
    const ObjectModel* target = nullptr;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
    bool operator==(const Key& o) const {
      return sampler == o.sampler && object == o.object && target == o.target &&
             position == o.position && orientation.coeffs() == o.orientation.coeffs();
    }
  };
  struct Value {
    std::optional<SurfaceDraw> draw;
    std::string error;  ///< why there is no draw
  };
  /// The value stored for @p key, or nullptr.
  const Value* find(const Key& key) const;
  /// Stores @p value for @p key, replacing the one for the same sampler and object.
  const Value& store(const Key& key, Value value);

 private:
  std::vector<std::pair<Key, Value>> entries_;
};

/// How far @p p lies from @p surface inset by @p inset, 0 on it [m] (validation).
double surfaceShortfall(const SupportSurface& surface, double inset, const Eigen::Vector2d& p);

}  // namespace placement_samplers
