#include "placement_samplers/geometry/mjcf_geometry.hpp"

#include <mujoco/mujoco.h>

#include <cctype>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "geometry/mjcf_document.hpp"
#include "geometry/mujoco_compile.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/input_files.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace {

using detail::MujocoModelPtr;

const char* nameOf(const mjModel& m, int address) { return m.names + address; }

Eigen::Isometry3d bodyPose(const mjModel& m, int body) {
  const mjtNum* p = m.body_pos + 3 * body;
  const mjtNum* q = m.body_quat + 4 * body;  // w, x, y, z
  return Eigen::Translation3d(p[0], p[1], p[2]) *
         Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
}

/// Pose of @p body in the frame of @p top, through the chain of parents.
Eigen::Isometry3d poseInTop(const mjModel& m, int body, int top) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  while (body != top && body > 0) {
    pose = bodyPose(m, body) * pose;
    body = m.body_parentid[body];
  }
  return pose;
}

/// The body directly below the world that @p body belongs to (0 for the world itself).
int topLevelBodyOf(const mjModel& m, int body) {
  while (body > 0 && m.body_parentid[body] != 0) {
    body = m.body_parentid[body];
  }
  return body;
}

Shape meshShape(const mjModel& m, int meshId, const std::string& path, std::size_t& triangles,
                std::size_t maxTriangles) {
  const int faces = m.mesh_facenum[meshId];
  triangles += static_cast<std::size_t>(faces);
  if (triangles > maxTriangles) {
    throw ConfigError("its meshes have more than " + std::to_string(maxTriangles) +
                      " triangles (limit)");
  }
  auto mesh = std::make_shared<Mesh>();
  const int firstVertex = m.mesh_vertadr[meshId];
  const int vertices = m.mesh_vertnum[meshId];
  mesh->vertices.reserve(static_cast<std::size_t>(vertices));
  for (int v = 0; v < vertices; ++v) {
    const float* p = m.mesh_vert + 3 * (firstVertex + v);
    mesh->vertices.emplace_back(p[0], p[1], p[2]);
  }
  const int firstFace = m.mesh_faceadr[meshId];
  mesh->triangles.reserve(static_cast<std::size_t>(faces));
  for (int f = 0; f < faces; ++f) {
    const int* t = m.mesh_face + 3 * (firstFace + f);
    mesh->triangles.emplace_back(t[0], t[1], t[2]);
  }
  mesh->source =
      (path.empty() ? std::string("mjcf_param") : path) + "#" + nameOf(m, m.name_meshadr[meshId]);
  Shape shape;
  shape.type = ShapeType::Mesh;
  shape.mesh = std::move(mesh);
  return shape;
}

Eigen::Vector3d sitePos(const mjModel& m, const char* name, int top) {
  const int site = mj_name2id(&m, mjOBJ_SITE, name);
  if (site < 0) {
    throw ConfigError(std::string("no site '") + name +
                      "' (robosuite reads bottom_site, top_site and horizontal_radius_site)");
  }
  const int body = m.site_bodyid[site];
  if (topLevelBodyOf(m, body) != top) {
    throw ConfigError(std::string("site '") + name + "' is not in the top-level body");
  }
  const mjtNum* p = m.site_pos + 3 * site;
  return poseInTop(m, body, top) * Eigen::Vector3d(p[0], p[1], p[2]);
}

/// The name of the document's root element ("" when there is none): what is after the first
/// '<' that does not open a declaration, comment or processing instruction.
std::string rootElement(const std::string& text) {
  std::size_t at = 0;
  while ((at = text.find('<', at)) != std::string::npos) {
    if (text.compare(at, 4, "<!--") == 0) {
      const std::size_t end = text.find("-->", at);
      at = end == std::string::npos ? std::string::npos : end + 3;
      if (at == std::string::npos) {
        return "";
      }
      continue;
    }
    if (at + 1 < text.size() && (text[at + 1] == '?' || text[at + 1] == '!')) {
      ++at;
      continue;
    }
    std::size_t end = at + 1;
    while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) ||
                                 text[end] == '_' || text[end] == '-' || text[end] == ':')) {
      ++end;
    }
    return text.substr(at + 1, end - at - 1);
  }
  return "";
}

/// Loads @p text; @p path is its file, or "" when the text is all there is (it is then read
/// from the virtual file system).
MjcfObject loadMjcf(const std::string& text, const std::string& path, std::size_t maxTriangles);

}  // namespace

