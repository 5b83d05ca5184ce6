// The configuration builder: YAML text to SceneConfig, every validation rule and the exact
// message it gives (each names the full parameter path).

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "placement_samplers/sampling/sequential_composite_sampler.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"
#include "test_helpers.hpp"

namespace placement_samplers {
namespace {

using test::buildFromYaml;

// Objects and a fixture most tests build on. ball: radius 0.05 (prints exactly).
const std::string kObjects = R"(
objects:
  cube: {shape: box, size: [0.04, 0.04, 0.04]}
  ball: {shape: sphere, radius: 0.05}
  plate: {shape: cylinder, radius: 0.09, length: 0.02}
  cup: {shape: cylinder, radius: 0.04, length: 0.09}
  pill: {shape: capsule, radius: 0.02, length: 0.08}
  table_top: {shape: box, size: [1, 1, 0.05]}
fixtures:
  - {name: table, object: table_top, position: [0, 0, 0.8]}
)";

/// The ConfigError message of building @p yaml.
std::string buildError(const std::string& yaml) {
  try {
    buildFromYaml(yaml);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no ConfigError";
}

const UniformRandomSampler& uniformNamed(const SceneConfig& config, const std::string& name) {
  const auto* s = dynamic_cast<const UniformRandomSampler*>(config.root->find(name, nullptr));
  if (s == nullptr) {
    throw std::runtime_error("no uniform sampler " + name);
  }
  return *s;
}

TEST(ConfigBuilder, EmptyConfigurationGivesDefaults) {
  // An empty tree (an empty file is refused by the reader, as an empty namespace by the node).
  const auto config = buildSceneConfig(ConfigNode::makeRoot());
  EXPECT_EQ(config->frameId, "world");
  EXPECT_FALSE(config->tfPrefix.has_value());  // the node uses its own name
  EXPECT_EQ(config->seed, 0u);
  EXPECT_EQ(config->collisionCheck, CollisionMode::Radius);
  EXPECT_EQ(config->maxAttempts, 5000u);
  EXPECT_TRUE(config->objects.empty());
  ASSERT_TRUE(config->root != nullptr);
  EXPECT_EQ(config->root->name(), kRootSamplerName);
  EXPECT_EQ(config->root->size(), 0u);
}

TEST(ConfigBuilder, TopLevelValues) {
  const auto config = buildFromYaml(R"(
frame_id: map
tf_prefix: ""
seed: 18446744073709551615
collision_check: radius
collision_margin: 0
max_attempts: 100
)");
  EXPECT_EQ(config->frameId, "map");
  EXPECT_EQ(config->tfPrefix, std::optional<std::string>(""));
  // Above 2^63: kept as digits by the YAML reader and read back exactly.
  EXPECT_EQ(config->seed, 18446744073709551615ull);
  EXPECT_EQ(config->collisionMargin, 0.0);
  EXPECT_EQ(config->maxAttempts, 100u);
}

TEST(ConfigBuilder, LoadsTheDefaultConfiguration) {
  const auto config = buildSceneConfig(
      loadYamlFile(std::string(PLACEMENT_SAMPLERS_SOURCE_DIR) + "/config/default.yaml"));
  EXPECT_EQ(config->objects.size(), 7u);
  ASSERT_EQ(config->fixtures.size(), 1u);
  EXPECT_EQ(config->fixtures[0].name, "table");
  EXPECT_EQ(config->hidden, (std::vector<std::string>{"pill"}));
  std::vector<const PlacementSampler*> all;
  config->root->collectSamplers(all);
  std::vector<std::string> names;
  for (const PlacementSampler* s : all) {
    names.push_back(s->name());
  }
  EXPECT_EQ(names, (std::vector<std::string>{"root", "PlateSampler", "CupSampler", "TableSampler",
                                             SequentialCompositeSampler::kHideSamplerName}));
}

TEST(ConfigBuilder, UniformSamplerParameters) {
  const auto config = buildFromYaml(kObjects + R"(
max_attempts: 123
samplers:
  - name: S
    type: uniform
    objects: [cube, ball]
    x_range: [-0.3, 0.2]
    y_range: [-0.1, 0.4]
    rotation: 0.5
    rotation_axis: y
    ensure_object_boundary_in_range: false
    ensure_valid_placement: false
    reference_pos: [1, 2, 3]
    z_offset: 0.01
    sample_args: {reference: table, on_top: false}
  - name: T
    max_attempts: 7
)");
  const UniformRandomSampler& s = uniformNamed(*config, "S");
  const UniformSamplerParams& p = s.params();
  EXPECT_EQ(p.xRange, Eigen::Vector2d(-0.3, 0.2));
  EXPECT_EQ(p.yRange, Eigen::Vector2d(-0.1, 0.4));
  EXPECT_EQ(p.rotation.kind, RotationSpec::Kind::Fixed);
  EXPECT_EQ(p.rotation.low, 0.5);
  EXPECT_EQ(p.rotationAxis, 1);
  EXPECT_FALSE(p.ensureObjectBoundaryInRange);
  EXPECT_FALSE(p.ensureValidPlacement);
  EXPECT_EQ(p.referencePos, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(p.zOffset, 0.01);
  EXPECT_EQ(p.maxAttempts, 123u);  // the top-level default
  ASSERT_EQ(s.objects().size(), 2u);
  EXPECT_EQ(s.objects()[1]->name, "ball");
  SampleArgs args;
  config->root->find("S", &args);
  ASSERT_TRUE(args.reference.has_value());
  EXPECT_EQ(args.reference->kind, Reference::Kind::Name);
  EXPECT_EQ(args.reference->name, "table");
  EXPECT_EQ(args.onTop, std::optional<bool>(false));

  // robosuite's defaults where nothing is given; a sampler's own max_attempts wins.
  const UniformSamplerParams& t = uniformNamed(*config, "T").params();
  EXPECT_EQ(t.xRange, Eigen::Vector2d(0, 0));
  EXPECT_EQ(t.rotation.kind, RotationSpec::Kind::Full);
  EXPECT_EQ(t.rotationAxis, 2);
  EXPECT_TRUE(t.ensureObjectBoundaryInRange);
  EXPECT_TRUE(t.ensureValidPlacement);
  EXPECT_EQ(t.maxAttempts, 7u);
  config->root->find("T", &args);
  EXPECT_FALSE(args.reference.has_value());
  EXPECT_FALSE(args.onTop.has_value());
}

TEST(ConfigBuilder, IntegersAcceptedWhereRealsExpected) {
  const auto config = buildFromYaml(R"(
objects:
  block: {shape: box, size: [1, 2, 3]}
  drum: {shape: cylinder, radius: 1, length: 2, horizontal_radius: 3, bottom_offset: [0, 0, -1], top_offset: [0, 0, 1]}
  slab: {shape: box, size: [1, 1, 1], init_orientation: [0, 0, 0, 1]}
samplers:
  - name: S
    objects: [block]
    x_range: [-5, 5]
    y_range: [-5, 5]
    rotation: 1
    reference_pos: [0, 0, 1]
    z_offset: 2
    sample_args: {reference: [1, 2, 3]}
  - name: T
    rotation: [0, 3]
)");
  const ObjectModel* block = config->findObject("block");
  ASSERT_NE(block, nullptr);
  EXPECT_DOUBLE_EQ(block->topOffset.z(), 1.5);
  const ObjectModel* drum = config->findObject("drum");
  EXPECT_EQ(drum->horizontalRadius, 3.0);
  EXPECT_EQ(drum->bottomOffset.z(), -1.0);
  const UniformSamplerParams& p = uniformNamed(*config, "S").params();
  EXPECT_EQ(p.xRange, Eigen::Vector2d(-5, 5));
  EXPECT_EQ(p.rotation.low, 1.0);
  EXPECT_EQ(p.zOffset, 2.0);
  SampleArgs args;
  config->root->find("S", &args);
  EXPECT_EQ(args.reference->kind, Reference::Kind::Point);
  EXPECT_EQ(args.reference->point, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(uniformNamed(*config, "T").params().rotation.high, 3.0);
}

TEST(ConfigBuilder, RotationForms) {
  const auto config = buildFromYaml(R"(
samplers:
  - {name: Absent}
  - {name: NullRotation, rotation: null}
  - {name: TildeRotation, rotation: ~}
  - {name: Fixed, rotation: -0.25}
  - {name: Pair, rotation: [-0.5, 1.5]}
  - {name: Reversed, rotation: [1.5, -0.5]}
)");
  EXPECT_EQ(uniformNamed(*config, "Absent").params().rotation.kind, RotationSpec::Kind::Full);
  EXPECT_EQ(uniformNamed(*config, "NullRotation").params().rotation.kind, RotationSpec::Kind::Full);
  EXPECT_EQ(uniformNamed(*config, "TildeRotation").params().rotation.kind,
            RotationSpec::Kind::Full);
  const RotationSpec fixed = uniformNamed(*config, "Fixed").params().rotation;
  EXPECT_EQ(fixed.kind, RotationSpec::Kind::Fixed);
  EXPECT_EQ(fixed.low, -0.25);
  for (const char* name : {"Pair", "Reversed"}) {
    const RotationSpec r = uniformNamed(*config, name).params().rotation;
    EXPECT_EQ(r.kind, RotationSpec::Kind::Range) << name;
    EXPECT_EQ(r.low, -0.5) << name;
    EXPECT_EQ(r.high, 1.5) << name;
  }
  EXPECT_EQ(buildError("samplers:\n  - {name: S, rotation: full}\n"),
            "samplers[0].rotation: expected an angle in [rad], a pair [min, max] in [rad], or "
            "nothing for U(0, 2pi)");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, rotation: [0, 1, 2]}\n"),
            "samplers[0].rotation: expected a list of 2 numbers, got a list of 3 elements");
}

// costmap_2d's idiom: the list names the samplers in order and each one's parameters are in a
// top-level map of its name, so `rosparam set /node/TableSampler/x_range` changes one of them.
TEST(ConfigBuilder, NamedSamplersAreTheSameSamplersAsInlineOnes) {
  const std::string inlineForm = kObjects + R"(
samplers:
  - {name: PlateSampler, objects: [plate], x_range: [-0.3, 0.3], y_range: [-0.2, 0.2],
     sample_args: {reference: table}}
  - name: Nested
    type: sequential
    sample_args: {reference: plate}
    samplers:
      - {name: CupSampler, objects: [cup], ensure_valid_placement: false,
         ensure_object_boundary_in_range: false}
  - {name: TableSampler, objects: [cube, ball], x_range: [-0.4, 0.4], y_range: [-0.4, 0.4],
     rotation: [-0.5, 0.5], sample_args: {reference: table}}
)";
  const std::string namedForm = kObjects + R"(
samplers: [PlateSampler, {name: Nested, type: sequential}, TableSampler]
PlateSampler: {objects: [plate], x_range: [-0.3, 0.3], y_range: [-0.2, 0.2],
               sample_args: {reference: table}}
Nested: {sample_args: {reference: plate}, samplers: [CupSampler]}
CupSampler: {objects: [cup], ensure_valid_placement: false,
             ensure_object_boundary_in_range: false}
TableSampler: {objects: [cube, ball], x_range: [-0.4, 0.4], y_range: [-0.4, 0.4],
               rotation: [-0.5, 0.5], sample_args: {reference: table}}
)";
  const SceneGenerator inlineScenes(buildFromYaml(inlineForm));
  const SceneGenerator namedScenes(buildFromYaml(namedForm));
  const PreparedRequest a = inlineScenes.prepare(SampleRequest());
  const PreparedRequest b = namedScenes.prepare(SampleRequest());
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    const SceneResult x = inlineScenes.sampleScene(a, seed, 0);
    const SceneResult y = namedScenes.sampleScene(b, seed, 0);
    ASSERT_TRUE(x.success) << x.message;
    ASSERT_EQ(x.placements.size(), 4u);
    ASSERT_EQ(y.placements.size(), x.placements.size());
    for (std::size_t i = 0; i < x.placements.size(); ++i) {
      EXPECT_EQ(y.placements[i].name, x.placements[i].name);
      EXPECT_EQ(y.placements[i].sampler, x.placements[i].sampler);
      EXPECT_EQ(y.placements[i].position, x.placements[i].position) << "seed " << seed;
    }
  }
  const auto config = buildFromYaml(namedForm);
  EXPECT_EQ(uniformNamed(*config, "PlateSampler").params().yRange, Eigen::Vector2d(-0.2, 0.2));
}

