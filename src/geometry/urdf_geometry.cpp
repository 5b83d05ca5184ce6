#include "placement_samplers/geometry/urdf_geometry.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <system_error>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/input_files.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace {

/// Collects urdfdom's error messages while a document is parsed: parseURDF returns only a null
/// model, the reason goes to console_bridge. Other messages go to the handler in place before.
class ErrorCapture : public console_bridge::OutputHandler {
 public:
  explicit ErrorCapture(console_bridge::OutputHandler* next) : next_(next) {}

  void log(const std::string& text, console_bridge::LogLevel level, const char* filename,
           int line) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) {
      errors_ += (errors_.empty() ? "" : "; ") + text;
    } else if (next_ != nullptr) {
      next_->log(text, level, filename, line);
    }
  }

  const std::string& errors() const { return errors_; }

 private:
  console_bridge::OutputHandler* next_;
  std::string errors_;
};

urdf::ModelInterfaceSharedPtr parse(const std::string& xml) {
  // console_bridge's handler is process-wide: one parse at a time swaps it.
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  ErrorCapture capture(console_bridge::getOutputHandler());
  console_bridge::useOutputHandler(&capture);
  urdf::ModelInterfaceSharedPtr model;
  std::string exception;
  try {
    model = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    exception = e.what();
  }
  console_bridge::restorePreviousOutputHandler();
  // urdfdom drops a collision element it cannot parse (a "nan" size, an unknown geometry) and
  // still returns a model: geometry silently missing would be worse than an error.
  if (!model || !exception.empty() || !capture.errors().empty()) {
    std::string why = !exception.empty() ? exception : capture.errors();
    if (why.empty()) {
      why = "urdfdom gave no reason";
    }
    throw ConfigError("malformed URDF: " + escapeText(why));
  }
  return model;
}

Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  double x = 0.0, y = 0.0, z = 0.0, w = 1.0;
  pose.rotation.getQuaternion(x, y, z, w);
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  t.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return t;
}

std::string vectorText(const urdf::Vector3& v) {
  std::ostringstream out;
  out << "[" << v.x << ", " << v.y << ", " << v.z << "]";
  return out.str();
}

/// The link's collision elements; urdfdom fills collision_array, older documents `collision`.
std::vector<urdf::CollisionSharedPtr> collisionsOf(const urdf::Link& link) {
  if (!link.collision_array.empty()) {
    return link.collision_array;
  }
  if (link.collision) {
    return {link.collision};
  }
  return {};
}

class ShapeCollector {
 public:
  ShapeCollector(MeshLoader& meshes, std::string meshBaseDirectory)
      : meshes_(meshes), meshBaseDirectory_(std::move(meshBaseDirectory)) {}

  void addLink(const urdf::Link& link, const Eigen::Isometry3d& linkPose) {
    const std::vector<urdf::CollisionSharedPtr> collisions = collisionsOf(link);
    for (std::size_t i = 0; i < collisions.size(); ++i) {
      const std::string where =
          "link " + quoteText(link.name) + ", collision " + std::to_string(i) +
          (collisions[i]->name.empty() ? "" : " " + quoteText(collisions[i]->name));
      if (!collisions[i]->geometry) {
        throw ConfigError(where + ": no geometry");
      }
      Shape shape = toShape(*collisions[i]->geometry, where);
      shape.pose = linkPose * toIsometry(collisions[i]->origin);
      shapes_.push_back(std::move(shape));
    }
  }

  /// @p link and every link below it, depth first with children in joint order, walked with a
  /// stack of its own: a chain of links is as deep as it is long (30,000 overflowed the stack).
  void addTree(const urdf::Link& root, const Eigen::Isometry3d& rootPose) {
    std::vector<std::pair<const urdf::Link*, Eigen::Isometry3d>> stack{{&root, rootPose}};
    std::size_t visited = 0;
    while (!stack.empty()) {
      if (++visited > children_.size()) {
        throw ConfigError("malformed URDF: the joints reach a link twice");  // urdfdom prevents it
      }
      const urdf::Link& link = *stack.back().first;
      const Eigen::Isometry3d linkPose = stack.back().second;
      stack.pop_back();
      addLink(link, linkPose);
      for (auto joint = link.child_joints.rbegin(); joint != link.child_joints.rend(); ++joint) {
        const auto it = children_.find((*joint)->child_link_name);
        if (it == children_.end() || !it->second) {
          continue;
        }
        // Zero joint values: the child frame is the joint frame, for every joint type.
        stack.emplace_back(it->second.get(),
                           linkPose * toIsometry((*joint)->parent_to_joint_origin_transform));
      }
    }
  }

  void setLinks(const std::map<std::string, urdf::LinkSharedPtr>& links) { children_ = links; }
  std::vector<Shape>& shapes() { return shapes_; }

