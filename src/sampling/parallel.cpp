#include "sampling/parallel.hpp"

#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace placement_samplers {
namespace detail {

void runOnThreads(unsigned threads, const std::function<void()>& work,
                  const std::function<void()>& onError) {
  std::mutex errorMutex;
  std::exception_ptr error;
  auto guarded = [&] {
    try {
      work();
    } catch (...) {
      if (onError) {
        onError();
      }
      std::lock_guard<std::mutex> lock(errorMutex);
      if (!error) {
        error = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) {
    try {
      pool.emplace_back(guarded);
    } catch (const std::system_error&) {
      break;  // no more threads to be had: the ones running share the work
    }
  }
  guarded();
  for (std::thread& t : pool) {
    t.join();
  }
  if (error) {
    std::rethrow_exception(error);
  }
}

}  // namespace detail
}  // namespace placement_samplers
