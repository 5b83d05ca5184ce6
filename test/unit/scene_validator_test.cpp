// validateScene(): each kind of violation with its message, tolerances, request fixtures, and
// every sampled scene of every shipped configuration valid under each collision check.

#include <gtest/gtest.h>

#include <dirent.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/collision/make_collision_checker.hpp"
#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/validation/scene_validator.hpp"

namespace placement_samplers {
namespace {

const std::string kSource = PLACEMENT_SAMPLERS_SOURCE_DIR;

// Plate on the table (top at z = 0.8), a cup on the plate (unchecked), cube and ball on the
// table. Heights: plate 0.82, cup plate + 0.055, cube 0.83, ball 0.84.
const std::string kConfig = R"(
collision_check: radius
objects:
  table_top: {shape: box, size: [0.8, 0.8, 0.05]}
  plate: {shape: cylinder, radius: 0.09, length: 0.02}
  cup: {shape: cylinder, radius: 0.04, length: 0.09}
  cube: {shape: box, size: [0.04, 0.04, 0.04]}
  ball: {shape: sphere, radius: 0.03}
fixtures:
  - {name: table, object: table_top, position: [0, 0, 0.775]}
samplers: [PlateSampler, CupSampler, TableSampler]
PlateSampler: {objects: [plate], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3], z_offset: 0.01,
               sample_args: {reference: table, on_top: true}}
CupSampler: {objects: [cup], x_range: [-0.02, 0.02], y_range: [-0.02, 0.02],
             ensure_object_boundary_in_range: false, ensure_valid_placement: false,
             sample_args: {reference: plate, on_top: true}}
TableSampler: {objects: [cube, ball], x_range: [-0.35, 0.35], y_range: [-0.35, 0.35],
               z_offset: 0.01, sample_args: {reference: table, on_top: true}}
)";

class SceneValidatorTest : public ::testing::Test {
 protected:
  SceneValidatorTest() : generator_(buildSceneConfig(parseYaml(kConfig, "test"))) {}

  /// A valid scene.
  static std::vector<GivenPose> scene() {
    return {pose("plate", 0.0, 0.0, 0.82), pose("cup", 0.01, 0.0, 0.875),
            pose("cube", 0.2, 0.2, 0.83), pose("ball", -0.2, 0.2, 0.84)};
  }
  static GivenPose pose(const std::string& name, double x, double y, double z) {
    GivenPose p;
    p.name = name;
    p.position = Eigen::Vector3d(x, y, z);
    return p;
  }
  SceneVerdict validate(const std::vector<GivenPose>& poses, const SampleRequest& request = {},
                        const ValidationOptions& options = {}) const {
    return validateScene(generator_, generator_.prepare(request), poses, options);
  }
  /// The reasons' messages of object @p name.
  static std::vector<std::string> reasons(const SceneVerdict& v, const std::string& name) {
    std::vector<std::string> out;
    for (const ObjectVerdict& o : v.objects) {
      if (o.name == name) {
        for (const Violation& r : o.reasons) {
          out.push_back(std::string(violationKindName(r.kind)) + ": " + r.message);
        }
      }
    }
    return out;
  }

  SceneGenerator generator_;
};

using Reasons = std::vector<std::string>;

TEST_F(SceneValidatorTest, ValidScene) {
  const SceneVerdict v = validate(scene());
  EXPECT_TRUE(v.valid);
  ASSERT_EQ(v.objects.size(), 4u);
  EXPECT_EQ(v.objects[0].name, "plate");  // sampling order
  EXPECT_EQ(v.objects[3].name, "ball");
  for (const ObjectVerdict& o : v.objects) {
    EXPECT_TRUE(o.valid) << o.name;
  }
}