TEST(ConfigBuilder, NamedSamplerErrorsNameThePath) {
  EXPECT_EQ(buildError(kObjects + "samplers: [TableSampler]\n"),
            "samplers[0]: sampler 'TableSampler' has no parameters: expected a map "
            "'TableSampler' at the top level of the configuration");
  EXPECT_EQ(buildError(kObjects + "samplers: [S]\nS: [1, 2]\n"),
            "S: expected the parameters of sampler 'S' (a map), got a list");
  // The keys of a named sampler's map: `name` is the map's own key.
  const std::string keys =
      " (expected one of: type, objects, x_range, y_range, rotation, rotation_axis, "
      "ensure_object_boundary_in_range, ensure_valid_placement, reference_pos, z_offset, "
      "sample_args, max_attempts, region, keep_out, strategy, resting, min_probability, "
      "allow_rolling, relations)";
  EXPECT_EQ(buildError(kObjects + "samplers: [S]\nS: {objects: [cube], x_rnage: [0, 1]}\n"),
            "S: unknown key 'x_rnage'" + keys);
  EXPECT_EQ(buildError(kObjects + "samplers: [S]\nS: {name: S}\n"), "S: unknown key 'name'" + keys);
  EXPECT_EQ(buildError(kObjects + "samplers: [{name: S, type: uniform}]\nS: {type: uniform}\n"),
            "S.type: the type of sampler 'S' is also given in its list item; give it once");
  EXPECT_EQ(buildError(kObjects + "samplers: [hide]\n"),
            "samplers[0]: sampler name 'hide' is a top-level key of the configuration; choose "
            "another name");
  EXPECT_EQ(buildError(kObjects + "samplers: [S, S]\nS: {objects: []}\n"),
            "samplers[1]: sampler name 'S' is already used by another sampler");
  EXPECT_EQ(buildError(kObjects + "samplers: [3]\n"),
            "samplers[0]: expected a sampler: a map of its parameters, or its name with the "
            "parameters in a top-level map of that name");
  // A top-level map no list names is still a typo.
  EXPECT_EQ(
      buildError(kObjects + "samplers: [S]\nS: {objects: []}\nT: {objects: []}\n").substr(0, 32),
      "configuration: unknown key 'T' (");
}

