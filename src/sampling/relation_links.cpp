#include "placement_samplers/sampling/relation_links.hpp"

#include "placement_samplers/collision/make_collision_checker.hpp"
#include "placement_samplers/sampling/sample_context.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"

namespace placement_samplers {

std::vector<RelationLink> relationLinks(const PreparedRequest& request, const SceneResult& scene) {
  std::vector<RelationLink> links;
  // The fcl modes' gaps are the shapes' exact distances: the scene in a checker of the request's
  // mode (made only when some sampler has relations).
  std::unique_ptr<CollisionChecker> checker;
  Engine engine;
  std::unique_ptr<SampleContext> context;
  const auto exactContext = [&]() -> SampleContext* {
    if (request.collisionCheck == CollisionMode::Radius) {
      return nullptr;
    }
    if (!context) {
      checker = makeCollisionChecker(request.collisionCheck, 0.0);
      context = std::make_unique<SampleContext>(engine, *checker);
      for (const FixtureSpec& f : request.fixtures) {
        context->addFixture(f.name, f.object.get(), f.position, f.orientation);
      }
      for (const ObjectPlacement& p : scene.placements) {
        Candidate c;
        c.object = p.object;
        c.position = p.position;
        c.orientation = p.orientation;
        context->addPlacement(p.sampler, c, p.attempts, p.hidden, p.restPose);
      }
    }
    return context.get();
  };
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
            SampleContext* exact = r.isPosition() ? exactContext() : nullptr;
            const PlacedEntry* entry = exact ? exact->find(r.target) : nullptr;
            double gap = 0.0;
            Candidate c;
            c.object = p.object;
            c.position = p.position;
            c.orientation = p.orientation;
            if (entry != nullptr &&
                exact->exactDistance(static_cast<std::size_t>(entry - exact->entries().data()), c,
                                     gap)) {
              const PositionTest test(r, i, relationTarget(target));
              link.satisfied = test.holdsGap(p.position.head<2>(), gap);
            }
            links.push_back(std::move(link));
          }
        }
      });
  return links;
}

}  // namespace placement_samplers
