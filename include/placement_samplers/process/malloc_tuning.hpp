#pragma once

#include <cstddef>
#include <cstdint>

namespace placement_samplers {

/// Freed memory a process that called keepFreedMemoryForBatches() keeps at most [bytes]:
/// 32 MiB at the top of each of at most 4 malloc arenas.
constexpr std::size_t kKeptFreeBytes = std::size_t{128} << 20;

/// Tells glibc's malloc to keep freed memory for the next batch instead of returning it to the
/// kernel at once, within kKeptFreeBytes: free memory at the top of a heap is returned beyond
/// 32 MiB (trim threshold), there are at most 4 arenas (one per thread otherwise, up to eight
/// per core, each keeping its own), and allocations from 32 MiB up are memory-mapped (returned
/// when freed).
///
/// Why: a batch's results are many small blocks, freed together when the batch has been
/// printed or answered; with glibc's defaults the next batch gets the same memory back from
/// the kernel page by page, and those page faults were a third of a PickPlace batch
/// (docs/benchmarks.md). For the main() of the programs that sample batches (sample_scenes,
/// placement_server, placement_benchmark); a library leaves this to its host.
/// Free blocks inside the heaps (below blocks still in use) are not covered by these settings:
/// trimAfterBatch() returns them after large batches.
/// @return true when the allocator took the settings (false without glibc)
bool keepFreedMemoryForBatches();

/// Batches of at least this many placements are large for trimAfterBatch() (about 35 MB of
/// results, as much again as service messages).
constexpr std::uint64_t kTrimAfterPlacements = 250000;

/// Call when the results of a batch of @p placements placements (and any copies, such as a
/// service answer) have been freed: for a large batch (kTrimAfterPlacements or more), returns
/// the freed memory beyond what keepFreedMemoryForBatches() keeps to the kernel (glibc's
/// malloc_trim: free pages inside every arena's heaps, the main heap's top beyond
/// kKeptFreeBytes). A large batch leaves free blocks between blocks still in use, which the
/// allocator would otherwise keep for good (1.1-1.9 GB after large service calls).
/// Costs about a millisecond per GB returned; nothing for smaller batches.
/// @return true when it trimmed (false for a small batch or without glibc)
bool trimAfterBatch(std::uint64_t placements);

/// Input of at least this many bytes is large for trimAfterInput().
constexpr std::size_t kTrimAfterInputBytes = std::size_t{4} << 20;

/// trimAfterBatch() for work measured by its input: call when what was made of @p bytes bytes
/// of input (a line of sample_scenes --validate: its poses and verdict) has been freed; trims
/// from kTrimAfterInputBytes up.
/// @return true when it trimmed
bool trimAfterInput(std::size_t bytes);

}  // namespace placement_samplers
