// MuJoCo's memory per simulation (MuJoCo 2.2.2 preallocates constraint arrays of rows x rows):
// buffers sized by what the bodies touch and grown when a scene needs more, the estimate of
// what they take, the request's cap with its threads, and densities MuJoCo can simulate.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <memory>
#include <string>
#include <vector>

#include "physics/physics_buffers.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/physics/physics_model.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "sampling/scene_physics.hpp"
#include "temp_dir.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::buildFromYaml;

/// @p n boxes of 4 cm on a table (ground_z), with @p extra top-level keys.
std::string boxes(int n, const std::string& extra = "") {
  std::string yaml = "ground_z: 0.8\nseed: 1\n" + extra + "objects:\n";
  std::string names;
  for (int i = 0; i < n; ++i) {
    yaml += "  box" + std::to_string(i) + ": {shape: box, size: [0.04, 0.04, 0.04]}\n";
    names += (i > 0 ? ", box" : "box") + std::to_string(i);
  }
  return yaml + "samplers:\n  - {name: S, objects: [" + names +
         "], x_range: [-1, 1], y_range: [-1, 1], rotation: 0.0, reference_pos: [0, 0, 0.8], "
         "z_offset: 0.001}\n";
}

std::string requestError(const std::function<void()>& f) {
  try {
    f();
  } catch (const RequestError& e) {
    return e.what();
  }
  return "no RequestError";
}

// A plate resting on 144 balls touches them all: more contacts than the first buffers hold
// (four per geom of a body). The world grows its buffers and simulates the scene again; the
// answer is the one buffers large enough from the start give.
TEST(PhysicsMemory, BuffersGrowForScenesWithManyContacts) {
  const ObjectModel plate = makeObject("plate", {Shape::box(Eigen::Vector3d(0.4, 0.4, 0.02))},
                                       Eigen::Quaterniond::Identity());
  const ObjectModel ball =
      makeObject("ball", {Shape::sphere(0.01)}, Eigen::Quaterniond::Identity());
  std::vector<PhysicsFixture> fixtures;
  for (int i = 0; i < 12; ++i) {
    for (int j = 0; j < 12; ++j) {
      fixtures.push_back(PhysicsFixture{
          &ball, Eigen::Vector3d(-0.165 + 0.03 * i, -0.165 + 0.03 * j, 0.01), {1, 0, 0, 0}});
    }
  }
  PhysicsSettings settings;
  settings.seconds = 0.2;
  const auto model = std::make_shared<const PhysicsModel>(
      fixtures, std::vector<PhysicsBody>{PhysicsBody{&plate, 0.0, 500.0}}, settings);
  PhysicsWorld world(model);
  EXPECT_EQ(world.contactCapacity(), 20u);
  EXPECT_EQ(world.bytes(), model->worldBytes());
  const std::vector<BodyPose> start{BodyPose{Eigen::Vector3d(0, 0, 0.03), {1, 0, 0, 0}}};
  std::vector<BodyPose> poses = start;
  std::vector<PhysicsOutcome> outcomes;
  EXPECT_EQ(world.simulate(poses, outcomes), PhysicsStatus::Stable);
  EXPECT_EQ(world.contactCapacity(), 160u);  // 20, 40, 80, 160 >= 144
  EXPECT_GT(world.bytes(), model->worldBytes());
  EXPECT_NEAR(poses[0].position.z(), 0.03, 1e-3);
  // Again with the grown buffers from the start, and in a new world that grows again.
  std::vector<BodyPose> again = start;
  EXPECT_EQ(world.simulate(again, outcomes), PhysicsStatus::Stable);
  EXPECT_EQ(again[0].position, poses[0].position);
  EXPECT_EQ(again[0].orientation.coeffs(), poses[0].orientation.coeffs());
  PhysicsWorld fresh(model);
  std::vector<BodyPose> third = start;
  EXPECT_EQ(fresh.simulate(third, outcomes), PhysicsStatus::Stable);
  EXPECT_EQ(third[0].position, poses[0].position);
  // A world that may not grow says so instead of simulating with contacts left out.
  PhysicsWorld small(model, model->worldBytes());
  std::vector<BodyPose> fourth = start;
  EXPECT_EQ(small.simulate(fourth, outcomes), PhysicsStatus::TooLarge);
  EXPECT_EQ(small.contactCapacity(), 20u);
}

