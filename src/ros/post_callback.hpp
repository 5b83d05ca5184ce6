#pragma once

// Internal to the node: running a function on a callback queue. Not installed.

#include <ros/callback_queue.h>

#include <boost/make_shared.hpp>
#include <functional>
#include <utility>

namespace placement_samplers {
namespace ros_interface {

/// Runs @p function once from @p queue (by whichever thread spins it).
inline void postCallback(ros::CallbackQueueInterface* queue, std::function<void()> function) {
  class Callback : public ros::CallbackInterface {
   public:
    explicit Callback(std::function<void()> f) : f_(std::move(f)) {}
    CallResult call() override {
      f_();
      return Success;
    }

   private:
    std::function<void()> f_;
  };
  queue->addCallback(boost::make_shared<Callback>(std::move(function)));
}

}  // namespace ros_interface
}  // namespace placement_samplers
