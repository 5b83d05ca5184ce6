#include "placement_samplers/geometry/mesh_loader.hpp"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "placement_samplers/errors.hpp"
#include "placement_samplers/input_files.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {
namespace fs = std::filesystem;

namespace {

constexpr const char* kPackageScheme = "package://";
constexpr const char* kFileScheme = "file://";

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

/// The <name> of a package.xml, or "" when it cannot be read (or is larger than a megabyte).
std::string packageName(const fs::path& packageXml) {
  std::string s;
  try {
    s = readFileBounded(packageXml.string(), std::size_t{1} << 20, "package.xml");
  } catch (const ConfigError&) {
    return "";
  }
  // The first <name>\s*([^<\s]+)\s*</name>, matched by hand: std::regex recurses per character.
  const auto space = [](char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
  };
  for (std::size_t at = s.find("<name>"); at != std::string::npos; at = s.find("<name>", at + 1)) {
    std::size_t i = at + 6;
    while (i < s.size() && space(s[i])) {
      ++i;
    }
    const std::size_t begin = i;
    while (i < s.size() && s[i] != '<' && !space(s[i])) {
      ++i;
    }
    const std::size_t end = i;
    while (i < s.size() && space(s[i])) {
      ++i;
    }
    if (end > begin && s.compare(i, 7, "</name>") == 0) {
      return s.substr(begin, end - begin);
    }
  }
  return "";
}

bool isFile(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

/// A package.xml naming @p package in @p dir or below it, down to @p depth levels. A package
/// directory is not searched further (packages do not nest), nor are hidden directories or
/// those holding a CATKIN_IGNORE, as rospack does.
std::string crawl(const fs::path& dir, const std::string& package, int depth) {
  if (isFile(dir / "CATKIN_IGNORE")) {
    return "";
  }
  if (isFile(dir / "package.xml")) {
    return packageName(dir / "package.xml") == package ? dir.string() : "";
  }
  if (depth == 0) {
    return "";
  }
  std::error_code ec;
  for (fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec), end;
       !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    std::error_code dirError;
    if (name.empty() || name[0] == '.' || !it->is_directory(dirError)) {
      continue;
    }
    const std::string found = crawl(it->path(), package, depth - 1);
    if (!found.empty()) {
      return found;
    }
  }
  return "";
}

std::string vectorText(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return out.str();
}

/// Appends the triangles of @p root and the nodes below it, in the frame of the root's parent,
/// walking the node tree with a stack of its own (depth first, children in order, as a
/// recursion would). Each instance of a mesh counts against @p maxTriangles, checked before
/// its vertices are copied: a small file that instantiates a large mesh many times stops there.
void collect(const aiScene& scene, const aiNode& root, const Eigen::Vector3d& scale,
             std::size_t maxTriangles, const std::string& where, Mesh& out) {
  std::vector<std::pair<const aiNode*, aiMatrix4x4>> stack{{&root, root.mTransformation}};
  while (!stack.empty()) {
    const aiNode& node = *stack.back().first;
    const aiMatrix4x4 transform = stack.back().second;
    stack.pop_back();
    for (unsigned m = 0; m < node.mNumMeshes; ++m) {
      const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
      if (mesh.mNumFaces > maxTriangles - out.triangles.size()) {
        throw ConfigError(where + ": more than " + std::to_string(maxTriangles) +
                          " triangles (the limit of all meshes of a configuration together is " +
                          std::to_string(limits::kMeshTriangles) + ")");
      }
      const int base = static_cast<int>(out.vertices.size());
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const aiVector3D p = transform * mesh.mVertices[v];
        out.vertices.emplace_back(p.x * scale.x(), p.y * scale.y(), p.z * scale.z());
      }
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices == 3) {  // points and lines do not collide
          out.triangles.emplace_back(base + static_cast<int>(face.mIndices[0]),
                                     base + static_cast<int>(face.mIndices[1]),
                                     base + static_cast<int>(face.mIndices[2]));
        }
      }
    }
    for (unsigned c = node.mNumChildren; c-- > 0;) {
      stack.emplace_back(node.mChildren[c], transform * node.mChildren[c]->mTransformation);
    }
  }
}

/// The file name's extension in lower case, with its dot ("" when it has none).
std::string lowerExtension(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  for (char& c : extension) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return extension;
}

}  // namespace

std::string findPackageInRosPackagePath(const std::string& package) {
  const char* env = std::getenv("ROS_PACKAGE_PATH");
  if (env == nullptr || package.empty()) {
    return "";
  }
  std::vector<fs::path> roots;
  std::stringstream list(env);
  std::string item;
  while (std::getline(list, item, ':')) {
    if (!item.empty()) {
      roots.emplace_back(item);
    }
  }
  // The cheap checks for every root first, so a deep crawl runs only on a miss.
  for (const fs::path& root : roots) {
    if (isFile(root / "package.xml") && packageName(root / "package.xml") == package) {
      return root.string();
    }
    if (isFile(root / package / "package.xml")) {
      return (root / package).string();
    }
  }
  for (const fs::path& root : roots) {
    const std::string found = crawl(root, package, 3);
    if (!found.empty()) {
      return found;
    }
  }
  return "";
}

