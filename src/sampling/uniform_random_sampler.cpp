#include "placement_samplers/sampling/uniform_random_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <unordered_set>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"
#include "sampling/sin_cos.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace {

std::string rangeText(const Eigen::Vector2d& r) {
  return placement_samplers::rangeText(r[0], r[1]);
}

}  // namespace

RotationSpec RotationSpec::fixed(double angle) {
  RotationSpec r;
  r.kind = Kind::Fixed;
  r.low = r.high = angle;
  return r;
}

RotationSpec RotationSpec::range(double a, double b) {
  RotationSpec r;
  r.kind = Kind::Range;
  r.low = std::min(a, b);
  r.high = std::max(a, b);
  return r;
}

UniformRandomSampler::UniformRandomSampler(std::string name, const UniformSamplerParams& params,
                                           const std::vector<ObjectPtr>& objects)
    : PlacementSampler(std::move(name)), params_(params) {
  const std::string where = "sampler " + quoteText(this->name()) + ": ";
  std::ostringstream bound;
  bound << "within [-" << limits::kCoordinate << ", " << limits::kCoordinate << "] m";
  const auto inBounds = [](double v) { return std::abs(v) <= limits::kCoordinate; };
  for (int axis = 0; axis < 2 && params_.checkInputs; ++axis) {
    const Eigen::Vector2d& r = axis == 0 ? params_.xRange : params_.yRange;
    const std::string key = axis == 0 ? "x_range" : "y_range";
    if (!std::isfinite(r[0]) || !std::isfinite(r[1])) {
      throw ConfigError(where + key + " must be finite, got " + rangeText(r));
    }
    if (r[0] > r[1]) {
      throw ConfigError(where + key + " must be [min, max] with min <= max, got " + rangeText(r));
    }
    // Positions are sums of such values: bounded, they stay finite (so does the width).
    if (!inBounds(r[0]) || !inBounds(r[1])) {
      throw ConfigError(where + key + " must lie " + bound.str() + ", got " + rangeText(r));
    }
  }
  if (params_.rotationAxis < 0 || params_.rotationAxis > 2) {
    throw ConfigError(where + "rotation_axis must be x, y or z");
  }
  if (!params_.checkInputs) {
    // The caller's source checks what it draws; the rest is robosuite's to accept.
    if (params_.region || params_.surface || !params_.keepOut.empty() ||
        !params_.relations.empty() ||
        params_.strategy != UniformSamplerParams::Strategy::Rejection) {
      throw ConfigError(where + "unchecked inputs are for rectangular rejection sampling only");
    }
    if (params_.maxAttempts == 0) {
      throw ConfigError(where + "max_attempts must be at least 1");
    }
    axis_ = Eigen::Vector3d::Unit(params_.rotationAxis);
    addObjects(objects);
    return;
  }
  if (!std::isfinite(params_.rotation.low) || !std::isfinite(params_.rotation.high)) {
    throw ConfigError(where + "rotation must be finite");
  }
  // U(low, high) is low + (high - low) u: the width must be finite too.
  if (!std::isfinite(params_.rotation.high - params_.rotation.low)) {
    std::ostringstream out;
    out << where << "rotation [" << params_.rotation.low << ", " << params_.rotation.high
        << "] is too wide: its width overflows a double";
    throw ConfigError(out.str());
  }
  if (!params_.referencePos.allFinite()) {
    throw ConfigError(where + "reference_pos must be finite");
  }
  if ((params_.referencePos.array().abs() > limits::kCoordinate).any()) {
    std::ostringstream out;
    out << where << "reference_pos must lie " << bound.str() << ", got ["
        << params_.referencePos.x() << ", " << params_.referencePos.y() << ", "
        << params_.referencePos.z() << "]";
    throw ConfigError(out.str());
  }
  if (!std::isfinite(params_.zOffset)) {
    throw ConfigError(where + "z_offset must be finite");
  }
  if (!inBounds(params_.zOffset)) {
    std::ostringstream out;
    out << where << "z_offset must lie " << bound.str() << ", got " << params_.zOffset;
    throw ConfigError(out.str());
  }
  if (params_.maxAttempts == 0) {
    throw ConfigError(where + "max_attempts must be at least 1");
  }
  checkShapes(where);
  checkRelations(where);
  if (params_.resting == UniformSamplerParams::Resting::Stable) {
    if (params_.rotationAxis != 2) {
      throw ConfigError(where +
                        "resting: stable turns each object about z after its resting pose: "
                        "rotation_axis must be z");
    }
    if (params_.strategy != UniformSamplerParams::Strategy::Rejection) {
      throw ConfigError(where + "resting: stable takes strategy rejection only");
    }
  }
  axis_ = Eigen::Vector3d::Unit(params_.rotationAxis);
  // free_space's box: the region's bounds, once (a shape's bounds come from its triangles).
  shapeBounds(
      params_.region ? *params_.region : RegionShape::rectangle(params_.xRange, params_.yRange),
      boundsLo_, boundsHi_);
  addObjects(objects);
}

