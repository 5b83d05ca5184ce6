#include <unistd.h>

#include <iostream>
#include <string>
#include <vector>

#include "placement_samplers/process/malloc_tuning.hpp"
#include "cli/sample_scenes_cli.hpp"

int main(int argc, char** argv) {
  placement_samplers::keepFreedMemoryForBatches();
  const std::vector<std::string> args(argv + 1, argv + argc);
  placement_samplers::Terminals terminals;
  terminals.out = ::isatty(STDOUT_FILENO) == 1;
  terminals.err = ::isatty(STDERR_FILENO) == 1;
  return placement_samplers::runSampleScenes(args, std::cout, std::cerr, terminals);
}
