#pragma once

namespace placement_samplers {

/// Tells glibc's malloc to keep freed memory for the next batch instead of returning it to the
/// kernel at once (trim threshold 128 MiB, memory-mapped allocations from 32 MiB up).
///
/// Why: a batch's results are many small blocks, freed together when the batch has been
/// printed or answered; with glibc's defaults the next batch gets the same memory back from
/// the kernel page by page, and those page faults were a third of a PickPlace batch
/// (docs/benchmarks.md). For the main() of the programs that sample batches (sample_scenes,
/// placement_server, placement_benchmark); a library leaves this to its host.
/// @return true when the allocator took the settings (false without glibc)
bool keepFreedMemoryForBatches();

}  // namespace placement_samplers