TEST(ConfigBuilder, UnknownKeysNameThePath) {
  EXPECT_EQ(buildError("sed: 3\n"),
            "configuration: unknown key 'sed' (expected one of: frame_id, tf_prefix, seed, "
            "collision_check, collision_margin, max_attempts, objects, fixtures, samplers, hide, "
            "threads, max_scenes_per_request, max_request_seconds, max_fixtures_per_request, "
            "max_placements_per_request, tf_static, tf_rate, physics, physics_seconds, "
            "physics_timestep, physics_position_tolerance, physics_rotation_tolerance, "
            "physics_retry, physics_max_draws, physics_max_memory_mb, ground_z, density)");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, x_rnage: [0, 1]}\n"),
            "samplers[0]: unknown key 'x_rnage' (expected one of: name, type, objects, x_range, "
            "y_range, rotation, rotation_axis, ensure_object_boundary_in_range, "
            "ensure_valid_placement, reference_pos, z_offset, sample_args, max_attempts, region, "
            "keep_out, strategy, resting, min_probability, allow_rolling, relations)");
  EXPECT_EQ(buildError("objects:\n  cube: {shape: box, size: [1, 1, 1], radius: 1}\n"),
            "objects.cube: unknown key 'radius' (expected one of: shape, size, horizontal_radius, "
            "bottom_offset, top_offset, init_orientation, density)");
  EXPECT_EQ(
      buildError("objects:\n  ball: {shape: sphere, radius: 1, length: 1}\n"),
      "objects.ball: unknown key 'length' (expected one of: shape, radius, horizontal_radius, "
      "bottom_offset, top_offset, init_orientation, density)");
  EXPECT_EQ(
      buildError(kObjects + "  - {name: desk, object: cube, pos: [0, 0, 0]}\n"),
      "fixtures[1]: unknown key 'pos' (expected one of: name, object, position, orientation)");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, sample_args: {ontop: true}}\n"),
            "samplers[0].sample_args: unknown key 'ontop' (expected one of: reference, on_top)");
  EXPECT_EQ(buildError("samplers:\n  - {name: C, type: sequential, samplers: [], objects: []}\n"),
            "samplers[0]: unknown key 'objects' (expected one of: name, type, samplers, "
            "sample_args)");
}

