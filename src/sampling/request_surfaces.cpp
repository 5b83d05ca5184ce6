#include "sampling/request_surfaces.hpp"

#include "placement_samplers/errors.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers::detail {

void prepareRequestSurfaces(PreparedRequest& request) {
  request.sampler->forEachUniform(
      request.reference, request.onTop,
      [&](const UniformRandomSampler& sampler, const Reference&, bool) {
        const std::optional<SurfaceRegion>& region = sampler.params().surface;
        if (!region || sampler.surfacesBound()) {
          return;
        }
        const FixtureSpec* fixture = nullptr;
        for (const FixtureSpec& f : request.fixtures) {
          if (f.name == region->of) {
            fixture = &f;
          }
        }
        if (fixture == nullptr) {
          throw RequestError("sampler " + quoteText(sampler.name()) + ": region.of " +
                             quoteText(region->of) +
                             " is neither a configured fixture, a fixture of this request nor "
                             "an object an earlier sampler places");
        }
        const PlacedEntry target(fixture->name, fixture->object.get(), fixture->position,
                                 fixture->orientation, true);
        TargetSurfaces found;
        found.sampler = &sampler;
        try {
          found.surfaces = std::make_shared<const std::vector<SupportSurface>>(
              sampler.surfacesOn(target, nullptr, &found.indices));
        } catch (const ConfigError& e) {
          throw RequestError("sampler " + quoteText(sampler.name()) + ": " + e.what());
        }
        for (const ObjectPtr& object : sampler.objects()) {
          SurfaceDraw::NoFit why;
          if (!SurfaceDraw::make(*found.surfaces, sampler.surfaceInset(*object),
                                 object->topOffset.z() - object->bottomOffset.z(), &why)) {
            throw RequestError(sampler.noFitMessage(*object, why));
          }
        }
        request.surfaces.push_back(std::move(found));
      });
}

}  // namespace placement_samplers::detail