 private:
  Shape toShape(const urdf::Geometry& geometry, const std::string& where) {
    Shape shape;
    switch (geometry.type) {
      case urdf::Geometry::BOX: {
        const urdf::Vector3& d = static_cast<const urdf::Box&>(geometry).dim;
        shape = Shape::box(Eigen::Vector3d(d.x, d.y, d.z));
        break;
      }
      case urdf::Geometry::CYLINDER: {
        const auto& c = static_cast<const urdf::Cylinder&>(geometry);
        shape = Shape::cylinder(c.radius, c.length);
        break;
      }
      case urdf::Geometry::SPHERE:
        shape = Shape::sphere(static_cast<const urdf::Sphere&>(geometry).radius);
        break;
      case urdf::Geometry::MESH: {
        const auto& m = static_cast<const urdf::Mesh&>(geometry);
        const Eigen::Vector3d scale(m.scale.x, m.scale.y, m.scale.z);
        if (!scale.allFinite() || (scale.array() <= 0.0).any()) {
          throw ConfigError(where + ": mesh scale must be three finite positive factors, got " +
                            vectorText(m.scale));
        }
        shape.type = ShapeType::Mesh;
        try {
          shape.mesh = meshes_.load(m.filename, scale, meshBaseDirectory_);
        } catch (const ConfigError& e) {
          throw ConfigError(where + ": " + e.what());
        }
        return shape;
      }
      default:
        throw ConfigError(where + ": unknown geometry type");
    }
    checkSizes(shape, where);
    return shape;
  }

  static void checkSizes(const Shape& shape, const std::string& where) {
    try {
      validateShape(shape);
    } catch (const ConfigError& e) {
      throw ConfigError(where + ": " + e.what());
    }
  }

  MeshLoader& meshes_;
  std::string meshBaseDirectory_;
  std::map<std::string, urdf::LinkSharedPtr> children_;
  std::vector<Shape> shapes_;
};

}  // namespace

std::vector<Shape> urdfCollisionShapes(const std::string& urdfXml, const std::string& link,
                                       MeshLoader& meshes, const std::string& meshBaseDirectory) {
  if (urdfXml.size() > limits::kUrdfBytes) {
    throw ConfigError("the URDF document has " + std::to_string(urdfXml.size()) +
                      " bytes, more than the limit of " + std::to_string(limits::kUrdfBytes) +
                      " bytes (" + std::to_string(limits::kUrdfBytes >> 20) + " MiB)");
  }
  // tinyxml2 recurses per element level (100,000 levels overflowed the stack).
  if (xmlNestingDepth(urdfXml, limits::kXmlDepth) > limits::kXmlDepth) {
    throw ConfigError("malformed URDF: XML elements nested more than " +
                      std::to_string(limits::kXmlDepth) + " levels deep");
  }
  const urdf::ModelInterfaceSharedPtr model = parse(urdfXml);
  if (model->links_.size() > limits::kUrdfLinks) {
    throw ConfigError("the URDF document has " + std::to_string(model->links_.size()) +
                      " links, more than the limit of " + std::to_string(limits::kUrdfLinks));
  }
  ShapeCollector collector(meshes, meshBaseDirectory);
  collector.setLinks(model->links_);
  if (link.empty()) {
    if (!model->getRoot()) {
      throw ConfigError("malformed URDF: no root link");
    }
    collector.addTree(*model->getRoot(), Eigen::Isometry3d::Identity());
    if (collector.shapes().empty()) {
      throw ConfigError("no collision geometry in robot " + quoteText(model->getName()) + " (" +
                        countText(model->links_.size(), "link") + ")");
    }
  } else {
    const urdf::LinkConstSharedPtr l = model->getLink(link);
    if (!l) {
      std::string names;
      std::size_t listed = 0;
      for (const auto& entry : model->links_) {
        if (names.size() > 2000) {
          names += ", ... (" + std::to_string(model->links_.size() - listed) + " more)";
          break;
        }
        names += (names.empty() ? "" : ", ") + escapeText(entry.first);
        ++listed;
      }
      throw ConfigError("link " + quoteText(link) + " does not exist (links: " + names + ")");
    }
    collector.addLink(*l, Eigen::Isometry3d::Identity());
    if (collector.shapes().empty()) {
      throw ConfigError("link " + quoteText(link) + " has no collision geometry");
    }
  }
  return std::move(collector.shapes());
}

std::string readTextFile(const std::string& path, std::size_t maxBytes) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) {
    throw ConfigError("file not found");
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw ConfigError("not a regular file");
  }
  return readFileBounded(path, maxBytes, "the file");
}

}  // namespace placement_samplers