TEST(ConfigBuilder, DuplicateYamlKey) {
  EXPECT_EQ(buildError("samplers:\n  - {name: S, name: T}\n"), "samplers[0]: duplicate key 'name'");
}

TEST(ConfigBuilder, YamlSyntaxAndDocumentErrors) {
  const std::string syntax = buildError("samplers: [1, 2\nseed: 3\n");
  EXPECT_EQ(syntax.rfind("test.yaml: invalid YAML at line ", 0), 0u) << syntax;
  EXPECT_EQ(buildError("- a\n- b\n"), "test.yaml: the configuration must be a map of parameters");
}

// robosuite's CompositeObject (a hammer: handle and head): parts at their poses in the object
// frame; offsets and radius derived over all of them.
TEST(ConfigBuilder, CompositeObjectsDeriveTheirBoundsOverEveryPart) {
  const auto config = buildFromYaml(R"(
objects:
  hammer:
    shapes:
      - {shape: cylinder, radius: 0.015, length: 0.2, orientation: [0, 0.7071067811865476, 0, 0.7071067811865476]}
      - {shape: box, size: [0.03, 0.08, 0.04], position: [0.1, 0, 0]}
)");
  const ObjectModel& hammer = *config->findObjectPtr("hammer");
  ASSERT_EQ(hammer.shapes.size(), 2u);
  // The handle lies along x (rotated 90 degrees about y), the head sits at its end.
  EXPECT_NEAR((hammer.shapes[0].pose.linear() * Eigen::Vector3d::UnitZ()).x(), 1.0, 1e-12);
  EXPECT_EQ(hammer.shapes[1].pose.translation(), Eigen::Vector3d(0.1, 0, 0));
  // Bottom and top from the head (z +-0.02), the radius from the head's far corner.
  EXPECT_NEAR(hammer.bottomOffset.z(), -0.02, 1e-12);
  EXPECT_NEAR(hammer.topOffset.z(), 0.02, 1e-12);
  EXPECT_NEAR(hammer.horizontalRadius, std::hypot(0.115, 0.04), 1e-12);

  EXPECT_EQ(buildError("objects:\n  h: {shapes: []}\n"),
            "objects.h.shapes: expected a non-empty list of shapes, each a map with shape, its "
            "sizes, position and orientation");
  EXPECT_EQ(buildError("objects:\n  h: {shapes: [{size: [1, 1, 1]}]}\n"),
            "objects.h.shapes[0]: expected a map with the key 'shape' (box, cylinder, sphere, "
            "capsule or mesh)");
  EXPECT_EQ(buildError("objects:\n  h: {shapes: [{shape: sphere, radius: 1, init_orientation: "
                       "[0, 0, 0, 1]}]}\n"),
            "objects.h.shapes[0]: unknown key 'init_orientation' (expected one of: shape, radius, "
            "position, orientation)");
  EXPECT_EQ(buildError("objects:\n  h: {shape: sphere, radius: 1, shapes: []}\n"),
            "objects.h: give either shape or shapes (a composite object), not both");
  EXPECT_EQ(buildError("objects:\n  h: {shapes: [{shape: box, size: [1, 1, 1], orientation: "
                       "[0, 0, 0, 2]}]}\n"),
            "objects.h.shapes[0].orientation: expected a unit quaternion [x, y, z, w], got one of "
            "norm 2");
}