TEST_F(SceneValidatorTest, OutsideRegion) {
  std::vector<GivenPose> poses = scene();
  poses[3].position.x() = 0.42;  // ball's region: x in [-0.32, 0.32] around the table
  const SceneVerdict v = validate(poses);
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(reasons(v, "ball"), Reasons{"outside_region: object 'ball' is outside the region of "
                                        "sampler 'TableSampler' by 0.1 m"});
  EXPECT_NEAR(v.objects[3].reasons[0].distance, 0.1, 1e-12);
  EXPECT_EQ(v.objects[3].reasons[0].sampler, "TableSampler");
  // The cup's region moves with the plate it references.
  poses = scene();
  poses[0].position.x() = 0.1;
  poses[1].position.x() = 0.1 + 0.02;
  EXPECT_TRUE(validate(poses).valid);
  poses[1].position.x() = 0.1 - 0.05;
  EXPECT_EQ(reasons(validate(poses), "cup"),
            Reasons{"outside_region: object 'cup' is outside the region of sampler 'CupSampler' "
                    "by 0.03 m"});
}

TEST_F(SceneValidatorTest, HeightAndTolerance) {
  std::vector<GivenPose> poses = scene();
  poses[2].position.z() = 0.85;
  EXPECT_EQ(reasons(validate(poses), "cube"),
            Reasons{"height: object 'cube' is at z 0.85 m, off the height of sampler "
                    "'TableSampler' (0.83 m) by 0.02 m"});
  poses[2].position.z() = 0.834;  // within the default 0.005 m
  EXPECT_TRUE(validate(poses).valid);
  poses[2].position.z() = 0.836;
  EXPECT_FALSE(validate(poses).valid);
  ValidationOptions loose;
  loose.heightTolerance = 0.01;
  EXPECT_TRUE(validate(poses, {}, loose).valid);
  // The cup's height follows the plate (on_top: the plate's top).
  poses = scene();
  poses[0].position.z() = 0.9;
  const SceneVerdict v = validate(poses);
  EXPECT_EQ(reasons(v, "plate").size(), 1u);
  EXPECT_EQ(reasons(v, "cup"), Reasons{"height: object 'cup' is at z 0.875 m, off the height of "
                                       "sampler 'CupSampler' (0.955 m) by 0.08 m"});
  ValidationOptions bad;
  bad.heightTolerance = -1.0;
  EXPECT_THROW(validate(scene(), {}, bad), RequestError);
}

TEST_F(SceneValidatorTest, OverlapsUnderEachCheck) {
  std::vector<GivenPose> poses = scene();
  poses[3].position = Eigen::Vector3d(0.0, 0.1, 0.84);  // 0.1 m from the plate: radii 0.12
  poses[2].position = Eigen::Vector3d(0.02, 0.1, 0.83);
  SceneVerdict v = validate(poses);
  EXPECT_EQ(reasons(v, "cube"),
            Reasons{"overlap: object 'cube' overlaps object 'plate' under the radius check"});
  // Every object it overlaps, placed before it in sampling order.
  EXPECT_EQ(reasons(v, "ball"),
            (Reasons{"overlap: object 'ball' overlaps object 'plate' under the radius check",
                     "overlap: object 'ball' overlaps object 'cube' under the radius check"}));
  EXPECT_EQ(v.objects[3].reasons[1].other, "cube");
  EXPECT_EQ(v.objects[3].reasons[1].check, "radius");
  EXPECT_EQ(v.objects[3].reasons[1].sampler, "TableSampler");
  // The cup sits on the plate, inside its radius, but its sampler does not check.
  EXPECT_TRUE(reasons(v, "cup").empty());
  SampleRequest fcl;
  fcl.collisionCheck = CollisionMode::Fcl;
  v = validate(poses, fcl);
  EXPECT_EQ(reasons(v, "ball").back(),
            "overlap: object 'ball' overlaps object 'cube' under the fcl check");
}