std::string resolveUri(const std::string& uri, const PackageResolver& resolver,
                       const std::string& baseDirectory) {
  if (uri.find('\0') != std::string::npos) {
    // The system would read the path only up to it: another file.
    throw ConfigError(quoteText(uri) + ": a path cannot contain a NUL byte");
  }
  if (startsWith(uri, kPackageScheme)) {
    const std::string rest = uri.substr(std::char_traits<char>::length(kPackageScheme));
    const std::size_t slash = rest.find('/');
    const std::string package = rest.substr(0, slash);
    const std::string relative = slash == std::string::npos ? "" : rest.substr(slash + 1);
    if (package.empty() || relative.empty()) {
      throw ConfigError(quoteText(uri) + ": expected package://PACKAGE/PATH");
    }
    const std::string dir = resolver ? resolver(package) : findPackageInRosPackagePath(package);
    if (dir.empty()) {
      std::string where = "by the package resolver";
      if (!resolver) {
        const char* env = std::getenv("ROS_PACKAGE_PATH");
        where = env != nullptr ? "in ROS_PACKAGE_PATH (" + escapeText(env, std::string::npos) + ")"
                               : std::string("(ROS_PACKAGE_PATH is not set)");
      }
      throw ConfigError(quoteText(uri) + ": package " + quoteText(package) + " not found " + where);
    }
    return (fs::path(dir) / relative).lexically_normal().string();
  }
  std::string path = uri;
  if (startsWith(uri, kFileScheme)) {
    path = uri.substr(std::char_traits<char>::length(kFileScheme));
  } else if (uri.find("://") != std::string::npos) {
    throw ConfigError(quoteText(uri) +
                      ": unsupported URI scheme (use package://, file:// or a path)");
  }
  if (path.empty()) {
    throw ConfigError(quoteText(uri) + ": empty path");
  }
  fs::path p(path);
  if (p.is_relative() && !baseDirectory.empty()) {
    p = fs::path(baseDirectory) / p;
  }
  return p.lexically_normal().string();
}

Mesh loadMeshFile(const std::string& path, const Eigen::Vector3d& scale, const std::string& source,
                  std::size_t maxTriangles) {
  const std::string where =
      "mesh " + quoteText(source) + (path != source ? " (" + escapeText(path) + ")" : "");
  if (!scale.allFinite() || (scale.array() <= 0.0).any()) {
    throw ConfigError(where + ": scale must be three finite positive factors, got " +
                      vectorText(scale));
  }
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) {
    throw ConfigError(where + ": file not found");
  }
  if (!fs::is_regular_file(status)) {
    throw ConfigError(where + ": not a regular file");
  }
  // The three formats of the documentation only: assimp's other readers recurse into nested
  // input we do not check (and assimp picks the reader by the extension).
  const std::string extension = lowerExtension(path);
  if (extension != ".stl" && extension != ".dae" && extension != ".obj") {
    throw ConfigError(where + ": unsupported mesh format " + quoteText(extension) +
                      " (expected .stl, .dae or .obj)");
  }
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (ec) {
    throw ConfigError(where + ": cannot read the mesh file: " + ec.message());
  }
  if (bytes == 0) {
    throw ConfigError(where + ": the file is empty");
  }
  if (bytes > limits::kMeshBytes) {
    throw ConfigError(where + ": the mesh file is larger than the limit of " +
                      std::to_string(limits::kMeshBytes) + " bytes (" +
                      std::to_string(limits::kMeshBytes >> 20) + " MiB): it has " +
                      std::to_string(bytes) + " bytes");
  }
  // assimp's COLLADA reader recurses per <node> level (10,000 levels overflowed the stack).
  if (extension == ".dae") {
    std::string text;
    try {
      text = readFileBounded(path, limits::kMeshBytes, "the mesh file");
    } catch (const ConfigError& e) {
      throw ConfigError(where + ": " + e.what());
    }
    if (xmlNestingDepth(text, limits::kXmlDepth) > limits::kXmlDepth) {
      throw ConfigError(where + ": XML elements nested more than " +
                        std::to_string(limits::kXmlDepth) + " levels deep");
    }
  }

  Assimp::Importer importer;
  // rviz and the ROS tools keep a mesh's z axis up, whatever COLLADA's up_axis says.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Normals dropped so that STL's per-facet copies of a vertex merge into one.
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_DropNormals |
                                  aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    std::string why = importer.GetErrorString();
    throw ConfigError(where + ": cannot read it as a mesh: " +
                      (why.empty() ? std::string("unknown error") : escapeText(why)));
  }
  Mesh mesh;
  mesh.source = source;
  // The root's own transform applies as the other nodes' do (collect starts from it).
  collect(*scene, *scene->mRootNode, scale, maxTriangles, where, mesh);
  if (mesh.triangles.empty()) {
    throw ConfigError(where + ": the mesh has no triangles");
  }
  for (const Eigen::Vector3d& v : mesh.vertices) {
    if (!v.allFinite()) {
      throw ConfigError(where + ": the mesh has a non-finite vertex");
    }
  }
  return mesh;
}

MeshLoader::MeshLoader(PackageResolver resolver, std::string baseDirectory)
    : resolver_(std::move(resolver)), baseDirectory_(std::move(baseDirectory)) {}

std::string MeshLoader::resolve(const std::string& uri, const std::string& baseDirectory) const {
  return resolveUri(uri, resolver_, baseDirectory.empty() ? baseDirectory_ : baseDirectory);
}

std::shared_ptr<const Mesh> MeshLoader::load(const std::string& uri, const Eigen::Vector3d& scale,
                                             const std::string& baseDirectory) {
  const std::string path = resolve(uri, baseDirectory);
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  const Key key{ec ? path : absolute.lexically_normal().string(), scale.x(), scale.y(), scale.z()};
  const auto it = cache_.find(key);
  if (it != cache_.end()) {
    return it->second;
  }
  auto mesh = std::make_shared<const Mesh>(
      loadMeshFile(path, scale, uri, limits::kMeshTriangles - triangles_));
  triangles_ += mesh->triangles.size();
  cache_.emplace(key, mesh);
  return mesh;
}

}  // namespace placement_samplers