TEST(ConfigBuilder, ObjectShapeErrors) {
  EXPECT_EQ(buildError("objects:\n  cube: {size: [1, 1, 1]}\n"),
            "objects.cube: missing required key 'shape' (box, cylinder, sphere, capsule or mesh), "
            "or shapes, mjcf_file, urdf_file or urdf_param");
  EXPECT_EQ(buildError("objects:\n  cube: {shape: cube, size: [1, 1, 1]}\n"),
            "objects.cube.shape: expected one of box, cylinder, sphere, capsule, mesh, got 'cube'");
  EXPECT_EQ(buildError("objects:\n  cube: {shape: 3}\n"),
            "objects.cube.shape: expected a string, got an integer (3)");
  EXPECT_EQ(buildError("objects:\n  cube: [1, 2]\n"),
            "objects.cube: expected a map with the object's shape and sizes, got a list");
  EXPECT_EQ(buildError("objects:\n  ball: {shape: sphere}\n"),
            "objects.ball: missing required key 'radius'");
  EXPECT_EQ(buildError("objects:\n  cube: {shape: box, size: [1, 1]}\n"),
            "objects.cube.size: expected a list of 3 numbers, got a list of 2 elements");
  EXPECT_EQ(buildError("objects:\n  - cube\n"), "objects: expected a map, got a list of 1 element");
  EXPECT_EQ(buildError("objects:\n  \"my cube\": {shape: sphere, radius: 1}\n"),
            "objects.my cube: object names must match [A-Za-z0-9_-]+");
}

TEST(ConfigBuilder, NonPositiveSizes) {
  EXPECT_EQ(buildError("objects:\n  cube: {shape: box, size: [0.1, 0, 0.1]}\n"),
            "objects.cube.size: box size y must be finite and positive, got 0");
  EXPECT_EQ(buildError("objects:\n  can: {shape: cylinder, radius: -0.1, length: 1}\n"),
            "objects.can.radius: cylinder radius must be finite and positive, got -0.1");
  EXPECT_EQ(buildError("objects:\n  pill: {shape: capsule, radius: 0.1, length: 0}\n"),
            "objects.pill.length: capsule length must be finite and positive, got 0");
  EXPECT_EQ(buildError("objects:\n  ball: {shape: sphere, radius: 0}\n"),
            "objects.ball.radius: sphere radius must be finite and positive, got 0");
  EXPECT_EQ(buildError("objects:\n  ball: {shape: sphere, radius: 1, horizontal_radius: -1}\n"),
            "objects.ball.horizontal_radius: expected a non-negative radius in [m]");
}

TEST(ConfigBuilder, NonFiniteNumbersRejected) {
  EXPECT_EQ(buildError("samplers:\n  - {name: S, x_range: [.nan, 1]}\n"),
            "samplers[0].x_range[0]: expected a finite number, got a number (nan)");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, z_offset: .inf}\n"),
            "samplers[0].z_offset: expected a finite number, got a number (inf)");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, reference_pos: [0, -.inf, 0]}\n"),
            "samplers[0].reference_pos[1]: expected a finite number, got a number (-inf)");
  EXPECT_EQ(buildError("objects:\n  ball: {shape: sphere, radius: .NaN}\n"),
            "objects.ball.radius: expected a finite number, got a number (nan)");
  EXPECT_EQ(buildError("collision_margin: .Inf\n"),
            "collision_margin: expected a finite number, got a number (inf)");
}

TEST(ConfigBuilder, QuotedNumbersAreStrings) {
  EXPECT_EQ(buildError("samplers:\n  - {name: S, x_range: [\"1\", 2]}\n"),
            "samplers[0].x_range[0]: expected a number, got a string ('1')");
}

TEST(ConfigBuilder, InitOrientation) {
  const auto config = buildFromYaml(R"(
objects:
  lying: {shape: cylinder, radius: 0.03, length: 0.2, init_orientation: [0.7071067811865476, 0, 0, 0.7071067811865476]}
  almost: {shape: box, size: [1, 1, 1], init_orientation: [0, 0, 0, 1.0005]}
)");
  // Lying on its side: top = radius (bounds derived under the orientation).
  EXPECT_NEAR(config->findObject("lying")->topOffset.z(), 0.03, 1e-12);
  // Within 1e-3 of unit: accepted and normalized.
  EXPECT_NEAR(config->findObject("almost")->initOrientation.norm(), 1.0, 1e-15);
  EXPECT_EQ(
      buildError(
          "objects:\n  cube: {shape: box, size: [1, 1, 1], init_orientation: [0, 0, 0, 2]}\n"),
      "objects.cube.init_orientation: expected a unit quaternion [x, y, z, w], got one of "
      "norm 2");
  EXPECT_EQ(
      buildError("objects:\n  cube: {shape: box, size: [1, 1, 1], init_orientation: [0, 0, 1]}\n"),
      "objects.cube.init_orientation: expected a list of 4 numbers, got a list of 3 elements");
}

