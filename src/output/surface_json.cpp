// A surface region in --describe: its keys and the surfaces found on its target.
#include <algorithm>
#include <cmath>

#include "output/json_numbers.hpp"
#include "output/surface_json.hpp"
#include "placement_samplers/output/scene_json.hpp"

namespace placement_samplers::detail {
namespace {

void appendPoints(std::string& out, const std::vector<Eigen::Vector2d>& points) {
  out += '[';
  for (std::size_t i = 0; i < points.size(); ++i) {
    out += i == 0 ? "" : ", ";
    appendVector(out, points[i].data(), 2);
  }
  out += ']';
}

}  // namespace

void appendSurfaces(std::string& out, const std::vector<SupportSurface>& surfaces,
                    const std::vector<std::size_t>& selected) {
  out += '[';
  for (std::size_t i = 0; i < surfaces.size(); ++i) {
    const SupportSurface& s = surfaces[i];
    out += i == 0 ? "{\"index\": " : ", {\"index\": ";
    appendInteger(out, i);
    const bool taken = std::find(selected.begin(), selected.end(), i) != selected.end();
    out += taken ? ", \"selected\": true" : ", \"selected\": false";
    out += ", \"z\": ";
    appendNumber(out, s.z);
    out += ", \"area\": ";
    appendNumber(out, s.area);
    out += ", \"clearance\": ";
    if (std::isfinite(s.clearance)) {
      appendNumber(out, s.clearance);
    } else {
      out += "null";
    }
    out += ", \"vertices\": ";
    appendPoints(out, s.outer);
    out += ", \"holes\": [";
    for (std::size_t h = 0; h < s.holes.size(); ++h) {
      out += h == 0 ? "" : ", ";
      appendPoints(out, s.holes[h]);
    }
    out += "]}";
  }
  out += ']';
}

void appendSurfaceRegion(std::string& out, const UniformRandomSampler& sampler) {
  const SurfaceRegion& r = *sampler.params().surface;
  out += "{\"shape\": \"surface\", \"of\": ";
  appendJsonString(out, r.of);
  out += ", \"select\": ";
  if (r.select == SurfaceRegion::Select::Indices) {
    out += selectText(r);
  } else {
    appendJsonString(out, selectText(r));
  }
  out += ", \"min_area\": ";
  appendNumber(out, r.minArea);
  out += ", \"normal_tolerance\": ";
  appendNumber(out, r.normalTolerance);
  out += ", \"margin\": ";
  appendNumber(out, r.margin);
  // The selected surfaces: in the world for a configured fixture, at the object's origin for
  // an earlier object (they move with it), none for a request's fixture (found per call).
  out += ", \"surfaces_frame\": ";
  if (!sampler.foundSurfaces()) {
    out += "null, \"surfaces\": null}";
    return;
  }
  out += sampler.surfacesBoundToObject() ? "\"object\"" : "\"world\"";
  out += ", \"surfaces\": ";
  appendSurfaces(out, sampler.foundSurfaces()->surfaces, sampler.selectedSurfaces());
  out += '}';
}

}  // namespace placement_samplers::detail
