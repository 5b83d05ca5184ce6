// ~validate_placements through the real node: sampled scenes are valid under each check, and a
// moved, missing or unknown object gets its reason; a bad request gets a message.
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <string>
#include <vector>

#include "placement_samplers/SamplePlacements.h"
#include "placement_samplers/ValidatePlacements.h"
#include "node_test_helpers.hpp"

namespace {

using placement_samplers::PoseViolation;
using placement_samplers::SamplePlacements;
using placement_samplers::ValidatePlacements;

const char* const kSample = "/placement_server/sample_placements";
const char* const kValidate = "/placement_server/validate_placements";

class ValidatePlacementsTest : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(ros::service::waitForService(kSample, ros::Duration(30.0)));
    ASSERT_TRUE(ros::service::waitForService(kValidate, ros::Duration(30.0)));
  }

  /// The first scene of a dry-run request with @p seed and check @p check.
  static SamplePlacements::Response sample(std::uint64_t seed, std::uint8_t check) {
    SamplePlacements srv;
    srv.request.seed = seed;
    srv.request.dry_run = true;
    srv.request.collision_check = check;
    EXPECT_TRUE(ros::service::call(kSample, srv));
    EXPECT_TRUE(srv.response.success) << srv.response.message;
    return srv.response;
  }

  static ValidatePlacements::Response validate(const ValidatePlacements::Request& request) {
    ValidatePlacements srv;
    srv.request = request;
    EXPECT_TRUE(ros::service::call(kValidate, srv));
    return srv.response;
  }
};

TEST_F(ValidatePlacementsTest, SampledScenesAreValidUnderEachCheck) {
  for (const std::uint8_t check :
       {ValidatePlacements::Request::CHECK_RADIUS, ValidatePlacements::Request::CHECK_FCL,
        ValidatePlacements::Request::CHECK_RADIUS_AND_FCL}) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      ValidatePlacements::Request request;
      request.placements = sample(seed, check).scenes.at(0).placements;
      request.collision_check = check;
      const ValidatePlacements::Response response = validate(request);
      EXPECT_TRUE(response.valid) << "check " << int(check) << " seed " << seed;
      EXPECT_EQ(response.message, "");
      ASSERT_EQ(response.objects.size(), 6u);
      EXPECT_EQ(response.objects[0].name, "plate");  // sampling order
      for (const auto& object : response.objects) {
        EXPECT_TRUE(object.valid) << object.name;
        EXPECT_TRUE(object.reasons.empty()) << object.name;
      }
    }
  }
}

TEST_F(ValidatePlacementsTest, ReasonsForMovedMissingAndUnknownObjects) {
  ValidatePlacements::Request request;
  request.placements =
      sample(7, ValidatePlacements::Request::CHECK_DEFAULT).scenes.at(0).placements;
  for (auto& p : request.placements) {
    if (p.name == "ball") {
      p.pose.position.z += 0.05;
    }
  }
  request.placements.erase(request.placements.begin() + 1);  // the cup
  placement_samplers::Placement stranger;
  stranger.name = "stranger";
  stranger.pose.orientation.w = 1.0;
  request.placements.push_back(stranger);
  const ValidatePlacements::Response response = validate(request);
  EXPECT_FALSE(response.valid);
  ASSERT_EQ(response.objects.size(), 7u);
  for (const auto& object : response.objects) {
    if (object.name == "ball") {
      ASSERT_EQ(object.reasons.size(), 1u);
      EXPECT_EQ(object.reasons[0].kind, PoseViolation::HEIGHT);
      EXPECT_EQ(object.reasons[0].sampler, "TableSampler");
      EXPECT_NEAR(object.reasons[0].distance, 0.05, 1e-9);
    } else if (object.name == "cup") {
      ASSERT_EQ(object.reasons.size(), 1u);
      EXPECT_EQ(object.reasons[0].kind, PoseViolation::MISSING_OBJECT);
      EXPECT_EQ(object.reasons[0].message, "object 'cup' of sampler 'CupSampler' is missing");
    } else if (object.name == "stranger") {
      ASSERT_EQ(object.reasons.size(), 1u);
      EXPECT_EQ(object.reasons[0].kind, PoseViolation::UNKNOWN_OBJECT);
    } else {
      EXPECT_TRUE(object.valid) << object.name;
    }
  }
  // A looser tolerance accepts the raised ball.
  request.height_tolerance = 0.06;
  for (const auto& object : validate(request).objects) {
    if (object.name == "ball") {
      EXPECT_TRUE(object.valid);
    }
  }
}