TEST(ConfigBuilder, Fixtures) {
  const auto config = buildFromYaml(kObjects + R"(
  - {name: wall, object: table_top, position: [2, 0, 0.5], orientation: [0.7071067811865476, 0, 0, 0.7071067811865476]}
)");
  ASSERT_EQ(config->fixtures.size(), 2u);
  const FixtureSpec& table = config->fixtures[0];
  EXPECT_EQ(table.name, "table");
  EXPECT_EQ(table.objectName, "table_top");
  EXPECT_EQ(table.position, Eigen::Vector3d(0, 0, 0.8));
  EXPECT_NEAR(table.object->topOffset.z(), 0.025, 1e-12);
  // The wall is the table top stood on its edge: bounds derived under its orientation.
  const FixtureSpec& wall = config->fixtures[1];
  EXPECT_NEAR(wall.object->topOffset.z(), 0.5, 1e-12);
  EXPECT_NEAR(wall.orientation.angularDistance(
                  Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitX()))),
              0.0, 1e-12);
}

TEST(ConfigBuilder, FixtureErrors) {
  EXPECT_EQ(buildError(kObjects + "  - {name: desk, object: desk_top, position: [0, 0, 0]}\n"),
            "fixtures[1].object: unknown object 'desk_top' (not under objects)");
  EXPECT_EQ(buildError(kObjects + "  - {name: cube, object: table_top, position: [0, 0, 0]}\n"),
            "fixtures[1].name: 'cube' is already the name of an object or fixture");
  EXPECT_EQ(buildError(kObjects + "  - {name: table, object: table_top, position: [0, 0, 0]}\n"),
            "fixtures[1].name: 'table' is already the name of an object or fixture");
  EXPECT_EQ(buildError(kObjects + "  - {name: my desk, object: table_top, position: [0, 0, 0]}\n"),
            "fixtures[1].name: fixture names must match [A-Za-z0-9_-]+, got 'my desk'");
  EXPECT_EQ(buildError(kObjects + "  - {name: desk, object: table_top}\n"),
            "fixtures[1]: missing required key 'position'");
  EXPECT_EQ(
      buildError(kObjects + "  - {name: desk, object: table_top, position: [0, 0, 0], orientation: "
                            "[0, 0, 0, 0.5]}\n"),
      "fixtures[1].orientation: expected a unit quaternion [x, y, z, w], got one of norm 0.5");
}

TEST(ConfigBuilder, ReversedRange) {
  EXPECT_EQ(buildError("samplers:\n  - {name: S, x_range: [0.3, -0.3]}\n"),
            "samplers[0].x_range: expected [min, max] with min <= max, got [0.3, -0.3]");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, y_range: [1, 0]}\n"),
            "samplers[0].y_range: expected [min, max] with min <= max, got [1, 0]");
}

TEST(ConfigBuilder, EmptyShrunkRegion) {
  EXPECT_EQ(
      buildError(kObjects + "samplers:\n  - {name: S, objects: [ball], x_range: [-0.04, 0.04], "
                            "y_range: [-1, 1]}\n"),
      "samplers[0].x_range: sampler 'S': x_range [-0.04, 0.04] leaves no room for object 'ball' "
      "(horizontal radius 0.05 m) with ensure_object_boundary_in_range on: the range must be "
      "at least 0.1 m wide");
  // Without the shrink the same region is fine.
  EXPECT_NO_THROW(buildFromYaml(kObjects +
                                "samplers:\n  - {name: S, objects: [ball], x_range: [-0.04, 0.04], "
                                "y_range: [-1, 1], ensure_object_boundary_in_range: false}\n"));
}

TEST(ConfigBuilder, SamplerValueErrors) {
  EXPECT_EQ(buildError("samplers:\n  - {name: S, rotation_axis: w}\n"),
            "samplers[0].rotation_axis: expected x, y or z, got 'w'");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, type: random}\n"),
            "samplers[0].type: expected uniform or sequential, got 'random'");
  EXPECT_EQ(buildError("samplers:\n  - {objects: []}\n"),
            "samplers[0]: missing required key 'name'");
  EXPECT_EQ(buildError("samplers:\n  - {name: \"\"}\n"),
            "samplers[0].name: expected a non-empty sampler name");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, ensure_valid_placement: yes}\n"),
            "samplers[0].ensure_valid_placement: expected true or false, got a string ('yes')");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, max_attempts: 0}\n"),
            "samplers[0].max_attempts: expected an integer in [1, 4294967295], got an integer (0)");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, max_attempts: 2.5}\n"),
            "samplers[0].max_attempts: expected an integer, got a number (2.5)");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, sample_args: {reference: 3}}\n"),
            "samplers[0].sample_args.reference: expected an object or fixture name, or a point "
            "[x, y, z]");
  EXPECT_EQ(buildError("samplers:\n  - {name: S, sample_args: {on_top: 1}}\n"),
            "samplers[0].sample_args.on_top: expected true or false, got an integer (1)");
  EXPECT_EQ(buildError("samplers: {name: S}\n"), "samplers: expected a list, got a map");
}

TEST(ConfigBuilder, TopLevelValueErrors) {
  EXPECT_EQ(buildError("seed: -1\n"), "seed: expected a non-negative integer, got an integer (-1)");
  EXPECT_EQ(buildError("max_attempts: 0\n"),
            "max_attempts: expected an integer in [1, 4294967295], got an integer (0)");
  EXPECT_EQ(buildError("collision_check: exact\n"),
            "collision_check: expected radius, fcl or radius_and_fcl, got 'exact'");
  EXPECT_EQ(buildError("collision_margin: -0.1\n"),
            "collision_margin: expected a finite, non-negative clearance in [m] of at most 1e+06, "
            "got -0.1");
  EXPECT_EQ(buildError("frame_id: \"\"\n"), "frame_id: expected a non-empty frame name");
}