TEST_F(SceneValidatorTest, OverlapsListedPerObjectAtMost) {
  std::vector<GivenPose> poses = scene();
  poses[3].position = Eigen::Vector3d(0.0, 0.1, 0.84);  // the ball overlaps the plate and cube
  poses[2].position = Eigen::Vector3d(0.02, 0.1, 0.83);
  ValidationOptions one;
  one.maxOverlapsListed = 1;
  SceneVerdict v = validate(poses, {}, one);
  EXPECT_EQ(reasons(v, "ball"),
            Reasons{"overlap: object 'ball' overlaps object 'plate' under the radius check (and 1 "
                    "more fixture or object, not listed)"});
  EXPECT_EQ(v.objects[3].reasons[0].other, "plate");
  ValidationOptions none;
  none.maxOverlapsListed = 0;
  v = validate(poses, {}, none);
  EXPECT_EQ(reasons(v, "ball"),
            Reasons{"overlap: object 'ball' overlaps 2 fixtures and objects under the radius check "
                    "(not listed)"});
  EXPECT_EQ(v.objects[3].reasons[0].other, "");
  EXPECT_EQ(v.objects[3].reasons[0].check, "radius");
}

/// 300 objects at one point: each lists at most 10 of the objects before it (45,000 reasons
/// otherwise), the last one says how many it did not list.
TEST(SceneValidatorPile, ListsAtMostTenOverlapsPerObject) {
  std::string yaml = "objects:\n";
  std::string names;
  std::vector<GivenPose> poses;
  for (int i = 0; i < 300; ++i) {
    yaml += "  o" + std::to_string(i) + ": {shape: sphere, radius: 0.01}\n";
    names += (i ? ", o" : "o") + std::to_string(i);
    GivenPose p;
    p.name = "o" + std::to_string(i);
    p.position = Eigen::Vector3d(0.0, 0.0, 0.01);
    poses.push_back(p);
  }
  yaml +=
      "samplers:\n  - {name: S, objects: [" + names + "], x_range: [-1, 1], y_range: [-1, 1]}\n";
  const SceneGenerator generator(buildSceneConfig(parseYaml(yaml, "test")));
  const SceneVerdict v = validateScene(generator, generator.prepare(SampleRequest()), poses);
  ASSERT_EQ(v.objects.size(), 300u);
  EXPECT_TRUE(v.objects[0].valid);
  ASSERT_EQ(v.objects[5].reasons.size(), 5u);
  EXPECT_EQ(v.objects[5].reasons[4].message,
            "object 'o5' overlaps object 'o4' under the radius check");
  const std::vector<Violation>& last = v.objects[299].reasons;
  ASSERT_EQ(last.size(), 10u);
  EXPECT_EQ(last[0].other, "o0");
  EXPECT_EQ(last[9].other, "o9");
  EXPECT_EQ(last[9].message,
            "object 'o299' overlaps object 'o9' under the radius check (and 289 more fixtures "
            "and objects, not listed)");
  // The scene's pair tests run out at object 45 (1 + 2 + ... + 44 = 990 of 1000 before it).
  ValidationOptions few;
  few.maxOverlapTests = 1000;
  const SceneVerdict cut = validateScene(generator, generator.prepare(SampleRequest()), poses, few);
  EXPECT_EQ(cut.objects[44].reasons.back().message,
            "object 'o44' overlaps object 'o9' under the radius check (and 34 more fixtures and "
            "objects, not listed)");
  EXPECT_EQ(cut.objects[45].reasons.back().message,
            "object 'o45' overlaps object 'o9' under the radius check (and possibly others: the "
            "scene's overlap search stopped after 1000 tests)");
  // Later objects list the overlap that the sampling test found.
  ASSERT_EQ(cut.objects[299].reasons.size(), 1u);
  EXPECT_FALSE(cut.objects[299].valid);
  EXPECT_NE(cut.objects[299].reasons[0].other, "");
  const std::string& message = cut.objects[299].reasons[0].message;
  EXPECT_EQ(message.substr(message.find(" under")),
            " under the radius check (and possibly others: the scene's overlap search stopped "
            "after 1000 tests)");
}

