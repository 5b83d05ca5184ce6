// A uniform sampler's `relations:` list (README, "Relations"): each item's keys, and its target
// against what is in the scene when the sampler runs.
#include <algorithm>
#include <functional>
#include <sstream>

#include "config/builder_parts.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers::detail {
namespace {

struct KindKeys {
  const char* key;
  Relation::Kind kind;
  std::vector<std::string> allowed;
};

const std::vector<KindKeys>& kindKeys() {
  static const std::vector<KindKeys> kinds{
      {"next_to",
       Relation::Kind::NextTo,
       {"next_to", "side", "distance", "objects", "request_fixture"}},
      {"away_from",
       Relation::Kind::AwayFrom,
       {"away_from", "distance", "objects", "request_fixture"}},
      {"align_with",
       Relation::Kind::AlignWith,
       {"align_with", "tolerance", "period", "objects", "request_fixture"}},
      {"face", Relation::Kind::Face, {"face", "tolerance", "objects", "request_fixture"}},
  };
  return kinds;
}

double nonNegative(const ConfigNode& n, const std::string& where, const char* unit) {
  const double v = n.asDouble();
  if (v < 0.0) {
    std::ostringstream out;
    out << where << "expected a number >= 0 [" << unit << "], got " << v;
    n.fail(out.str());
  }
  return v;
}

}  // namespace

std::vector<Relation> parseRelations(const ConfigNode& list, const std::string& sampler) {
  const std::string where = "sampler " + quoteText(sampler) + ": ";
  if (!list.isList()) {
    list.fail(where + "expected a list of relations, got " + ConfigNode::typeName(list.type()));
  }
  std::vector<Relation> relations;
  for (const ConfigNode& item : list.elements()) {
    if (!item.isMap()) {
      item.fail(where + "expected a map with one of next_to, away_from, align_with, face");
    }
    const KindKeys* kind = nullptr;
    for (const KindKeys& k : kindKeys()) {
      if (item.get(k.key) != nullptr) {
        if (kind != nullptr) {
          item.fail(where + "give one of next_to, away_from, align_with, face; got " + kind->key +
                    " and " + k.key);
        }
        kind = &k;
      }
    }
    if (kind == nullptr) {
      item.fail(where + "expected one of next_to, away_from, align_with, face (the target)");
    }
    item.checkKeys(kind->allowed);
    Relation r;
    r.kind = kind->kind;
    r.target = item.at(kind->key).asString();
    if (r.target.empty()) {
      item.at(kind->key).fail(where + "expected the name of a fixture or an earlier object");
    }
    if (const ConfigNode* n = item.get("side")) {
      const std::string& side = n->asString();
      const std::vector<std::pair<const char*, Relation::Side>> sides{
          {"any", Relation::Side::Any},
          {"left", Relation::Side::Left},
          {"right", Relation::Side::Right},
          {"front", Relation::Side::Front},
          {"back", Relation::Side::Back}};
      const auto found =
          std::find_if(sides.begin(), sides.end(), [&](const auto& s) { return side == s.first; });
      if (found == sides.end()) {
        n->fail(where + "expected left, right, front, back or any, got " + quoteText(side));
      }
      r.side = found->second;
    }
    if (r.kind == Relation::Kind::NextTo) {
      const ConfigNode& d = item.at("distance");
      if (!d.isList()) {
        d.fail(where + "expected the gap's [min, max] [m]");
      }
      const Eigen::Vector2d range = parseRange(d);
      if (range[0] < 0.0) {
        d.fail(where + "expected a gap [min, max] with min >= 0 [m]");
      }
      r.minGap = range[0];
      r.maxGap = range[1];
    } else if (r.kind == Relation::Kind::AwayFrom) {
      r.minGap = nonNegative(item.at("distance"), where, "m");
    } else if (r.kind == Relation::Kind::AlignWith) {
      const ConfigNode& t = item.at("tolerance");
      r.tolerance = nonNegative(t, where, "rad");
      if (!(r.tolerance > 0.0 && r.tolerance <= M_PI)) {
        t.fail(where + "expected a tolerance in (0, pi] [rad]: the turn is drawn within it");
      }
      if (const ConfigNode* p = item.get("period")) {
        r.period = p->asDouble();
        if (!(r.period > 0.0 && r.period <= 2 * M_PI)) {
          p->fail(where + "expected a period in (0, 2 pi] [rad]");
        }
      }
    } else if (const ConfigNode* t = item.get("tolerance")) {
      r.tolerance = nonNegative(*t, where, "rad");
      if (r.tolerance > M_PI) {
        t->fail(where + "expected a tolerance in [0, pi] [rad]");
      }
    }
    if (const ConfigNode* objects = item.get("objects")) {
      for (const ConfigNode& o : objects->elements()) {
        r.objects.push_back(o.asString());
      }
      if (r.objects.empty()) {
        objects->fail(where + "expected the names of some objects of this sampler");
      }
    }
    if (const ConfigNode* f = item.get("request_fixture")) {
      r.requestFixture = f->asBool();
    }
    relations.push_back(std::move(r));
  }
  return relations;
}

