#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace placement_samplers {

/// The sample_scenes command line tool, as a function so that tests can run it in-process.
/// Prints one JSON line per scene to @p out, errors to @p err.
/// @return 0 when every scene succeeded, 1 when some failed, 2 on a usage or configuration error
int runSampleScenes(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace placement_samplers