TEST_F(SceneValidatorTest, PosesPerSceneBounded) {
  std::vector<GivenPose> poses(limits::kValidatedPlacements + 1, pose("cube", 0.2, 0.2, 0.83));
  try {
    validate(poses);
    ADD_FAILURE() << "no RequestError";
  } catch (const RequestError& e) {
    EXPECT_STREQ(e.what(), "the scene has 100001 placements, more than the limit of 100000");
  }
  poses.pop_back();
  const SceneVerdict v = validate(poses);  // duplicates: one reason each, on the cube
  EXPECT_EQ(v.objects[2].reasons.size(), limits::kValidatedPlacements - 1);
}

TEST_F(SceneValidatorTest, RequestFixtures) {
  SampleRequest request;
  RequestFixture box;
  box.name = "crate";
  box.shape = Shape::box(Eigen::Vector3d(0.1, 0.1, 0.1));
  box.position = Eigen::Vector3d(0.2, 0.2, 0.85);
  request.fixtures.push_back(box);
  EXPECT_EQ(reasons(validate(scene(), request), "cube"),
            Reasons{"overlap: object 'cube' overlaps fixture 'crate' under the radius check"});
}

TEST_F(SceneValidatorTest, UnknownMissingDuplicateReference) {
  std::vector<GivenPose> poses = scene();
  poses.erase(poses.begin());  // the plate, which the cup references
  poses.push_back(pose("mug", 0, 0, 0));
  poses.push_back(pose("ball", 0.3, 0.3, 0.84));
  const SceneVerdict v = validate(poses);
  EXPECT_FALSE(v.valid);
  ASSERT_EQ(v.objects.size(), 5u);
  EXPECT_EQ(reasons(v, "plate"),
            Reasons{"missing_object: object 'plate' of sampler 'PlateSampler' is missing"});
  EXPECT_EQ(reasons(v, "cup"),
            Reasons{"reference_missing: object 'cup': reference 'plate' of sampler 'CupSampler' "
                    "is neither a fixture nor an object placed before it"});
  EXPECT_EQ(reasons(v, "mug"),
            Reasons{"unknown_object: object 'mug' is not placed by sampler 'root'"});
  EXPECT_EQ(reasons(v, "ball"),
            Reasons{"duplicate: object 'ball' is given more than once: the first pose counts"});
  EXPECT_TRUE(v.objects[2].valid) << "cube";
}

// A real scene has no hidden objects (sampling parks them 10 m away): they are not required.
TEST(SceneValidatorHidden, HiddenObjectsMayBeLeftOutButAGivenOneIsChecked) {
  std::string yaml = kConfig;
  const std::string ball = "  ball: {shape: sphere, radius: 0.03}\n";
  yaml.replace(yaml.find(ball), ball.size(),
               ball + "  pill: {shape: capsule, radius: 0.02, length: 0.08}\n");
  yaml += "hide: [pill]\n";
  const SceneGenerator generator(buildSceneConfig(parseYaml(yaml, "test")));
  const PreparedRequest prepared = generator.prepare(SampleRequest());
  auto pose = [](const std::string& name, double x, double y, double z) {
    return GivenPose{name, Eigen::Vector3d(x, y, z), Eigen::Quaterniond::Identity()};
  };
  std::vector<GivenPose> poses = {pose("plate", 0.0, 0.0, 0.82), pose("cup", 0.01, 0.0, 0.875),
                                  pose("cube", 0.2, 0.2, 0.83), pose("ball", -0.2, 0.2, 0.84)};
  SceneVerdict v = validateScene(generator, prepared, poses);
  EXPECT_TRUE(v.valid);
  ASSERT_EQ(v.objects.size(), 5u);
  EXPECT_EQ(v.objects[4].name, "pill");
  EXPECT_TRUE(v.objects[4].valid);
  EXPECT_TRUE(v.objects[4].reasons.empty());
  // Where sampling parks it: valid; on the table: not where the configuration puts it.
  poses.push_back(pose("pill", -15.0, -15.0, 10.06));
  EXPECT_TRUE(validateScene(generator, prepared, poses).valid);
  poses.back() = pose("pill", 0.0, 0.2, 0.84);
  v = validateScene(generator, prepared, poses);
  EXPECT_FALSE(v.valid);
  ASSERT_FALSE(v.objects[4].reasons.empty());
  EXPECT_EQ(v.objects[4].reasons[0].kind, Violation::Kind::OutsideRegion);
  // Only hidden objects: a missing table object is still missing.
  poses.erase(poses.begin() + 3);
  v = validateScene(generator, prepared, poses);
  EXPECT_FALSE(v.objects[3].valid);
  EXPECT_EQ(v.objects[3].reasons[0].kind, Violation::Kind::Missing);
}

