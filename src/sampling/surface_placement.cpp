// The uniform sampler's surface region: objects drawn on the support surfaces of a fixture or
// of an object placed earlier (README, "Support surfaces").
#include <cmath>
#include <sstream>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace {

/// A rotation whose x and y parts are below this is one about z (a placed object's yaw).
constexpr double kPureYaw = 1e-12;

}  // namespace

double UniformRandomSampler::surfaceInset(const ObjectModel& object) const {
  return (params_.ensureObjectBoundaryInRange ? object.horizontalRadius : 0.0) +
         params_.surface->margin;
}

std::string UniformRandomSampler::noFitMessage(const ObjectModel& object,
                                               const SurfaceDraw::NoFit& why) const {
  const SurfaceRegion& region = *params_.surface;
  std::ostringstream out;
  out << "sampler " << quoteText(name()) << ": object " << quoteText(object.name);
  if (why.tooTall) {
    out << " (height " << object.topOffset.z() - object.bottomOffset.z()
        << " m) fits on no selected surface of " << quoteText(region.of)
        << " (select: " << selectText(region) << "): the largest clearance is "
        << why.largestClearance << " m";
  } else {
    out << " finds no room on the selected surfaces of " << quoteText(region.of)
        << " (select: " << selectText(region) << ") that it fits under: none has a point "
        << surfaceInset(object) << " m from its edges (";
    if (params_.ensureObjectBoundaryInRange) {
      out << "its horizontal radius " << object.horizontalRadius
          << " m with ensure_object_boundary_in_range on, plus ";
    }
    out << "margin " << region.margin << " m)";
  }
  return out.str();
}

void UniformRandomSampler::bindSurfaces(const ObjectModel& target, const Eigen::Vector3d& position,
                                        const Eigen::Quaterniond& orientation, bool objectFrame) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = position;
  pose.linear() = orientation.normalized().toRotationMatrix();
  auto found = std::make_shared<const SurfaceSearch>(
      findSupportSurfaces(target.shapes, pose, params_.surface->options()));
  std::vector<std::size_t> indices = selectIndices(*params_.surface, *found);
  std::vector<SupportSurface> selected;
  for (const std::size_t i : indices) {
    selected.push_back(found->surfaces[i]);
  }
  auto surfaces = std::make_shared<const std::vector<SupportSurface>>(std::move(selected));
  boundSurfaces_ = std::move(surfaces);
  foundSurfaces_ = std::move(found);
  selectedIndices_ = std::move(indices);
  boundToObject_ = objectFrame;
  for (Entry& entry : entries_) {
    if (entry.poses.empty()) {
      bindEntrySurfaces(entry);
      continue;
    }
    // A resting pose that fits on no surface is not drawn; one of them must fit.
    bool any = false;
    for (Entry& pose : entry.poses) {
      try {
        bindEntrySurfaces(pose);
        any = any || pose.usable;
      } catch (const ConfigError& e) {
        pose.usable = false;
        pose.problem = e.what();
      }
    }
    if (!any) {
      throw ConfigError(entry.poses.front().problem);
    }
  }
}

void UniformRandomSampler::bindEntrySurfaces(Entry& entry) const {
  if (!boundSurfaces_) {
    return;
  }
  const ObjectModel& object = *entry.object;
  SurfaceDraw::NoFit why;
  std::optional<SurfaceDraw> draw = SurfaceDraw::make(
      *boundSurfaces_, surfaceInset(object), object.topOffset.z() - object.bottomOffset.z(), &why);
  if (!draw) {
    throw ConfigError(noFitMessage(object, why));
  }
  if (!boundToObject_) {
    entry.surfaceDraw = std::make_shared<const SurfaceDraw>(std::move(*draw));
  }
}

