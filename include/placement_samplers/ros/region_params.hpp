#pragma once

#include <XmlRpcValue.h>

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "placement_samplers/sampling/region.hpp"

namespace placement_samplers {
namespace ros_interface {

/// A uniform sampler's region or one of its keep-out zones, as the region handles show and
/// edit it, in its frame: around the sampler's reference, or the world for a world zone [m].
struct HandleShape {
  RegionShape shape;  ///< a rectangle for x_range/y_range
  /// The region is the sampler's x_range/y_range (no `region` key): it stays so while it is
  /// not turned.
  bool ranges = false;
  std::optional<std::size_t> keepOut;  ///< the zone's index in keep_out; none: the region
  bool world = false;                  ///< a keep-out zone with `frame: world`
};

/// Where the handles put a shape: its centre [m] and the angle of its x axis [rad]. Disks and
/// annuli have no angle; a polygon's centre is the mean of its vertices.
struct ShapePose {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double yaw = 0.0;
};

ShapePose shapePose(const RegionShape& shape);

/// True for shapes a turn changes (rectangles, rotated rectangles, polygons).
bool turns(const RegionShape& shape);

/// The resize handles of a shape: "size_x" and "size_y" (rectangles), "radius" (disks),
/// "inner_radius" and "outer_radius" (annuli); none for polygons.
std::vector<std::string> sizeHandles(const RegionShape& shape);

/// Where resize handle @p handle sits, in the shape's frame [m].
Eigen::Vector2d handlePosition(const RegionShape& shape, const std::string& handle);

/// @p shape with its pose moved to @p pose: turned about its centre by the change of yaw (a
/// turned rectangle becomes a rotated_rectangle) and moved with it.
RegionShape moveShape(const RegionShape& shape, const ShapePose& pose);

/// @p shape with resize handle @p handle released at @p at (shape frame [m]): a rectangle's
/// side through the handle's distance from the centre along that side's axis (both sides move:
/// the centre stays), a radius the handle's distance from the centre.
RegionShape resizeShape(const RegionShape& shape, const std::string& handle,
                        const Eigen::Vector2d& at);

/// The shape as the configuration writes it: {shape: rectangle, x_range, y_range}, ...
XmlRpc::XmlRpcValue shapeParams(const RegionShape& shape);

/// Moves sampler @p name's parameters in @p tree (a private namespace's parameters) into the
/// map form (README, "A sampler's parameters under its own name"): an inline item of a
/// `samplers` list becomes the name, and its map (without `name`) the top-level map of that
/// name. A sampler already in that form stays as it is.
/// @return the sampler's parameters in @p tree
/// @throw ConfigError when no `samplers` list holds a sampler of that name
XmlRpc::XmlRpcValue& samplerParams(XmlRpc::XmlRpcValue& tree, const std::string& name);

/// Writes @p edited into a sampler's parameters @p params: x_range and y_range while the
/// region is an unturned rectangle given so, else `region`; a zone keeps its `frame`.
void writeShape(XmlRpc::XmlRpcValue& params, const HandleShape& edited);

/// The top-level keys of @p after whose values differ from @p before's (or are new there).
std::vector<std::string> changedKeys(XmlRpc::XmlRpcValue& before, XmlRpc::XmlRpcValue& after);

}  // namespace ros_interface
}  // namespace placement_samplers