TEST_F(SceneValidatorTest, BadPoses) {
  std::vector<GivenPose> poses = scene();
  poses[2].position.x() = std::numeric_limits<double>::quiet_NaN();
  poses[3].orientation.coeffs().setZero();
  const SceneVerdict v = validate(poses);
  EXPECT_EQ(reasons(v, "cube"),
            Reasons{"bad_pose: object 'cube': the position must be finite and within +-1e+06 m"});
  EXPECT_EQ(reasons(v, "ball"),
            Reasons{"bad_pose: object 'ball': the orientation must be a finite non-zero "
                    "quaternion"});
  // A non-unit quaternion is a rotation: normalised.
  poses = scene();
  poses[3].orientation.coeffs() << 0.0, 0.0, 0.0, 2.0;
  EXPECT_TRUE(validate(poses).valid);
}

std::vector<GivenPose> posesOf(const SceneResult& scene) {
  std::vector<GivenPose> poses;
  for (const ObjectPlacement& p : scene.placements) {
    poses.push_back(GivenPose{std::string(p.name), p.position, p.orientation});
  }
  return poses;
}

std::vector<std::string> configFiles() {
  std::vector<std::string> files;
  if (DIR* dir = opendir((kSource + "/config").c_str())) {
    while (const dirent* entry = readdir(dir)) {
      const std::string name = entry->d_name;
      if (name.size() > 5 && name.substr(name.size() - 5) == ".yaml") {
        files.push_back(kSource + "/config/" + name);
      }
    }
    closedir(dir);
  }
  files.push_back(kSource + "/test/data/robosuite/crowded.yaml");
  files.push_back(kSource + "/test/data/robosuite/mixed.yaml");
  return files;
}

// Every sampled scene validates; a failed one lacks exactly the objects it did not place.
TEST(SceneValidatorRoundTrip, EverySampledSceneIsValid) {
  BuildOptions options;
  options.packageResolver = [](const std::string& package) {
    return package == "placement_samplers" ? kSource : std::string();
  };
  const std::vector<std::string> files = configFiles();
  ASSERT_GE(files.size(), 9u);
  std::size_t total = 0;
  for (const std::string& file : files) {
    options.baseDirectory = file.substr(0, file.rfind('/'));
    const SceneGenerator generator(buildSceneConfig(loadYamlFile(file), options));
    for (const CollisionMode mode :
         {CollisionMode::Radius, CollisionMode::Fcl, CollisionMode::RadiusAndFcl}) {
      SampleRequest request;
      request.collisionCheck = mode;
      const PreparedRequest prepared = generator.prepare(request);
      std::size_t valid = 0;
      for (const SceneResult& scene : generator.sampleScenes(prepared, 42, 60, 2)) {
        const SceneVerdict v = validateScene(generator, prepared, posesOf(scene));
        const std::string label =
            file + " " + collisionModeName(mode) + " scene " + std::to_string(scene.index);
        EXPECT_EQ(v.valid, scene.success) << label;
        valid += v.valid ? 1 : 0;
        for (const ObjectVerdict& o : v.objects) {
          for (const Violation& r : o.reasons) {
            EXPECT_EQ(r.kind, Violation::Kind::Missing) << label << ": " << r.message;
          }
        }
      }
      total += valid;
    }
  }
  // Most configurations place most scenes (long_boxes.yaml none, by design).
  EXPECT_GT(total, 1000u);
}

}  // namespace
}  // namespace placement_samplers