// The estimate is what mj_makeData allocates, each of its arrays rounded up to 64 bytes.
TEST(PhysicsMemory, DataBytesAreWhatMujocoAllocates) {
  const test::TempDir dir("placement_samplers_physics");
  const std::string path =
      dir.file("scene.xml",
               "<mujoco><worldbody><geom type='plane' size='0 0 1'/><body><freejoint/>"
               "<geom type='box' size='0.1 0.1 0.1'/></body><body><freejoint/><geom type='sphere' "
               "size='0.1'/></body></worldbody></mujoco>");
  char error[1000] = "";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  for (const std::uint64_t contacts : {20u, 1000u}) {
    const detail::PhysicsBuffers b = detail::physicsBuffers(contacts, m->nv);
    m->nconmax = static_cast<int>(b.contacts);
    m->njmax = static_cast<int>(b.rows);
    m->nstack = static_cast<int>(b.stack);
    mjData* d = mj_makeData(m);
    ASSERT_NE(d, nullptr);
    const std::uint64_t allocated = sizeof(mjData) + static_cast<std::uint64_t>(d->nbuffer) +
                                    sizeof(mjtNum) * static_cast<std::uint64_t>(d->nstack);
    const std::uint64_t estimate = detail::dataBytes(*m, b);
    EXPECT_GE(estimate, allocated);
    EXPECT_LE(estimate, allocated + 64 * 128);
    // The part known before compiling is a lower bound.
    EXPECT_LE(detail::bufferBytes(b, m->nv), estimate);
    mj_deleteData(d);
  }
  mj_deleteModel(m);
}

// 300 boxes took 1.5 GB per simulating thread, 1000 request fixtures 12 GB or more: a request
// whose one simulation does not fit physics_max_memory_mb is refused with the numbers.
TEST(PhysicsMemory, RequestsThatDoNotFitAreRefusedWithTheNumbers) {
  const SceneGenerator generator(buildFromYaml(boxes(100, "physics_max_memory_mb: 16\n")));
  SampleRequest request;
  request.physics = PhysicsMode::Check;
  const PreparedRequest prepared = generator.prepare(request);
  const std::uint64_t dofs = 600;
  const std::uint64_t bytes =
      detail::bufferBytes(detail::physicsBuffers(detail::restingContacts(100), dofs), dofs);
  EXPECT_EQ(requestError([&] { generator.sampleScenes(prepared, 1, 2, 2); }),
            "physics: simulating the scene takes an estimated " + std::to_string(bytes) +
                " bytes of MuJoCo data (100 free bodies with 100 geoms; MuJoCo 2.2.2 "
                "preallocates contact arrays that grow with the square of the contacts), more "
                "than physics_max_memory_mb (16 MiB = 16777216 bytes)");
  // Physics none needs none of it.
  request.physics = PhysicsMode::None;
  EXPECT_TRUE(generator.sampleScene(generator.prepare(request), 1, 0).success);
}

// Each simulating thread holds its own MuJoCo data: as many threads simulate as fit, with an
// equal share each, and the scenes are the same whatever the threads.
TEST(PhysicsMemory, ThreadsAreCountedInTheMemory) {
  const SceneGenerator generator(
      buildFromYaml(boxes(30, "physics_max_memory_mb: 64\nphysics_seconds: 0.1\n")));
  SampleRequest request;
  request.physics = PhysicsMode::Check;
  const PreparedRequest prepared = generator.prepare(request);
  const std::uint64_t perThread = prepared.physicsModel->model()->worldBytes();
  const std::uint64_t cap = std::uint64_t{64} << 20;
  ASSERT_LT(perThread * 4, cap);
  EXPECT_EQ(prepared.physicsModel->simulatingThreads(1024), cap / perThread);
  EXPECT_EQ(prepared.physicsModel->simulatingThreads(3), 3u);
  EXPECT_EQ(prepared.physicsModel->threadShare(4), cap / 4);
  const auto one = generator.sampleScenes(prepared, 7, 8, 1);
  const auto many = generator.sampleScenes(prepared, 7, 8, 1024);
  ASSERT_EQ(one.size(), many.size());
  for (std::size_t k = 0; k < one.size(); ++k) {
    ASSERT_TRUE(one[k].simulated) << one[k].message;
    EXPECT_EQ(one[k].stable, many[k].stable);
    for (std::size_t i = 0; i < one[k].physics.size(); ++i) {
      EXPECT_EQ(one[k].physics[i].moved, many[k].physics[i].moved);
    }
  }
}

