#include "placement_samplers/geometry/object_model.hpp"

namespace placement_samplers {

ObjectModel makeObject(const std::string& name, std::vector<Shape> shapes,
                       const Eigen::Quaterniond& initOrientation,
                       const ObjectOverrides& overrides) {
  ObjectModel object;
  object.name = name;
  object.initOrientation = initOrientation.normalized();
  const Bounds bounds = shapesBounds(shapes, object.initOrientation);
  object.shapes = std::move(shapes);
  object.bottomOffset = Eigen::Vector3d(0.0, 0.0, bounds.bottomZ);
  object.topOffset = Eigen::Vector3d(0.0, 0.0, bounds.topZ);
  object.horizontalRadius = bounds.horizontalRadius;
  if (overrides.hasBottomOffset) {
    object.bottomOffset = overrides.bottomOffset;
  }
  if (overrides.hasTopOffset) {
    object.topOffset = overrides.topOffset;
  }
  if (overrides.hasHorizontalRadius) {
    object.horizontalRadius = overrides.horizontalRadius;
    // A smaller radius than the geometry's no longer bounds it.
    object.radiusBoundsGeometry = overrides.horizontalRadius >= bounds.horizontalRadius;
  }
  object.bottomGap = bounds.bottomZ - object.bottomOffset.z();
  object.topGap = object.topOffset.z() - bounds.topZ;
  object.overrides = overrides;
  return object;
}

ObjectModel reorientedObject(const ObjectModel& object, const Eigen::Quaterniond& orientation) {
  return makeObject(object.name, object.shapes, orientation, object.overrides);
}

}  // namespace placement_samplers
