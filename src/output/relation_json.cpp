#include "output/relation_json.hpp"

#include "output/json_numbers.hpp"
#include "placement_samplers/output/scene_json.hpp"

namespace placement_samplers::detail {

void appendRelations(std::string& out, const std::vector<Relation>& relations) {
  if (relations.empty()) {
    return;
  }
  out += ", \"relations\": [";
  for (std::size_t i = 0; i < relations.size(); ++i) {
    const Relation& r = relations[i];
    out += i == 0 ? "{\"" : ", {\"";
    out += relationKindName(r.kind);
    out += "\": ";
    appendJsonString(out, r.target);
    switch (r.kind) {
      case Relation::Kind::NextTo: {
        out += ", \"side\": \"";
        out += relationSideName(r.side);
        out += "\", \"distance\": ";
        const double range[2] = {r.minGap, r.maxGap};
        appendVector(out, range, 2);
        break;
      }
      case Relation::Kind::AwayFrom:
        out += ", \"distance\": ";
        appendNumber(out, r.minGap);
        break;
      case Relation::Kind::AlignWith:
        out += ", \"tolerance\": ";
        appendNumber(out, r.tolerance);
        out += ", \"period\": ";
        appendNumber(out, r.period);
        break;
      case Relation::Kind::Face:
        out += ", \"tolerance\": ";
        appendNumber(out, r.tolerance);
        break;
    }
    out += ", \"objects\": ";
    if (r.objects.empty()) {
      out += "null";
    } else {
      out += '[';
      for (std::size_t k = 0; k < r.objects.size(); ++k) {
        out += k == 0 ? "" : ", ";
        appendJsonString(out, r.objects[k]);
      }
      out += ']';
    }
    out += r.requestFixture ? ", \"request_fixture\": true}" : ", \"request_fixture\": false}";
  }
  out += ']';
}

}  // namespace placement_samplers::detail