// A settled answer validates as it was sampled (its simulated placements at sampled_pose),
// as the CLI validates sampled_position; its settled poses alone would not.
TEST_F(ValidatePlacementsTest, SettledScenesValidateAtTheirSampledPoses) {
  SamplePlacements srv;
  srv.request.seed = 8;
  srv.request.dry_run = true;
  srv.request.physics = SamplePlacements::Request::PHYSICS_SETTLE;
  ASSERT_TRUE(ros::service::call(kSample, srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  ValidatePlacements::Request request;
  request.placements = srv.response.scenes.at(0).placements;
  ASSERT_TRUE(srv.response.scenes[0].simulated);
  const ValidatePlacements::Response response = validate(request);
  EXPECT_TRUE(response.valid);
  for (const auto& object : response.objects) {
    EXPECT_TRUE(object.reasons.empty()) << object.name << ": " << object.reasons[0].message;
  }
  // The settled poses as measured ones: the plate rests 1 cm below its sampled height.
  for (auto& p : request.placements) {
    p.simulated = false;
  }
  bool plateHeight = false;
  for (const auto& object : validate(request).objects) {
    for (const auto& reason : object.reasons) {
      plateHeight = plateHeight || (object.name == "plate" && reason.kind == PoseViolation::HEIGHT);
    }
  }
  EXPECT_TRUE(plateHeight);
}

// A real scene has no hidden object: the configuration's hidden pill is not required.
TEST_F(ValidatePlacementsTest, HiddenObjectsNeedNotBeGiven) {
  const SamplePlacements::Response sampled = sample(9, ValidatePlacements::Request::CHECK_DEFAULT);
  ValidatePlacements::Request request;
  for (const auto& p : sampled.scenes.at(0).placements) {
    if (p.name != "pill") {
      request.placements.push_back(p);
    }
  }
  ASSERT_EQ(request.placements.size(), 5u);
  const ValidatePlacements::Response response = validate(request);
  EXPECT_TRUE(response.valid);
  ASSERT_EQ(response.objects.size(), 6u);
  EXPECT_EQ(response.objects[5].name, "pill");
  EXPECT_TRUE(response.objects[5].valid);
  EXPECT_TRUE(response.objects[5].reasons.empty());
}

TEST_F(ValidatePlacementsTest, BadRequestsGetAMessage) {
  ValidatePlacements::Request request;
  request.sampler = "NoSuchSampler";
  ValidatePlacements::Response response = validate(request);
  EXPECT_FALSE(response.valid);
  EXPECT_NE(response.message.find("NoSuchSampler"), std::string::npos) << response.message;
  EXPECT_TRUE(response.objects.empty());
  request.sampler = "";
  request.collision_check = 9;
  response = validate(request);
  EXPECT_FALSE(response.valid);
  EXPECT_NE(response.message.find("collision_check"), std::string::npos) << response.message;
  request.collision_check = 0;
  request.height_tolerance = -1.0;
  response = validate(request);
  EXPECT_EQ(response.message,
            "height_tolerance: expected a finite non-negative number of metres, got -1");
}

}  // namespace

int main(int argc, char** argv) {
  return placement_samplers::test::runNodeTests(argc, argv, "validate_placements_test");
}