// A plate on a bed of 900 balls touches 900 of them: buffers for 320 contacts already take
// more than 16 MiB (rows x rows doubles). The
// scene fails and says why; the request and the other scenes go on.
TEST(PhysicsMemory, ScenesBeyondTheThreadsShareFailWithAMessage) {
  std::string yaml =
      "physics_max_memory_mb: 16\nphysics_seconds: 0.1\nobjects:\n"
      "  ball: {shape: sphere, radius: 0.01}\n  plate: {shape: box, size: [1.0, 1.0, 0.02]}\n"
      "fixtures:\n";
  for (int i = 0; i < 30; ++i) {
    for (int j = 0; j < 30; ++j) {
      yaml += "  - {name: b" + std::to_string(30 * i + j) + ", object: ball, position: [" +
              std::to_string(-0.435 + 0.03 * i) + ", " + std::to_string(-0.435 + 0.03 * j) +
              ", 0.01]}\n";
    }
  }
  yaml +=
      "samplers:\n  - {name: S, objects: [plate], x_range: [0, 0], y_range: [0, 0], rotation: "
      "0.0, reference_pos: [0, 0, 0.02], z_offset: 0.001, ensure_object_boundary_in_range: "
      "false}\n";
  const SceneGenerator generator(buildFromYaml(yaml));
  SampleRequest request;
  request.physics = PhysicsMode::Check;
  const SceneResult scene = generator.sampleScene(generator.prepare(request), 1, 0);
  EXPECT_FALSE(scene.success);
  EXPECT_FALSE(scene.simulated);
  EXPECT_EQ(scene.message,
            "physics: the scene has more contacts than MuJoCo's buffers of 160 contacts hold, "
            "and twice as many would take more than this thread's share of "
            "physics_max_memory_mb (16777216 bytes of its 16 MiB)");
}

// Fixtures touch nothing but the bodies: a thousand of them no longer size the buffers.
TEST(PhysicsMemory, FixturesDoNotSizeTheBuffers) {
  const SceneGenerator generator(buildFromYaml(boxes(1)));
  SampleRequest request;
  request.physics = PhysicsMode::Check;
  const std::uint64_t alone = generator.prepare(request).physicsModel->model()->worldBytes();
  for (int i = 0; i < 1000; ++i) {
    RequestFixture f;
    f.name = "post" + std::to_string(i);
    f.shape = Shape::cylinder(0.01, 0.1);
    f.position = Eigen::Vector3d(5.0 + 0.05 * (i % 40), 0.05 * (i / 40), 0.85);
    request.fixtures.push_back(f);
  }
  const PreparedRequest prepared = generator.prepare(request);
  const std::uint64_t withFixtures = prepared.physicsModel->model()->worldBytes();
  EXPECT_LT(withFixtures, alone + (std::uint64_t{1} << 20));
  const SceneResult scene = generator.sampleScene(prepared, 1, 0);
  EXPECT_TRUE(scene.simulated) << scene.message;
}

// A body MuJoCo finds too light is named by its object, with what to change.
TEST(PhysicsMemory, BodiesTooLightForMujocoNameTheirObject) {
  const SceneGenerator generator(buildFromYaml(
      "ground_z: 0.8\nobjects:\n  speck: {shape: box, size: [0.0002, 0.0002, 0.0002], density: "
      "1}\nsamplers:\n  - {name: S, objects: [speck], x_range: [-0.1, 0.1], y_range: [-0.1, "
      "0.1], reference_pos: [0, 0, 0.8]}\n"));
  SampleRequest request;
  request.physics = PhysicsMode::Check;
  const std::string message =
      requestError([&] { generator.sampleScene(generator.prepare(request), 1, 0); });
  const std::string expected =
      "physics: MuJoCo could not build the scene: object 'speck' is too light for MuJoCo: with "
      "density 1 kg/m^3 its mass or rotational inertia is below mjMINVAL (1e-15); give it a "
      "larger density or size (MuJoCo: Error: mass and inertia of moving bodies must be larger "
      "than mjMINVAL; Object name = body0";
  EXPECT_EQ(message.substr(0, expected.size()), expected);
}

}  // namespace
}  // namespace placement_samplers
