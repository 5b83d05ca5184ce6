#pragma once

// Internal to the node: the priority of its working threads. Not installed.

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>

#include "placement_samplers/ros/placement_server.hpp"

namespace placement_samplers {
namespace ros_interface {

/// Lowers the calling thread's priority by kSamplingNiceness, once per thread (threads it starts
/// inherit it): sampling and publishing yield a core at once to the light services' thread and
/// to roscpp's own network threads, which stay at the process's priority.
inline void lowerThreadPriority() {
  thread_local bool lowered = false;
  if (!lowered) {
    lowered = true;
    const auto tid = static_cast<id_t>(::syscall(SYS_gettid));
    const int now = ::getpriority(PRIO_PROCESS, tid);
    ::setpriority(PRIO_PROCESS, tid, std::min(now + kSamplingNiceness, 19));
  }
}

}  // namespace ros_interface
}  // namespace placement_samplers
