#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "placement_samplers/geometry/shape.hpp"

namespace placement_samplers {

/// Optional explicit values that win over the derived ones.
struct ObjectOverrides {
  bool hasHorizontalRadius = false;
  double horizontalRadius = 0.0;
  bool hasBottomOffset = false;
  Eigen::Vector3d bottomOffset = Eigen::Vector3d::Zero();
  bool hasTopOffset = false;
  Eigen::Vector3d topOffset = Eigen::Vector3d::Zero();
};

/// An object to place, with robosuite's conventions. Offsets are z values from the object's
/// origin in a frame aligned with the world, after the initial orientation is applied.
struct ObjectModel {
  std::string name;
  std::vector<Shape> shapes;  ///< collision geometry in the object frame
  Eigen::Quaterniond initOrientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d bottomOffset = Eigen::Vector3d::Zero();  ///< [m], robosuite's bottom_offset
  Eigen::Vector3d topOffset = Eigen::Vector3d::Zero();     ///< [m], robosuite's top_offset
  double horizontalRadius = 0.0;                           ///< [m]
  /// The collision geometry's lowest z minus bottomOffset.z() [m]: how far above the bottom
  /// offset (an MJCF bottom_site, a given bottom_offset) the geometry ends, so how far the object
  /// drops when placed by it; 0 for derived offsets, negative when the geometry reaches below.
  double bottomGap = 0.0;
  /// topOffset.z() minus the geometry's highest z [m]: how far an object placed on top of this
  /// one (by its top offset) drops onto the geometry; 0 for derived offsets.
  double topGap = 0.0;
  /// True when horizontalRadius bounds the geometry, so circles may skip exact checks.
  bool radiusBoundsGeometry = true;
  /// Its own density for physics [kg/m^3]; 0 = the configuration's `density`.
  double density = 0.0;
  ObjectOverrides overrides;  ///< kept so that a fixture's pose can re-derive the bounds
};

using ObjectPtr = std::shared_ptr<const ObjectModel>;

/// Builds an object: derives offsets and radius from @p shapes under @p initOrientation, then
/// applies @p overrides.
/// @throw std::invalid_argument when @p shapes is empty
ObjectModel makeObject(const std::string& name, std::vector<Shape> shapes,
                       const Eigen::Quaterniond& initOrientation,
                       const ObjectOverrides& overrides = ObjectOverrides());

/// The same object seen under another orientation (a fixture's): bounds derived again under
/// @p orientation, overrides applied again.
ObjectModel reorientedObject(const ObjectModel& object, const Eigen::Quaterniond& orientation);

}  // namespace placement_samplers