TEST(ConfigBuilder, ServiceSettings) {
  const auto defaults = buildSceneConfig(ConfigNode::makeRoot());
  EXPECT_EQ(defaults->threads, 16u);
  EXPECT_EQ(defaults->maxScenesPerRequest, 10000u);
  EXPECT_EQ(defaults->maxRequestSeconds, 10.0);
  EXPECT_EQ(defaults->maxFixturesPerRequest, 1000u);
  EXPECT_EQ(defaults->maxPlacementsPerRequest, 1000000u);
  const auto config = buildFromYaml(
      "threads: 4\nmax_scenes_per_request: 50\nmax_request_seconds: 2\n"
      "max_fixtures_per_request: 0\nmax_placements_per_request: 7\n");
  EXPECT_EQ(config->threads, 4u);
  EXPECT_EQ(config->maxScenesPerRequest, 50u);
  EXPECT_EQ(config->maxRequestSeconds, 2.0);
  EXPECT_EQ(config->maxFixturesPerRequest, 0u);
  EXPECT_EQ(config->maxPlacementsPerRequest, 7u);
  EXPECT_EQ(buildError("max_fixtures_per_request: -1\n"),
            "max_fixtures_per_request: expected an integer in [0, 1000000], got an integer (-1)");
  EXPECT_EQ(
      buildError("max_placements_per_request: 0\n"),
      "max_placements_per_request: expected an integer in [1, 1000000000], got an integer (0)");
  EXPECT_EQ(buildError("threads: 0\n"),
            "threads: expected an integer in [1, 64], got an integer (0)");
  EXPECT_EQ(buildError("max_scenes_per_request: 0\n"),
            "max_scenes_per_request: expected an integer in [1, 100000000], got an integer (0)");
  EXPECT_EQ(buildError("max_request_seconds: 0\n"),
            "max_request_seconds: expected a positive duration in [s]");
}

TEST(ConfigBuilder, UnknownObjects) {
  EXPECT_EQ(buildError(kObjects + "samplers:\n  - {name: S, objects: [cube, cub]}\n"),
            "samplers[0].objects[1]: unknown object 'cub' (not under objects)");
  EXPECT_EQ(buildError(kObjects + "hide: [ghost]\n"),
            "hide[0]: unknown object 'ghost' (not under objects)");
}

TEST(ConfigBuilder, DuplicateObjects) {
  EXPECT_EQ(buildError(kObjects + "samplers:\n  - {name: S, objects: [cube, cube]}\n"),
            "samplers[0].objects[1]: object 'cube' is already placed by another sampler or hidden");
  EXPECT_EQ(
      buildError(kObjects +
                 "samplers:\n  - {name: S, objects: [cube], x_range: [-1, 1], y_range: [-1, 1]}\n"
                 "  - {name: T, objects: [ball, cube]}\n"),
      "samplers[1].objects[1]: object 'cube' is already placed by another sampler or hidden");
  EXPECT_EQ(
      buildError(kObjects +
                 "samplers:\n  - {name: S, objects: [cube], x_range: [-1, 1], y_range: [-1, 1]}\n"
                 "hide: [pill, cube]\n"),
      "hide[1]: object 'cube' is already placed by another sampler or hidden");
}

TEST(ConfigBuilder, DuplicateOrReservedSamplerName) {
  EXPECT_EQ(buildError("samplers:\n  - {name: S}\n  - {name: S}\n"),
            "samplers[1].name: sampler name 'S' is already used by another sampler");
  EXPECT_EQ(
      buildError("samplers:\n  - {name: root}\n"),
      "samplers[0].name: sampler name 'root' is reserved (root is the root, HideSampler places the "
      "hidden objects)");
  EXPECT_EQ(
      buildError("samplers:\n  - {name: HideSampler}\n"),
      "samplers[0].name: sampler name 'HideSampler' is reserved (root is the root, HideSampler "
      "places the hidden objects)");
  EXPECT_EQ(
      buildError(
          "samplers:\n  - {name: S}\n  - {name: C, type: sequential, samplers: [{name: S}]}\n"),
      "samplers[1].samplers[0].name: sampler name 'S' is already used by another sampler");
}

