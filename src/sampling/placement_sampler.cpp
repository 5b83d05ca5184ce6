#include "placement_samplers/sampling/placement_sampler.hpp"

namespace placement_samplers {

Reference Reference::named(const std::string& name) {
  Reference r;
  r.kind = Kind::Name;
  r.name = name;
  return r;
}

Reference Reference::at(const Eigen::Vector3d& point) {
  Reference r;
  r.kind = Kind::Point;
  r.point = point;
  return r;
}

PlacementSampler::PlacementSampler(std::string name) : name_(std::move(name)) {}

const PlacementSampler* PlacementSampler::find(const std::string& name, SampleArgs* args) const {
  if (name != name_) {
    return nullptr;
  }
  if (args != nullptr) {
    *args = SampleArgs();
  }
  return this;
}

void PlacementSampler::collectSamplers(std::vector<const PlacementSampler*>& out) const {
  out.push_back(this);
}

}  // namespace placement_samplers
