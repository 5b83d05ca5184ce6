#include "placement_samplers/ros/logger_services.hpp"

#include <ros/service_manager.h>
#include <roscpp/GetLoggers.h>

#ifdef ROSCONSOLE_BACKEND_LOG4CXX
#include <log4cxx/level.h>
#include <log4cxx/logger.h>
#include <log4cxx/logmanager.h>
#endif

#include <string>

namespace placement_samplers {
namespace ros_interface {
namespace {

#ifdef ROSCONSOLE_BACKEND_LOG4CXX
/// The names roscpp's get_loggers gives the levels rosconsole sets.
const char* levelName(int level) {
  if (level <= log4cxx::Level::DEBUG_INT) {
    return "debug";
  }
  if (level <= log4cxx::Level::INFO_INT) {
    return "info";
  }
  if (level <= log4cxx::Level::WARN_INT) {
    return "warn";
  }
  if (level <= log4cxx::Level::ERROR_INT) {
    return "error";
  }
  return "fatal";
}

bool getLoggers(roscpp::GetLoggers::Request&, roscpp::GetLoggers::Response& response) {
  // LogManager hands out shared owners of the loggers; the hierarchy keeps its own.
  for (const log4cxx::LoggerPtr& logger : log4cxx::LogManager::getCurrentLoggers()) {
    roscpp::Logger entry;
    entry.name = logger->getName();
    const log4cxx::LevelPtr& level = logger->getEffectiveLevel();
    entry.level = level ? levelName(level->toInt()) : "info";
    response.loggers.push_back(entry);
  }
  return true;
}
#endif

}  // namespace

void LoggerServices::advertise(ros::NodeHandle& privateHandle) {
#ifdef ROSCONSOLE_BACKEND_LOG4CXX
  static const bool withdrawn = [] {
    // roscpp advertised it under the node's resolved private name at ros::start().
    return ros::ServiceManager::instance()->unadvertiseService(ros::names::resolve("~get_loggers"));
  }();
  (void)withdrawn;
  getLoggers_.shutdown();
  getLoggers_ = privateHandle.advertiseService("get_loggers", &getLoggers);
#else
  (void)privateHandle;
#endif
}

}  // namespace ros_interface
}  // namespace placement_samplers
