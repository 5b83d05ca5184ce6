#pragma once

// Internal to the core library: the one way it spreads work over threads. Not installed.

#include <functional>

namespace placement_samplers {
namespace detail {

/// Runs @p work on @p threads threads, the calling thread being one of them (one thread less
/// to start), and returns when all have finished. @p work takes its share itself (an atomic
/// counter), so a thread that cannot be started is skipped and the others do its part. The
/// first exception thrown by any of them is rethrown here, after all have stopped; @p onError
/// runs in the throwing thread first, so that the others can stop early.
void runOnThreads(unsigned threads, const std::function<void()>& work,
                  const std::function<void()>& onError = {});

}  // namespace detail
}  // namespace placement_samplers
