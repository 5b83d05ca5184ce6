// The node's live parts, wired to PlacementServer: /diagnostics, dynamic_reconfigure, the region
// handles and the ~sample action. Part of PlacementServer (placement_server.cpp samples and
// serves configurations).
#include <XmlRpcValue.h>

#include "placement_samplers/ros/node_diagnostics.hpp"
#include "placement_samplers/ros/param_reader.hpp"
#include "placement_samplers/ros/placement_server.hpp"
#include "placement_samplers/ros/reconfigure.hpp"
#include "placement_samplers/ros/region_handles.hpp"
#include "placement_samplers/ros/sample_action.hpp"
#include "ros/post_callback.hpp"

namespace placement_samplers {
namespace ros_interface {

void PlacementServer::startLive(const std::shared_ptr<const SceneGenerator>& generator) {
  std::lock_guard<std::recursive_mutex> serving(serveMutex_);
  diagnostics_->start(lightHandle_);

  // A knob changes the parameters as they are, with every knob set as dynamic_reconfigure has
  // it; dynamic_reconfigure writes them to the parameter server afterwards.
  reconfigure_ = std::make_unique<Reconfigure>(
      lightHandle_, [this](const PlacementServerConfig& knobs, std::string& error) {
        try {
          XmlRpc::XmlRpcValue tree = readParameterTree(privateHandle_);
          setKnobs(knobs, tree);
          return serveTree(tree, false, error);
        } catch (const std::exception& e) {
          error = e.what();
          diagnostics_->refused(error);
          return false;
        }
      });
  reconfigure_->start(generator->config());

  // A released handle: the sampler's parameters in the map form, written once the
  // configuration with them is served.
  const auto edit = [this](const std::string& sampler, const HandleShape& edited,
                           std::string& error) {
    try {
      XmlRpc::XmlRpcValue tree = readParameterTree(privateHandle_);
      XmlRpc::XmlRpcValue before = tree;
      writeShape(samplerParams(tree, sampler), edited);
      if (!serveTree(tree, false, error)) {
        return false;
      }
      for (const std::string& key : changedKeys(before, tree)) {
        privateHandle_.setParam(key, tree[key]);
      }
      ROS_INFO_STREAM(ros::this_node::getName()
                      << ": region handles: sampler '" << sampler << "' changed; "
                      << privateHandle_.getNamespace() << "/" << sampler << " written");
      return true;
    } catch (const std::exception& e) {
      error = e.what();
      diagnostics_->refused(error);
      return false;
    }
  };
  // "sample now": a default call, where service calls run.
  const auto sampleNow = [this] {
    postCallback(ros::getGlobalCallbackQueue(), [this] {
      SamplePlacements::Request request;
      SamplePlacements::Response response;
      CallOptions options;
      answer(request, response, options);
      ROS_INFO_STREAM(ros::this_node::getName()
                      << ": sample now: " << (response.success ? "placed" : "not placed")
                      << ", seed " << response.seed
                      << (response.message.empty() ? "" : ": " + response.message));
    });
  };
  handles_ = std::make_unique<RegionHandles>(privateHandle_.getNamespace() + "/region_handles",
                                             &lightQueue_, edit, sampleNow);
  handles_->show(generator);

  action_ = std::make_unique<SampleAction>(
      lightHandle_, threads_,
      [this](const SamplePlacements::Request& request, SamplePlacements::Response& response,
             CallOptions& options) { answer(request, response, options); });
  action_->start();
}

void PlacementServer::advertiseLive() {
  postCallback(&lightQueue_, [this] {
    std::lock_guard<std::recursive_mutex> serving(serveMutex_);
    diagnostics_->restart();
    reconfigure_->restart();
    handles_->restart();
    action_->restart();
  });
}

}  // namespace ros_interface
}  // namespace placement_samplers
