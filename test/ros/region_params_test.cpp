// The region handles' edits without a master: a sampler's parameters moved into the map form,
// shapes moved, turned and resized, and written back as the configuration reads them.

#include <gtest/gtest.h>

#include <XmlRpcValue.h>

#include <cmath>
#include <string>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/ros/param_reader.hpp"
#include "placement_samplers/ros/region_params.hpp"
#include "placement_samplers/sampling/uniform_random_sampler.hpp"

namespace placement_samplers {
namespace ros_interface {
namespace {

XmlRpc::XmlRpcValue pairOf(double a, double b) {
  XmlRpc::XmlRpcValue v;
  v[0] = a;
  v[1] = b;
  return v;
}

XmlRpc::XmlRpcValue names(std::initializer_list<const char*> list) {
  XmlRpc::XmlRpcValue v;
  v.setSize(0);
  for (const char* n : list) {
    v[v.size()] = std::string(n);
  }
  return v;
}

/// Objects a, b, c; samplers: A inline, B by name (its map at the top level), S an inline
/// composite holding C inline.
XmlRpc::XmlRpcValue tree() {
  XmlRpc::XmlRpcValue t;
  for (const char* name : {"a", "b", "c"}) {
    t["objects"][name]["shape"] = std::string("sphere");
    t["objects"][name]["radius"] = 0.02;
  }
  XmlRpc::XmlRpcValue a;
  a["name"] = std::string("A");
  a["objects"] = names({"a"});
  a["x_range"] = pairOf(-0.1, 0.1);
  a["y_range"] = pairOf(-0.2, 0.2);
  XmlRpc::XmlRpcValue c;
  c["name"] = std::string("C");
  c["objects"] = names({"c"});
  c["region"]["shape"] = std::string("disk");
  c["region"]["radius"] = 0.3;
  c["keep_out"][0]["shape"] = std::string("disk");
  c["keep_out"][0]["radius"] = 0.05;
  c["keep_out"][0]["frame"] = std::string("world");
  XmlRpc::XmlRpcValue s;
  s["name"] = std::string("S");
  s["type"] = std::string("sequential");
  s["samplers"][0] = c;
  t["samplers"][0] = a;
  t["samplers"][1] = std::string("B");
  t["samplers"][2] = s;
  t["B"]["objects"] = names({"b"});
  t["B"]["x_range"] = pairOf(-0.3, 0.3);
  t["B"]["y_range"] = pairOf(-0.3, 0.3);
  return t;
}

std::shared_ptr<SceneConfig> build(XmlRpc::XmlRpcValue& t) {
  return buildSceneConfig(toConfigNode(t, "/node"), BuildOptions());
}

const UniformRandomSampler& uniform(const SceneConfig& config, const std::string& name) {
  return dynamic_cast<const UniformRandomSampler&>(*config.root->find(name, nullptr));
}

TEST(RegionParams, AnInlineSamplerMovesToItsOwnMap) {
  XmlRpc::XmlRpcValue t = tree();
  XmlRpc::XmlRpcValue& a = samplerParams(t, "A");
  EXPECT_EQ(&a, &t["A"]);
  EXPECT_EQ(static_cast<std::string>(t["samplers"][0]), "A");
  EXPECT_FALSE(a.hasMember("name"));
  EXPECT_EQ(static_cast<double>(a["x_range"][0]), -0.1);
  // A second time, and a sampler already in the map form: nothing moves.
  const std::string once = t.toXml();
  EXPECT_EQ(&samplerParams(t, "A"), &t["A"]);
  EXPECT_EQ(&samplerParams(t, "B"), &t["B"]);
  EXPECT_EQ(t.toXml(), once);
  // Inside an inline composite: only the sampler moves, the composite stays inline.
  XmlRpc::XmlRpcValue& c = samplerParams(t, "C");
  EXPECT_EQ(&c, &t["C"]);
  EXPECT_EQ(static_cast<std::string>(t["samplers"][2]["samplers"][0]), "C");
  EXPECT_EQ(static_cast<std::string>(t["samplers"][2]["type"]), "sequential");
  EXPECT_FALSE(t.hasMember("S"));
  // The configuration built from the moved tree is the one built before.
  XmlRpc::XmlRpcValue original = tree();
  const auto before = build(original);
  const auto after = build(t);
  EXPECT_EQ(uniform(*after, "A").params().xRange, uniform(*before, "A").params().xRange);
  EXPECT_EQ(uniform(*after, "C").params().region->radius, 0.3);
  EXPECT_EQ(uniform(*after, "C").params().keepOut.size(), 1u);
}

TEST(RegionParams, UnknownSamplerIsAnError) {
  XmlRpc::XmlRpcValue t = tree();
  try {
    samplerParams(t, "Nope");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "no samplers list holds a sampler called 'Nope'");
  }
}

TEST(RegionParams, RangesMoveAndTurnIntoARotatedRectangle) {
  const RegionShape ranges =
      RegionShape::rectangle(Eigen::Vector2d(-0.1, 0.1), Eigen::Vector2d(-0.2, 0.2));
  const RegionShape moved = moveShape(ranges, ShapePose{Eigen::Vector2d(0.1, 0.05), 0.0});
  ASSERT_EQ(moved.kind, RegionShape::Kind::Rectangle);
  EXPECT_TRUE(moved.xRange.isApprox(Eigen::Vector2d(0.0, 0.2)));
  EXPECT_TRUE(moved.yRange.isApprox(Eigen::Vector2d(-0.15, 0.25)));

  XmlRpc::XmlRpcValue t = tree();
  HandleShape edited{moved, true, std::nullopt, false};
  writeShape(samplerParams(t, "A"), edited);
  EXPECT_NEAR(static_cast<double>(t["A"]["x_range"][1]), 0.2, 1e-12);
  EXPECT_FALSE(t["A"].hasMember("region"));

  edited.shape = moveShape(ranges, ShapePose{Eigen::Vector2d(0.1, 0.05), 0.5});
  ASSERT_EQ(edited.shape.kind, RegionShape::Kind::RotatedRectangle);
  EXPECT_TRUE(edited.shape.size.isApprox(Eigen::Vector2d(0.2, 0.4)));
  writeShape(t["A"], edited);
  EXPECT_FALSE(t["A"].hasMember("x_range"));
  EXPECT_FALSE(t["A"].hasMember("y_range"));
  EXPECT_EQ(static_cast<std::string>(t["A"]["region"]["shape"]), "rotated_rectangle");
  EXPECT_EQ(static_cast<double>(t["A"]["region"]["yaw"]), 0.5);
  const auto config = build(t);
  const UniformSamplerParams& p = uniform(*config, "A").params();
  ASSERT_TRUE(p.region);
  EXPECT_EQ(p.region->kind, RegionShape::Kind::RotatedRectangle);
  EXPECT_TRUE(p.region->centre.isApprox(Eigen::Vector2d(0.1, 0.05)));
}

TEST(RegionParams, ResizeHandles) {
  const RegionShape turned =
      RegionShape::rotatedRectangle(Eigen::Vector2d(1, 0), Eigen::Vector2d(0.2, 0.4), M_PI / 2);
  EXPECT_EQ(sizeHandles(turned), (std::vector<std::string>{"size_x", "size_y"}));
  // Its x axis points along the world's y: size_x sits 0.1 m from the centre along y.
  EXPECT_TRUE(handlePosition(turned, "size_x").isApprox(Eigen::Vector2d(1, 0.1)));
  const RegionShape wider = resizeShape(turned, "size_x", Eigen::Vector2d(1.02, 0.3));
  EXPECT_NEAR(wider.size.x(), 0.6, 1e-12);
  EXPECT_EQ(wider.size.y(), 0.4);
  EXPECT_EQ(wider.centre, turned.centre);

  const RegionShape ranges =
      RegionShape::rectangle(Eigen::Vector2d(0.0, 0.2), Eigen::Vector2d(-0.2, 0.2));
  const RegionShape narrow = resizeShape(ranges, "size_x", Eigen::Vector2d(0.15, 0.0));
  EXPECT_TRUE(narrow.xRange.isApprox(Eigen::Vector2d(0.05, 0.15)));
  EXPECT_EQ(narrow.yRange, ranges.yRange);

  const RegionShape ring = RegionShape::annulus(Eigen::Vector2d(0.5, 0.5), 0.1, 0.3);
  EXPECT_EQ(sizeHandles(ring), (std::vector<std::string>{"inner_radius", "outer_radius"}));
  EXPECT_NEAR(resizeShape(ring, "inner_radius", Eigen::Vector2d(0.5, 0.7)).innerRadius, 0.2, 1e-12);
  EXPECT_NEAR(resizeShape(ring, "outer_radius", Eigen::Vector2d(0.9, 0.5)).radius, 0.4, 1e-12);
  EXPECT_FALSE(turns(ring));
  // A disk does not turn: a turned pose only moves it.
  const RegionShape disk = RegionShape::disk(Eigen::Vector2d::Zero(), 0.2);
  const RegionShape moved = moveShape(disk, ShapePose{Eigen::Vector2d(0.1, 0), 1.0});
  EXPECT_EQ(moved.kind, RegionShape::Kind::Disk);
  EXPECT_EQ(moved.centre, Eigen::Vector2d(0.1, 0));
  EXPECT_TRUE(sizeHandles(RegionShape::polygon({{0, 0}, {1, 0}, {0, 1}})).empty());
}

TEST(RegionParams, PolygonTurnsAboutItsCentre) {
  const RegionShape square = RegionShape::polygon({{0, 0}, {2, 0}, {2, 2}, {0, 2}});
  EXPECT_TRUE(shapePose(square).centre.isApprox(Eigen::Vector2d(1, 1)));
  const RegionShape turned = moveShape(square, ShapePose{Eigen::Vector2d(3, 1), M_PI / 2});
  ASSERT_EQ(turned.vertices.size(), 4u);
  EXPECT_TRUE(turned.vertices[0].isApprox(Eigen::Vector2d(4, 0)));
  EXPECT_TRUE(turned.vertices[1].isApprox(Eigen::Vector2d(4, 2)));
  EXPECT_TRUE(turned.vertices[2].isApprox(Eigen::Vector2d(2, 2)));
}

TEST(RegionParams, KeepOutZoneKeepsItsFrame) {
  XmlRpc::XmlRpcValue t = tree();
  HandleShape zone{RegionShape::disk(Eigen::Vector2d(0.2, 0.1), 0.07), false, 0, true};
  writeShape(samplerParams(t, "C"), zone);
  XmlRpc::XmlRpcValue& written = t["C"]["keep_out"][0];
  EXPECT_EQ(static_cast<std::string>(written["frame"]), "world");
  EXPECT_EQ(static_cast<double>(written["radius"]), 0.07);
  EXPECT_EQ(static_cast<double>(written["center"][0]), 0.2);
  const auto config = build(t);
  const KeepOutZone& built = uniform(*config, "C").params().keepOut.at(0);
  EXPECT_TRUE(built.world);
  EXPECT_EQ(built.shape.radius, 0.07);
  // The region of C is a disk: a region edit replaces it.
  writeShape(t["C"], HandleShape{RegionShape::disk(Eigen::Vector2d(0, 0), 0.25), false,
                                 std::nullopt, false});
  EXPECT_EQ(static_cast<double>(t["C"]["region"]["radius"]), 0.25);
  zone.keepOut = 3;
  try {
    writeShape(t["C"], zone);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "the sampler has no keep_out zone 3");
  }
}

TEST(RegionParams, ChangedKeys) {
  XmlRpc::XmlRpcValue before = tree();
  XmlRpc::XmlRpcValue after = before;
  samplerParams(after, "A");
  EXPECT_EQ(changedKeys(before, after), (std::vector<std::string>{"A", "samplers"}));
  EXPECT_TRUE(changedKeys(before, before).empty());
}

}  // namespace
}  // namespace ros_interface
}  // namespace placement_samplers