Eigen::Vector2d UniformRandomSampler::effectiveRange(const ObjectModel& object, int axis) const {
  Eigen::Vector2d r = axis == 0 ? params_.xRange : params_.yRange;
  if (params_.ensureObjectBoundaryInRange) {
    r[0] += object.horizontalRadius;
    r[1] -= object.horizontalRadius;
  }
  return r;
}

void UniformRandomSampler::addObjects(const std::vector<ObjectPtr>& objects) {
  std::unordered_set<std::string_view> names;  // a set: thousands of objects are near-linear
  for (const Entry& e : entries_) {
    names.insert(e.object->name);
  }
  for (const ObjectPtr& object : objects) {
    if (!names.insert(object->name).second) {
      throw ConfigError("sampler " + quoteText(name()) + ": object " + quoteText(object->name) +
                        " is already in this sampler");
    }
    Entry entry = makeEntry(object);
    if (params_.resting == UniformSamplerParams::Resting::Stable) {
      addRestingPoses(entry);
    }
    if (entry.poses.empty()) {
      bindEntrySurfaces(entry);
    }
    bindRelations(entry);
    entries_.push_back(std::move(entry));
  }
}

std::vector<ObjectPtr> UniformRandomSampler::objects() const {
  std::vector<ObjectPtr> out;
  out.reserve(entries_.size());
  for (const Entry& e : entries_) {
    out.push_back(e.object);
  }
  return out;
}

void UniformRandomSampler::reset() { entries_.clear(); }

Eigen::Quaterniond UniformRandomSampler::orientationOf(double angle,
                                                       const ObjectModel& object) const {
  // A world-axis rotation applied after the initial orientation; Eigen's AngleAxis conversion,
  // with our sinCos.
  double s = 0.0;
  double c = 0.0;
  sinCos(0.5 * angle, s, c);
  return Eigen::Quaterniond(c, s * axis_.x(), s * axis_.y(), s * axis_.z()) *
         object.initOrientation;
}

std::optional<Eigen::Vector3d> UniformRandomSampler::base(const Reference& reference, bool onTop,
                                                          const Eigen::Vector3d* namedPosition,
                                                          const ObjectModel* namedObject) const {
  switch (reference.kind) {
    case Reference::Kind::Default:
      return params_.referencePos;
    case Reference::Kind::Point:
      return reference.point;
    case Reference::Kind::Name:
      break;
  }
  if (namedPosition == nullptr) {
    return std::nullopt;
  }
  Eigen::Vector3d b = *namedPosition;
  if (onTop) {
    b.z() += namedObject->topOffset.z();
  }
  return b;
}

void UniformRandomSampler::forEachUniform(const Reference& reference, bool onTop,
                                          const UniformVisitor& visit) const {
  visit(*this, reference, onTop);
}