void checkRelationTargets(const ConfigNode& list, const std::vector<Relation>& relations,
                          const std::string& sampler, const std::vector<ObjectPtr>& objects,
                          const std::set<std::string>& available, const SceneConfig& config) {
  const std::string where = "sampler " + quoteText(sampler) + ": ";
  const auto position = [&](const std::string& name) -> std::ptrdiff_t {
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (objects[i]->name == name) {
        return static_cast<std::ptrdiff_t>(i);
      }
    }
    return -1;
  };
  // An object's targets within this sampler: a path back to it is a cycle.
  const auto targetsOf = [&](const std::string& name) {
    std::vector<std::string> out;
    for (const Relation& r : relations) {
      if (r.appliesTo(name) && position(r.target) >= 0) {
        out.push_back(r.target);
      }
    }
    return out;
  };
  const std::function<bool(const std::string&, const std::string&, std::vector<std::string>&)>
      reaches =
          [&](const std::string& from, const std::string& to, std::vector<std::string>& path) {
            if (from == to) {
              return true;
            }
            if (std::find(path.begin(), path.end(), from) != path.end()) {
              return false;
            }
            path.push_back(from);
            for (const std::string& next : targetsOf(from)) {
              if (reaches(next, to, path)) {
                return true;
              }
            }
            path.pop_back();
            return false;
          };
  for (std::size_t i = 0; i < relations.size(); ++i) {
    const Relation& r = relations[i];
    const ConfigNode& item = list.elements()[i];
    const ConfigNode& targetNode = item.at(relationKindName(r.kind));
    const std::string label = where + relationLabel(r, i) + ": ";
    for (std::size_t j = 0; j < r.objects.size(); ++j) {
      if (position(r.objects[j]) < 0) {
        item.at("objects").elements()[j].fail(label + quoteText(r.objects[j]) +
                                              " is not an object of this sampler");
      }
    }
    const bool fixture = std::any_of(config.fixtures.begin(), config.fixtures.end(),
                                     [&](const FixtureSpec& f) { return f.name == r.target; });
    const bool object = config.findObject(r.target) != nullptr;
    if (r.requestFixture) {
      if (fixture || object) {
        item.at("request_fixture")
            .fail(label + quoteText(r.target) + " is a configured " +
                  (fixture ? "fixture" : "object") + ", not a fixture of the request");
      }
      continue;
    }
    if (available.count(r.target) != 0) {
      continue;  // a configured fixture or an object an earlier sampler places
    }
    const std::ptrdiff_t at = position(r.target);
    if (at < 0 && object) {
      targetNode.fail(label + "target " + quoteText(r.target) +
                      " is an object that no earlier sampler places: it is not in the scene "
                      "yet when this sampler runs");
    }
    if (at < 0) {
      targetNode.fail(label + "unknown target " + quoteText(r.target) +
                      ": neither a configured fixture nor an object (a fixture every request "
                      "gives takes request_fixture: true)");
    }
    for (const ObjectPtr& o : objects) {
      if (!r.appliesTo(o->name) || position(o->name) > at) {
        continue;
      }
      if (o->name == r.target) {
        targetNode.fail(label + "relates object " + quoteText(o->name) + " to itself");
      }
      std::vector<std::string> path;
      if (reaches(r.target, o->name, path)) {
        std::string cycle = o->name;
        for (const std::string& p : path) {
          cycle += " -> " + p;
        }
        targetNode.fail(label + "the relations form a cycle: " + cycle + " -> " + o->name);
      }
      targetNode.fail(label + "target " + quoteText(r.target) + " is placed after object " +
                      quoteText(o->name) +
                      " (a sampler places its objects in their order): list it before");
    }
  }
}

}  // namespace placement_samplers::detail
