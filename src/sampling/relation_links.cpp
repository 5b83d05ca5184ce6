#include "placement_samplers/sampling/relation_links.hpp"

#include "placement_samplers/sampling/uniform_random_sampler.hpp"

namespace placement_samplers {

std::vector<RelationLink> relationLinks(const PreparedRequest& request, const SceneResult& scene) {
  std::vector<RelationLink> links;
  // A target in the scene as a placed entry: a request fixture or a placement.
  const auto find = [&](const std::string& name, PlacedEntry& out) {
    for (const FixtureSpec& f : request.fixtures) {
      if (f.name == name) {
        out = PlacedEntry(f.name, f.object.get(), f.position, f.orientation, true);
        return true;
      }
    }
    for (const ObjectPlacement& p : scene.placements) {
      if (p.name == name) {
        out = PlacedEntry(p.name, p.object, p.position, p.orientation, false);
        return true;
      }
    }
    return false;
  };
  request.sampler->forEachUniform(
      request.reference, request.onTop,
      [&](const UniformRandomSampler& sampler, const Reference&, bool) {
        const std::vector<Relation>& relations = sampler.params().relations;
        if (relations.empty()) {
          return;
        }
        for (const ObjectPlacement& p : scene.placements) {
          if (p.hidden || p.sampler != sampler.name()) {
            continue;
          }
          for (std::size_t i = 0; i < relations.size(); ++i) {
            const Relation& r = relations[i];
            PlacedEntry target;
            if (!r.appliesTo(std::string(p.name)) || !find(r.target, target)) {
              continue;
            }
            RelationLink link;
            link.sampler = sampler.name();
            link.object = p.name;
            link.target = r.target;
            link.index = i;
            link.kind = r.kind;
            link.from = p.position;
            link.to = target.position;
            link.satisfied = relationHolds(r, relationTarget(target), p.position.head<2>(),
                                           p.object->horizontalRadius, p.orientation);
            links.push_back(std::move(link));
          }
        }
      });
  return links;
}

}  // namespace placement_samplers
