#include "physics/physics_mjcf.hpp"

#include <cstdio>
#include <unordered_map>

namespace placement_samplers::detail {
namespace {

/// 17 significant digits: the text reads back as the same double (the configured numbers).
void appendNumber(std::string& out, double v) {
  char buffer[32];
  const int n = std::snprintf(buffer, sizeof(buffer), "%.17g", v);
  out.append(buffer, static_cast<std::size_t>(n));
}

void appendAttribute(std::string& out, const char* name, const double* values, int count) {
  out += ' ';
  out += name;
  out += "=\"";
  for (int k = 0; k < count; ++k) {
    if (k > 0) {
      out += ' ';
    }
    appendNumber(out, values[k]);
  }
  out += '"';
}

/// Mesh asset names, one per distinct mesh (objects share their meshes).
class MeshAssets {
 public:
  const std::string& name(const Mesh* mesh, std::string& assets) {
    const auto found = names_.find(mesh);
    if (found != names_.end()) {
      return found->second;
    }
    std::string& name = names_[mesh];
    name = "mesh" + std::to_string(names_.size() - 1);
    // Vertices only: MuJoCo takes their convex hull, for collisions and for the inertia.
    assets += "    <mesh name=\"" + name + "\" vertex=\"";
    bool first = true;
    for (const Eigen::Vector3d& v : mesh->vertices) {
      for (int k = 0; k < 3; ++k) {
        if (!first) {
          assets += ' ';
        }
        first = false;
        appendNumber(assets, v[k]);
      }
    }
    assets += "\"/>\n";
    return name;
  }

 private:
  std::unordered_map<const Mesh*, std::string> names_;
};

/// One geom of @p shape at @p pose (in its body's frame); @p density < 0: static, none given.
void appendGeom(std::string& out, const Shape& shape, const Eigen::Isometry3d& pose, double density,
                MeshAssets& meshes, std::string& assets, const char* indent) {
  out += indent;
  out += "<geom";
  double size[3] = {0.0, 0.0, 0.0};
  int sizes = 1;
  switch (shape.type) {
    case ShapeType::Box:
      out += " type=\"box\"";
      for (int k = 0; k < 3; ++k) {
        size[k] = 0.5 * shape.size[k];  // MJCF takes half extents
      }
      sizes = 3;
      break;
    case ShapeType::Cylinder:
    case ShapeType::Capsule:
      out += shape.type == ShapeType::Cylinder ? " type=\"cylinder\"" : " type=\"capsule\"";
      size[0] = shape.radius;
      size[1] = 0.5 * shape.length;  // half length
      sizes = 2;
      break;
    case ShapeType::Sphere:
      out += " type=\"sphere\"";
      size[0] = shape.radius;
      break;
    case ShapeType::Mesh:
      out += " type=\"mesh\" mesh=\"" + meshes.name(shape.mesh.get(), assets) + "\"";
      sizes = 0;
      break;
  }
  if (sizes > 0) {
    appendAttribute(out, "size", size, sizes);
  }
  const Eigen::Vector3d p = pose.translation();
  const Eigen::Quaterniond q(pose.rotation());
  const double quat[4] = {q.w(), q.x(), q.y(), q.z()};
  appendAttribute(out, "pos", p.data(), 3);
  appendAttribute(out, "quat", quat, 4);
  if (density >= 0.0) {
    appendAttribute(out, "density", &density, 1);
  }
  out += "/>\n";
}

}  // namespace

std::string physicsBodyName(std::size_t index) { return "body" + std::to_string(index); }

std::string physicsMjcf(const std::vector<PhysicsFixture>& fixtures,
                        const std::vector<PhysicsBody>& bodies, const PhysicsSettings& settings,
                        const PhysicsBuffers& buffers) {
  MeshAssets meshes;
  std::string assets;
  std::string world;
  if (settings.groundZ) {
    const double pos[3] = {0.0, 0.0, *settings.groundZ};
    const double size[3] = {0.0, 0.0, 1.0};  // infinite for collisions whatever its size
    world += "    <geom type=\"plane\"";
    appendAttribute(world, "pos", pos, 3);
    appendAttribute(world, "size", size, 3);
    world += "/>\n";
  }
  for (const PhysicsFixture& f : fixtures) {
    const Eigen::Isometry3d pose = Eigen::Translation3d(f.position) * f.orientation;
    for (const Shape& shape : f.object->shapes) {
      appendGeom(world, shape, pose * shape.pose, -1.0, meshes, assets, "    ");
    }
  }
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const PhysicsBody& b = bodies[i];
    world += "    <body name=\"" + physicsBodyName(i) + "\">\n      <freejoint/>\n";
    for (const Shape& shape : b.object->shapes) {
      appendGeom(world, shape, shape.pose, b.density, meshes, assets, "      ");
    }
    world += "    </body>\n";
  }
  std::string out = "<mujoco model=\"placement_samplers_scene\">\n";
  out += "  <compiler angle=\"radian\"/>\n  <option";
  appendAttribute(out, "timestep", &settings.timestep, 1);
  // Several contact points between flat faces of convex shapes (a cylinder or a mesh on a
  // box): with one, as by default, a plate on a table rocks and rolls away.
  out += ">\n    <flag multiccd=\"enable\"/>\n  </option>\n  <size nconmax=\"" +
         std::to_string(buffers.contacts) + "\" njmax=\"" + std::to_string(buffers.rows) +
         "\" nstack=\"" + std::to_string(buffers.stack) + "\"/>\n";
  if (!assets.empty()) {
    out += "  <asset>\n" + assets + "  </asset>\n";
  }
  out += "  <worldbody>\n" + world + "  </worldbody>\n</mujoco>\n";
  return out;
}

}  // namespace placement_samplers::detail
