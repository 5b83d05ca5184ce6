// A uniform sampler's entries: each object's ranges and draws, and under resting: stable one
// entry per resting pose (README, "Resting poses").
#include <cmath>
#include <sstream>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/geometry/resting_poses.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace {

std::string rangeText(const Eigen::Vector2d& r) {
  return placement_samplers::rangeText(r[0], r[1]);
}

/// @p object in resting pose @p pose: the same shapes, turned by the pose instead of its initial
/// orientation, with robosuite's numbers of that pose (a file's sites describe it upright only).
ObjectPtr posedObject(const ObjectModel& object, const RestingPose& pose) {
  auto posed = std::make_shared<ObjectModel>(object);
  posed->initOrientation = pose.orientation;
  posed->bottomOffset = Eigen::Vector3d(0.0, 0.0, pose.bounds.bottomZ);
  posed->topOffset = Eigen::Vector3d(0.0, 0.0, pose.bounds.topZ);
  posed->horizontalRadius = pose.bounds.horizontalRadius;
  posed->bottomGap = 0.0;
  posed->topGap = 0.0;
  posed->radiusBoundsGeometry = true;
  posed->overrides = ObjectOverrides();
  return posed;
}

}  // namespace

UniformRandomSampler::Entry UniformRandomSampler::makeEntry(const ObjectPtr& object) {
  Entry entry;
  entry.object = object;
  entry.x = effectiveRange(*object, 0);
  entry.y = effectiveRange(*object, 1);
  for (int axis = 0; axis < 2 && !params_.region && !params_.surface && params_.checkInputs;
       ++axis) {
    const Eigen::Vector2d& r = axis == 0 ? entry.x : entry.y;
    if (r[0] > r[1]) {
      const char* key = axis == 0 ? "x_range" : "y_range";
      std::ostringstream out;
      out << "sampler " << quoteText(name()) << ": " << key << " "
          << rangeText(axis == 0 ? params_.xRange : params_.yRange) << " leaves no room for object "
          << quoteText(object->name) << " (horizontal radius " << object->horizontalRadius
          << " m) with ensure_object_boundary_in_range on: the range must be at least "
          << 2.0 * object->horizontalRadius << " m wide";
      throw ConfigError(out.str());
    }
  }
  if (!params_.surface && (params_.region || !params_.keepOut.empty())) {
    entry.draw = regionDraw(*object);
  }
  return entry;
}

void UniformRandomSampler::addRestingPoses(Entry& entry) {
  const ObjectModel& object = *entry.object;
  RestingOptions options;
  options.allowRolling = params_.allowRolling;
  std::vector<RestingPose> poses;
  try {
    poses = restingPoses(object.shapes, options);
  } catch (const std::invalid_argument& e) {
    throw ConfigError("sampler " + quoteText(name()) + ": the resting poses of object " +
                      quoteText(object.name) + ": " + e.what());
  }
  double total = 0.0;
  for (const RestingPose& pose : poses) {
    total += pose.probability >= params_.minProbability ? pose.probability : 0.0;
  }
  if (!(total > 0.0)) {
    return;  // no resting pose (a ball): placed as configured
  }
  bool any = false;
  double sum = 0.0;
  for (const RestingPose& pose : poses) {
    if (pose.probability < params_.minProbability) {
      continue;
    }
    Entry posed;
    try {
      posed = makeEntry(posedObject(object, pose));
    } catch (const ConfigError& e) {
      posed.object = posedObject(object, pose);
      posed.usable = false;
      posed.problem = e.what();
    }
    posed.restPose = static_cast<std::int16_t>(entry.poses.size());
    any = any || posed.usable;
    sum += pose.probability / total;
    entry.cumulative.push_back(sum);
    entry.poses.push_back(std::move(posed));
  }
  entry.cumulative.back() = 1.0;  // the last pose takes what rounding leaves
  if (!any) {
    throw ConfigError(entry.poses.front().problem);
  }
}

std::vector<UniformRandomSampler::RestingChoice> UniformRandomSampler::restingChoices(
    const ObjectModel& object) const {
  std::vector<RestingChoice> out;
  for (const Entry& e : entries_) {
    if (e.object->name != object.name) {
      continue;
    }
    double previous = 0.0;
    for (std::size_t k = 0; k < e.poses.size(); ++k) {
      out.push_back(
          RestingChoice{e.poses[k].restPose, e.poses[k].object.get(), e.cumulative[k] - previous});
      previous = e.cumulative[k];
    }
  }
  return out;
}

}  // namespace placement_samplers