MjcfObject loadMjcfObject(const std::string& path, std::size_t maxTriangles) {
  // The same limits as a URDF file, checked before MuJoCo's parser recurses over the document.
  return loadMjcf(readRegularFileBounded(path, limits::kUrdfBytes, "the MJCF file"), path,
                  maxTriangles);
}

MjcfObject loadMjcfText(const std::string& text, std::size_t maxTriangles) {
  if (text.size() > limits::kUrdfBytes) {
    throw ConfigError("the MJCF text is larger than the limit of " +
                      std::to_string(limits::kUrdfBytes) + " bytes");
  }
  return loadMjcf(text, "", maxTriangles);
}

namespace {

MjcfObject loadMjcf(const std::string& text, const std::string& path, std::size_t maxTriangles) {
  const int depth = xmlNestingDepth(text, limits::kXmlDepth);
  if (depth > limits::kXmlDepth) {
    throw ConfigError("the MJCF file is nested more than " + std::to_string(limits::kXmlDepth) +
                      " levels deep (limit)");
  }
  // MuJoCo also reads URDF: a robosuite object is MJCF.
  const std::string root = rootElement(text);
  if (root != "mujoco") {
    throw ConfigError("not an MJCF file: its root element is " +
                      (root.empty() ? std::string("missing") : "<" + escapeText(root) + ">") +
                      ", expected <mujoco>");
  }
  // MuJoCo reads every file from here, never from the disk itself.
  const detail::MjcfDocument document = detail::prepareMjcf(text, path);
  MujocoModelPtr model;
  try {
    model = detail::compileMjcf(document.file, document.vfs.get());
  } catch (const std::runtime_error& e) {
    throw ConfigError(std::string("MuJoCo could not load it: ") +
                      escapeText(document.originalNames(e.what())));
  }
  const mjModel& m = *model;
  if (m.nbody < 2) {
    throw ConfigError("no body in its worldbody (robosuite objects have one top-level body)");
  }
  const int top = 1;  // the first body below the world
  MjcfObject out;
  out.warnings = document.warnings;
  out.bottomOffset = sitePos(m, "bottom_site", top);
  out.topOffset = sitePos(m, "top_site", top);
  // robosuite's MujocoXMLObject.horizontal_radius is the site's x coordinate alone.
  out.horizontalRadius = sitePos(m, "horizontal_radius_site", top).x();
  if (!(out.horizontalRadius >= 0.0)) {
    throw ConfigError("horizontal_radius_site has a negative x (" +
                      std::to_string(out.horizontalRadius) +
                      "); robosuite takes x as the horizontal radius");
  }

  std::size_t triangles = 0;
  for (int g = 0; g < m.ngeom; ++g) {
    const int body = m.geom_bodyid[g];
    if (topLevelBodyOf(m, body) != top) {
      continue;  // another top-level body: not this object
    }
    if (m.geom_contype[g] == 0 && m.geom_conaffinity[g] == 0) {
      ++out.visualGeoms;  // robosuite's visual geoms collide with nothing
      continue;
    }
    const mjtNum* s = m.geom_size + 3 * g;
    Shape shape;
    switch (m.geom_type[g]) {
      case mjGEOM_BOX:
        shape = Shape::box(Eigen::Vector3d(2 * s[0], 2 * s[1], 2 * s[2]));
        break;
      case mjGEOM_SPHERE:
        shape = Shape::sphere(s[0]);
        break;
      case mjGEOM_CYLINDER:
        shape = Shape::cylinder(s[0], 2 * s[1]);
        break;
      case mjGEOM_CAPSULE:
        shape = Shape::capsule(s[0], 2 * s[1]);
        break;
      case mjGEOM_MESH:
        shape = meshShape(m, m.geom_dataid[g], path, triangles, maxTriangles);
        break;
      default: {
        const char* name = nameOf(m, m.name_geomadr[g]);
        std::ostringstream why;
        why << "geom " << (name[0] != '\0' ? quoteText(name) : std::to_string(g))
            << " has a type this loader does not support (" << m.geom_type[g]
            << "); boxes, spheres, cylinders, capsules and meshes are";
        throw ConfigError(why.str());
      }
    }
    const mjtNum* p = m.geom_pos + 3 * g;
    const mjtNum* q = m.geom_quat + 4 * g;
    shape.pose = poseInTop(m, body, top) * Eigen::Translation3d(p[0], p[1], p[2]) *
                 Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
    out.shapes.push_back(std::move(shape));
  }
  if (out.shapes.empty()) {
    throw ConfigError(
        "no collision geom in its top-level body (every geom has contype and "
        "conaffinity 0)");
  }
  return out;
}

}  // namespace

}  // namespace placement_samplers
