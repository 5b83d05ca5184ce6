#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace placement_samplers {

/// Where sample_scenes' streams go: a progress line is shown by default only on a terminal
/// that the scenes do not go to.
struct Terminals {
  bool out = false;  ///< @p out is a terminal
  bool err = false;  ///< @p err is a terminal
};

/// The sample_scenes command line tool, as a function so that tests can run it in-process.
/// Prints one JSON line per scene to @p out, errors (and the progress line) to @p err.
/// @return 0 when every scene succeeded, 1 when some failed, 2 on a usage or configuration error
int runSampleScenes(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
                    Terminals terminals = Terminals());

}  // namespace placement_samplers