std::vector<SupportSurface> UniformRandomSampler::surfacesOn(
    const PlacedEntry& target, const RequestSurfaces* request,
    std::vector<std::size_t>* indices) const {
  const SurfaceRegion& region = *params_.surface;
  if (boundSurfaces_ && indices != nullptr) {
    *indices = selectedIndices_;
  }
  if (boundSurfaces_ && !boundToObject_) {
    return *boundSurfaces_;
  }
  if (boundSurfaces_) {
    // Placed as robosuite places it: a turn about z after its initial orientation keeps the
    // faces that face up; the surfaces found at its origin turn and move with it.
    const Eigen::Quaterniond turn = target.orientation * target.object->initOrientation.inverse();
    if (std::abs(turn.x()) < kPureYaw && std::abs(turn.y()) < kPureYaw) {
      const double yaw = 2.0 * std::atan2(turn.z(), turn.w());
      std::vector<SupportSurface> out;
      out.reserve(boundSurfaces_->size());
      for (const SupportSurface& s : *boundSurfaces_) {
        out.push_back(movedSurface(s, yaw, target.position));
      }
      return out;
    }
  } else if (request != nullptr) {
    for (const TargetSurfaces& t : *request) {
      if (t.sampler == this) {
        if (indices != nullptr) {
          *indices = t.indices;
        }
        return *t.surfaces;
      }
    }
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = target.position;
  pose.linear() = target.orientation.normalized().toRotationMatrix();
  const SurfaceSearch found = findSupportSurfaces(target.object->shapes, pose, region.options());
  std::vector<std::size_t> selected = selectIndices(region, found);
  std::vector<SupportSurface> out;
  for (const std::size_t i : selected) {
    out.push_back(found.surfaces[i]);
  }
  if (indices != nullptr) {
    *indices = std::move(selected);
  }
  return out;
}

const SurfaceDraw* UniformRandomSampler::surfaceDrawOn(SampleContext& context, const Entry& entry,
                                                       const PlacedEntry& target,
                                                       std::string& error) const {
  if (entry.surfaceDraw) {
    return entry.surfaceDraw.get();
  }
  const SurfaceDrawCache::Key key{this, entry.object.get(), target.object, target.position,
                                  target.orientation};
  SurfaceDrawCache& cache = context.surfaceCache();
  const SurfaceDrawCache::Value* value = cache.find(key);
  if (value == nullptr) {
    SurfaceDrawCache::Value made;
    try {
      const ObjectModel& object = *entry.object;
      SurfaceDraw::NoFit why;
      made.draw =
          SurfaceDraw::make(surfacesOn(target, context.requestSurfaces()), surfaceInset(object),
                            object.topOffset.z() - object.bottomOffset.z(), &why);
      if (!made.draw) {
        made.error = noFitMessage(object, why);
      }
    } catch (const ConfigError& e) {
      made.error = "sampler " + quoteText(name()) + ": " + e.what();
    }
    value = &cache.store(key, std::move(made));
  }
  if (!value->draw) {
    error = value->error;
    return nullptr;
  }
  return &*value->draw;
}

bool UniformRandomSampler::placeOnSurface(SampleContext& context, const Entry& entry,
                                          const Eigen::Vector3d& base,
                                          PlacementRelations* relations) const {
  const ObjectModel& object = *entry.object;
  const SurfaceRegion& region = *params_.surface;
  const PlacedEntry* target = context.find(region.of);
  if (target == nullptr) {
    return fail(context, &object, 0,
                "sampler " + quoteText(name()) + ": region.of " + quoteText(region.of) +
                    " is neither a fixture nor an object placed before this sampler");
  }
  std::string error;
  const SurfaceDraw* draw = surfaceDrawOn(context, entry, *target, error);
  if (draw == nullptr) {
    return fail(context, &object, 0, error);
  }
  // Per attempt: the surface draws (README, "Support surfaces"), the rotation in the fcl
  // modes, then the edge test of a holed or non-convex surface, the keep-out zones and the
  // collision test; the rotation after the accepted attempt otherwise, as robosuite.
  Engine& engine = engineOf(context);
  const std::uint32_t limit = attemptLimit(context);
  const bool check = params_.ensureValidPlacement;
  const bool orientFirst = check && context.needsOrientation();
  std::vector<std::uint32_t>* counts = check ? &context.blockerCounts() : nullptr;
  const double keepOutMargin = params_.ensureObjectBoundaryInRange ? object.horizontalRadius : 0.0;
  const Eigen::Vector2d offset = base.head<2>();
  // robosuite's on_top rule with the surface as the reference's top.
  const double lift = params_.zOffset - object.bottomOffset.z();
  std::uint32_t outside = 0;
  std::uint32_t collided = 0;

  Candidate candidate;
  candidate.object = &object;
  candidate.support = target - context.entries().data();
  for (std::uint32_t attempt = 1; attempt <= limit; ++attempt) {
    if ((attempt & 1023u) == 0 && context.expired()) {
      return failOutOfTime(context, object, attempt - 1);
    }
    if (relations != nullptr && attempt == kRelationProbeAttempts &&
        !relationsPossible(context, object, *relations)) {
      return false;
    }
    std::size_t surface = 0;
    const Eigen::Vector2d p = draw->draw(engine, surface);
    candidate.position = Eigen::Vector3d(p.x(), p.y(), draw->z(surface) + lift);
    if (orientFirst && relations == nullptr) {
      candidate.orientation = sampleOrientation(engine, object);
    }
    bool blocked = !draw->accepts(p, surface);
    for (std::size_t i = 0; i < params_.keepOut.size() && !blocked; ++i) {
      const KeepOutZone& zone = params_.keepOut[i];
      blocked = keepOutBlocks(zone, zone.world ? p : Eigen::Vector2d(p - offset), keepOutMargin);
    }
    if (blocked) {
      ++outside;
      continue;
    }
    if (relations != nullptr) {
      // After the surface and keep-out tests; the turn before them in the fcl modes, whose
      // exact gaps need it.
      if (relations->exact) {
        candidate.orientation = relatedOrientation(engine, object, p, relations);
      }
      if (!relationsHold(context, *relations, candidate)) {
        continue;
      }
    }
    if (check && collidesCounted(context, candidate, *counts, collided)) {
      continue;
    }
    if (!orientFirst && (relations == nullptr || !relations->exact)) {
      candidate.orientation = relatedOrientation(engine, object, p, relations);
    }
    context.addPlacement(name(), candidate, attempt, params_.hides);
    return true;
  }
  return failPlacement(context, object, limit, collided > 0 ? counts : nullptr, outside, relations);
}

}  // namespace placement_samplers
