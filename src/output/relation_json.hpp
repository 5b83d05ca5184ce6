#pragma once
// A uniform sampler's relations in --describe (relation_json.cpp). Private to the core.

#include <string>
#include <vector>

#include "placement_samplers/sampling/relations.hpp"

namespace placement_samplers::detail {

/// ", \"relations\": [...]", each item as the configuration gives it with every key filled in
/// (next_to: side, distance; away_from: distance; align_with: tolerance, period; face:
/// tolerance; objects: the list or null for all); nothing when there are none.
void appendRelations(std::string& out, const std::vector<Relation>& relations);

}  // namespace placement_samplers::detail
