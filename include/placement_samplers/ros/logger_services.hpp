#pragma once

#include <ros/ros.h>

namespace placement_samplers {
namespace ros_interface {

/// Serves the node's `~get_loggers` in place of roscpp's own.
///
/// Debian 12's rosconsole (built against log4cxx 1.0) answers get_loggers by wrapping log4cxx's
/// logger hierarchy in a second owning pointer and so frees it: the node's next log message,
/// or the next `~set_logger_level` (rqt_logger_level calls the two in that order), then
/// crashes with SIGSEGV. This service lists the same loggers and levels through log4cxx's own
/// LogManager, which leaves the hierarchy alone. roscpp's `~set_logger_level` is safe and stays.
/// With a rosconsole backend other than log4cxx, roscpp's service is left as it is.
class LoggerServices {
 public:
  /// Withdraws roscpp's `~get_loggers` (once per process) and advertises this one on
  /// @p privateHandle (its callback queue serves it). Call again after a master restart to
  /// register again.
  void advertise(ros::NodeHandle& privateHandle);

 private:
  ros::ServiceServer getLoggers_;
};

}  // namespace ros_interface
}  // namespace placement_samplers