bool UniformRandomSampler::sample(SampleContext& context, const Reference& reference,
                                  bool onTop) const {
  const PlacedEntry* ref =
      reference.kind == Reference::Kind::Name ? context.find(reference.name) : nullptr;
  const std::optional<Eigen::Vector3d> resolved =
      this->base(reference, onTop, ref ? &ref->position : nullptr, ref ? ref->object : nullptr);
  if (!resolved) {
    return fail(context, nullptr, 0,
                "sampler " + quoteText(name()) + ": reference " + quoteText(reference.name) +
                    " is neither a fixture nor an object placed before this sampler");
  }
  const Eigen::Vector3d& base = *resolved;
  if (context.uniformSource() != nullptr &&
      (params_.region || params_.surface || !params_.keepOut.empty() ||
       !params_.relations.empty() || params_.resting != UniformSamplerParams::Resting::Upright ||
       params_.strategy != UniformSamplerParams::Strategy::Rejection)) {
    throw std::logic_error("sampler " + quoteText(name()) +
                           ": a UniformSource serves rectangular rejection sampling only");
  }
  if (params_.strategy == UniformSamplerParams::Strategy::FreeSpace) {
    return sampleFreeSpace(context, base, onTop);
  }
  if (params_.strategy == UniformSamplerParams::Strategy::Dense) {
    return sampleDense(context, base, onTop);
  }
  for (const Entry& entry : entries_) {
    if (!placeOne(context, entry, base, onTop)) {
      return false;
    }
  }
  return true;
}

bool UniformRandomSampler::fail(SampleContext& context, const ObjectModel* object,
                                std::uint32_t attempts, std::string message) const {
  Failure failure;
  if (object != nullptr) {
    failure.object = object->name;
  }
  failure.sampler = name();
  failure.attempts = attempts;
  failure.message = std::move(message);
  context.fail(std::move(failure));
  return false;
}

bool UniformRandomSampler::failOutOfTime(SampleContext& context, const ObjectModel& object,
                                         std::uint32_t attempts) const {
  return fail(context, &object, attempts,
              "stopped placing object " + quoteText(object.name) + " with sampler " +
                  quoteText(name()) + " after " + countText(attempts, "attempt") + ": " +
                  context.outOfTimeReason());
}

bool UniformRandomSampler::failPlacement(SampleContext& context, const ObjectModel& object,
                                         std::uint32_t limit,
                                         const std::vector<std::uint32_t>* counts,
                                         std::uint32_t outside,
                                         const PlacementRelations* relations) const {
  Failure failure;
  failure.object = object.name;
  failure.sampler = name();
  failure.attempts = limit;
  std::ostringstream out;
  out << "could not place object " << quoteText(object.name) << " with sampler "
      << quoteText(name()) << " in " << countText(limit, "attempt");
  if (counts != nullptr && !counts->empty()) {
    const auto most = std::max_element(counts->begin(), counts->end());
    const std::size_t index = static_cast<std::size_t>(most - counts->begin());
    failure.blocker = context.entries()[index].name;
    failure.blockerCount = *most;
    out << ": " << *most << " of them overlapped "
        << (context.entries()[index].fixture ? "fixture" : "object") << " "
        << quoteText(failure.blocker);
    std::size_t others = 0;
    for (std::size_t i = 0; i < counts->size(); ++i) {
      others += (i != index && (*counts)[i] > 0) ? 1 : 0;
    }
    if (others > 0) {
      out << " (and " << others << " other" << (others > 1 ? "s" : "") << " blocked too)";
    }
  }
  if (outside > 0) {
    out << (counts != nullptr && !counts->empty() ? "; " : ": ") << outside
        << " of them fell into a keep-out zone or too near the region's edge";
  }
  if (relations != nullptr && relations->count > 0) {
    // The relation that refused the most attempts (the first of them when tied).
    std::size_t most = 0;
    for (std::size_t i = 1; i < relations->count; ++i) {
      most = relations->refused[i] > relations->refused[most] ? i : most;
    }
    if (relations->refused[most] > 0) {
      const std::size_t index = relations->position[most].index;
      const bool listed = (counts != nullptr && !counts->empty()) || outside > 0;
      out << (listed ? "; " : ": ") << relations->refused[most] << " of them were refused by "
          << relationLabel(params_.relations[index], index);
    }
  }
  failure.message = out.str();
  context.fail(std::move(failure));
  return false;
}

bool UniformRandomSampler::collidesCounted(SampleContext& context, const Candidate& candidate,
                                           std::vector<std::uint32_t>& counts,
                                           std::uint32_t& collided) {
  const std::ptrdiff_t blocker = context.firstCollision(candidate);
  if (blocker == CollisionChecker::kNone) {
    return false;
  }
  ++counts[static_cast<std::size_t>(blocker)];
  ++collided;
  return true;
}

}  // namespace placement_samplers