TEST(ConfigBuilder, References) {
  // A fixture and an object placed by an earlier sampler are valid references.
  const auto config = buildFromYaml(kObjects + R"(
samplers:
  - {name: PlateSampler, objects: [plate], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3], sample_args: {reference: table}}
  - {name: CupSampler, objects: [cup], sample_args: {reference: plate, on_top: true}, ensure_object_boundary_in_range: false}
)");
  SampleArgs args;
  config->root->find("CupSampler", &args);
  EXPECT_EQ(args.reference->name, "plate");
  EXPECT_EQ(args.onTop, std::optional<bool>(true));
  // An object placed later, itself, or only hidden is not.
  EXPECT_EQ(buildError(kObjects + R"(
samplers:
  - {name: CupSampler, objects: [cup], sample_args: {reference: plate}}
  - {name: PlateSampler, objects: [plate]}
)"),
            "samplers[0].sample_args.reference: reference 'plate' of sampler 'CupSampler' is "
            "neither a fixture nor an object placed by an earlier sampler");
  EXPECT_EQ(
      buildError(kObjects +
                 "samplers:\n  - {name: S, objects: [plate], sample_args: {reference: plate}}\n"),
      "samplers[0].sample_args.reference: reference 'plate' of sampler 'S' is neither a "
      "fixture nor an object placed by an earlier sampler");
  EXPECT_EQ(buildError(kObjects + "samplers:\n  - {name: S, objects: [cube], sample_args: "
                                  "{reference: pill}}\nhide: [pill]\n"),
            "samplers[0].sample_args.reference: reference 'pill' of sampler 'S' is neither a "
            "fixture nor an object placed by an earlier sampler");
  EXPECT_EQ(buildError(kObjects + "samplers:\n  - {name: S, sample_args: {reference: nowhere}}\n"),
            "samplers[0].sample_args.reference: reference 'nowhere' of sampler 'S' is neither a "
            "fixture nor an object placed by an earlier sampler");
}

TEST(ConfigBuilder, SequentialNesting) {
  const auto config = buildFromYaml(kObjects + R"(
samplers:
  - {name: PlateSampler, objects: [plate], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3]}
  - name: OnPlate
    type: sequential
    sample_args: {reference: plate, on_top: true}
    samplers:
      - {name: CupSampler, objects: [cup], ensure_object_boundary_in_range: false}
      - name: Deeper
        type: sequential
        samplers:
          - {name: BallSampler, objects: [ball], sample_args: {reference: [1, 1, 0]}, ensure_object_boundary_in_range: false}
  - {name: CubeSampler, objects: [cube], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3]}
hide: [pill]
)");
  std::vector<const PlacementSampler*> all;
  config->root->collectSamplers(all);
  std::vector<std::string> names;
  for (const PlacementSampler* s : all) {
    names.push_back(s->name());
  }
  EXPECT_EQ(names,
            (std::vector<std::string>{"root", "PlateSampler", "OnPlate", "CupSampler", "Deeper",
                                      "BallSampler", "CubeSampler", "HideSampler"}));
  std::vector<std::string> objects;
  for (const ObjectPtr& o : config->root->objects()) {
    objects.push_back(o->name);
  }
  EXPECT_EQ(objects, (std::vector<std::string>{"plate", "cup", "ball", "cube", "pill"}));
  SampleArgs args;
  ASSERT_NE(dynamic_cast<const SequentialCompositeSampler*>(config->root->find("OnPlate", &args)),
            nullptr);
  EXPECT_EQ(args.reference->name, "plate");
  // Inside a composite, the inherited reference must exist before each child too.
  EXPECT_EQ(buildError(kObjects + R"(
samplers:
  - name: OnPlate
    type: sequential
    sample_args: {reference: plate}
    samplers:
      - {name: CupSampler, objects: [cup]}
  - {name: PlateSampler, objects: [plate]}
)"),
            "samplers[0].sample_args.reference: reference 'plate' of sampler 'CupSampler' is "
            "neither a fixture nor an object placed by an earlier sampler");
  // Errors inside name their nested path.
  EXPECT_EQ(
      buildError(
          kObjects +
          "samplers:\n  - {name: C, type: sequential, samplers: [{name: S, objects: [mug]}]}\n"),
      "samplers[0].samplers[0].objects[0]: unknown object 'mug' (not under objects)");
  EXPECT_EQ(buildError("samplers:\n  - {name: C, type: sequential}\n"),
            "samplers[0]: missing required key 'samplers'");
}

TEST(ConfigBuilder, HiddenObjects) {
  const auto config = buildFromYaml(kObjects + "hide: [pill, cube]\n");
  EXPECT_EQ(config->hidden, (std::vector<std::string>{"pill", "cube"}));
  SampleArgs args;
  const PlacementSampler* hide =
      config->root->find(SequentialCompositeSampler::kHideSamplerName, &args);
  ASSERT_NE(hide, nullptr);
  EXPECT_EQ(hide->objects().size(), 2u);
}

TEST(ConfigBuilder, RosparamStylePaths) {
  // The node builds the same tree from rosparam with '/' separators: messages follow it.
  ConfigNode root = ConfigNode::makeRoot("/placement_server", '/');
  ConfigNode& samplers = root.add("samplers");
  samplers.setList();
  ConfigNode& s = samplers.append();
  s.setMap();
  s.add("name").setString("S");
  ConfigNode& range = s.add("x_range");
  range.setList();
  range.append().setDouble(1.0);
  range.append().setInt(0);
  try {
    buildSceneConfig(root);
    FAIL() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "/placement_server/samplers[0]/x_range: expected [min, max] with min <= max, got "
              "[1, 0]");
  }
}

TEST(ConfigBuilder, MissingFile) {
  try {
    loadYamlFile("/nonexistent/scene.yaml");
    FAIL() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "/nonexistent/scene.yaml: cannot read the configuration file: file not found");
  }
}

}  // namespace
}  // namespace placement_samplers
