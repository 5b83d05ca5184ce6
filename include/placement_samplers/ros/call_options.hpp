#pragma once

#include "placement_samplers/sampling/scene_generator.hpp"

namespace placement_samplers {
namespace ros_interface {

/// How PlacementServer::answer() samples one call: as a service call, or as a goal of the
/// ~sample action.
struct CallOptions {
  /// Counts the call's scenes as they finish and cancels the rest between scenes (nullptr:
  /// neither). A cancelled call answers the scenes done before the first cancelled one.
  SampleProgress* progress = nullptr;
  /// A goal: the call as a whole has no time limit (its client sees progress and may cancel);
  /// each scene gets max_request_seconds. A service call gets max_request_seconds in all.
  bool goal = false;
  /// Set by the call: it stopped at a cancel before its last scene.
  bool cancelled = false;
};

}  // namespace ros_interface
}  // namespace placement_samplers
