#include "geometry/mjcf_document.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "geometry/mjcf_files.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/input_files.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers::detail {
namespace {

using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;
using tinyxml2::XMLNode;

/// The document's name in the virtual file system.
constexpr const char* kDocumentName = "placement_samplers_mjcf.xml";

/// Sections below the root that change no geometry. MuJoCo sizes its model and data by some
/// (<size> njmax, sensor dimensions, keyframes: gigabytes from a few bytes of text), and the
/// others name the joints that are left out.
constexpr std::array<std::string_view, 10> kDroppedSections = {
    "size",   "visual",   "statistic", "custom",   "keyframe",
    "tendon", "actuator", "sensor",    "equality", "contact"};

bool named(const XMLElement& e, std::string_view name) { return name == e.Name(); }

bool parentNamed(const XMLElement& e, std::string_view name) {
  const XMLNode* parent = e.Parent();
  return parent != nullptr && parent->ToElement() != nullptr && named(*parent->ToElement(), name);
}

std::string attribute(const XMLElement& e, const char* name) {
  const char* value = e.Attribute(name);
  return value == nullptr ? std::string() : std::string(value);
}

class Preparer {
 public:
  explicit Preparer(const std::string& path) : dir_(directoryOf(path)) {}

  MjcfDocument run(const std::string& text) {
    out_.vfs = makeVfs();
    parse(doc_, text);
    documentBytes_ = text.size();
    XMLElement* root = doc_.RootElement();
    if (root == nullptr || !named(*root, "mujoco")) {
      throw ConfigError("not an MJCF file: expected the root element <mujoco>");
    }
    expandIncludes(*root);
    checkDepth(*root);
    reduce(*root);
    for (XMLElement* e : files_) {
      readFile(*e);
    }
    defineMissingMaterials(*root);
    addFile(kDocumentName, printKeepingLines(doc_));
    out_.file = dir_ + kDocumentName;
    return std::move(out_);
  }

 private:
  static void parse(XMLDocument& doc, const std::string& text) {
    if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
      throw ConfigError(std::string("malformed XML: ") + escapeText(doc.ErrorStr()));
    }
  }

  /// "<mesh> 'name' (line 12)", or "(in included file 'parts.xml')".
  std::string describe(const XMLElement& e) const {
    std::string out = "<" + escapeText(e.Name()) + ">";
    if (const char* name = e.Attribute("name")) {
      out += " " + quoteText(name);
    }
    for (const XMLNode* n = &e; n != nullptr; n = n->Parent()) {
      const auto found = includedFrom_.find(n);
      if (found != includedFrom_.end()) {
        return out + " (in included file " + quoteText(found->second) + ")";
      }
    }
    return e.GetLineNum() > 0 ? out + " (line " + std::to_string(e.GetLineNum()) + ")" : out;
  }

  void addFile(const std::string& name, const std::string& data) {
    try {
      addVfsFile(*out_.vfs, name, data);
    } catch (const std::runtime_error& e) {
      throw ConfigError(e.what());
    }
  }

  /// Replaces each <include> by the elements of its file, as MuJoCo does: the path relative to
  /// the main document's directory, each file once.
  void expandIncludes(XMLElement& root) {
    std::vector<XMLElement*> stack{&root};
    while (!stack.empty()) {
      XMLElement* parent = stack.back();
      stack.pop_back();
      for (XMLElement* c = parent->FirstChildElement(); c != nullptr;) {
        if (named(*c, "include")) {
          c = include(*c);  // the first element of the file, which may be an include too
        } else {
          stack.push_back(c);
          c = c->NextSiblingElement();
        }
      }
    }
  }

  /// Puts the file's elements in place of @p include; returns the element after it now.
  XMLElement* include(XMLElement& include) {
    const std::string what = describe(include);
    const std::string file = attribute(include, "file");
    if (file.empty()) {
      throw ConfigError(what + ": no file attribute");
    }
    if (include.FirstChildElement() != nullptr) {
      throw ConfigError(what + ": an include element has no children");
    }
    const std::string path = isAbsolute(file) ? file : dir_ + file;
    const std::string label =
        what + " file " + quoteText(file) + (path != file ? " (" + escapeText(path) + ")" : "");
    if (!included_.insert(path).second) {
      throw ConfigError(label + ": the file is included twice");
    }
    std::string text;
    try {
      text = readRegularFileBounded(path, limits::kUrdfBytes, "the included file");
    } catch (const ConfigError& e) {
      throw ConfigError(label + ": " + e.what());
    }
    documentBytes_ += text.size();
    if (documentBytes_ > limits::kUrdfBytes) {
      throw ConfigError(label + ": the document and its included files are larger than the " +
                        "limit of " + std::to_string(limits::kUrdfBytes) + " bytes together");
    }
    if (xmlNestingDepth(text, limits::kXmlDepth) > limits::kXmlDepth) {
      throw ConfigError(label + ": nested more than " + std::to_string(limits::kXmlDepth) +
                        " levels deep (limit)");
    }
    XMLDocument doc;
    try {
      parse(doc, text);
    } catch (const ConfigError& e) {
      throw ConfigError(label + ": " + e.what());
    }
    const XMLElement* root = doc.RootElement();
    if (root == nullptr || !named(*root, "mujoco")) {
      throw ConfigError(label + ": expected the root element <mujoco>");
    }
    XMLNode* parent = include.Parent();
    XMLNode* last = &include;
    for (const XMLElement* c = root->FirstChildElement(); c != nullptr;
         c = c->NextSiblingElement()) {
      XMLNode* clone = c->DeepClone(&doc_);
      parent->InsertAfterChild(last, clone);
      includedFrom_[clone] = file;
      last = clone;
    }
    XMLElement* next = include.NextSiblingElement();
    parent->DeleteChild(&include);
    return next;
  }

  /// Included files nest the document further: bounded again before anything recurses on it.
  static void checkDepth(const XMLElement& root) {
    std::vector<std::pair<const XMLElement*, int>> stack{{&root, 1}};
    while (!stack.empty()) {
      const auto [e, depth] = stack.back();
      stack.pop_back();
      if (depth > limits::kXmlDepth) {
        throw ConfigError("with its included files, the document is nested more than " +
                          std::to_string(limits::kXmlDepth) + " levels deep (limit)");
      }
      for (const XMLElement* c = e->FirstChildElement(); c != nullptr;
           c = c->NextSiblingElement()) {
        stack.emplace_back(c, depth + 1);
      }
    }
  }

  /// Leaves out what changes no geometry, notes the compiler's settings, the materials and the
  /// files, and counts bodies, geoms and height field samples.
  void reduce(XMLElement& root) {
    std::vector<XMLElement*> dropped;
    for (XMLElement* c = root.FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
      if (std::find(kDroppedSections.begin(), kDroppedSections.end(), c->Name()) !=
          kDroppedSections.end()) {
        dropped.push_back(c);
      } else if (named(*c, "compiler")) {
        // The last setting counts, as in MuJoCo. fusestatic would fuse the bodies whose joints
        // are left out into their parents.
        if (c->Attribute("meshdir") != nullptr) {
          meshDir_ = attribute(*c, "meshdir");
        }
        if (c->Attribute("strippath") != nullptr) {
          stripPath_ = attribute(*c, "strippath") == "true";
        }
        c->DeleteAttribute("fusestatic");
      }
    }
    std::uint64_t bodies = 0;
    std::uint64_t geoms = 0;
    // Depth first in document order (warnings come in the file's order): element, inside
    // <default>.
    std::vector<std::pair<XMLElement*, bool>> stack;
    const auto pushChildren = [&](XMLElement& e, bool inDefault) {
      const std::size_t first = stack.size();
      for (XMLElement* c = e.FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
        if (std::find(dropped.begin(), dropped.end(), c) == dropped.end()) {
          stack.emplace_back(c, inDefault || named(*c, "default"));
        }
      }
      std::reverse(stack.begin() + static_cast<std::ptrdiff_t>(first), stack.end());
    };
    pushChildren(root, false);
    while (!stack.empty()) {
      const auto [e, inDefault] = stack.back();
      stack.pop_back();
      const bool inAsset = parentNamed(*e, "asset");
      if (inAsset && (named(*e, "texture") || named(*e, "skin"))) {
        // Textures and skins are drawn, never collided with.
        if (named(*e, "texture") && e->Attribute("name") != nullptr) {
          textures_.insert(attribute(*e, "name"));
        }
        dropped.push_back(e);
        continue;
      }
      if (!inDefault && (named(*e, "joint") || named(*e, "freejoint")) &&
          (parentNamed(*e, "body") || parentNamed(*e, "worldbody"))) {
        dropped.push_back(e);  // a joint moves nothing at the pose the geometry is read at
        continue;
      }
      if (inAsset && named(*e, "material")) {
        materials_.insert(attribute(*e, "name"));
        materialElements_.push_back(e);
      } else if (inAsset && (named(*e, "mesh") || named(*e, "hfield"))) {
        if (named(*e, "hfield")) {
          checkSamples(*e, countProduct(attribute(*e, "nrow") + " " + attribute(*e, "ncol"),
                                        limits::kHfieldSamples));
        }
        if (e->Attribute("file") != nullptr) {
          files_.push_back(e);
        }
      } else if (!inDefault && named(*e, "body")) {
        ++bodies;
      } else if (!inDefault && named(*e, "geom")) {
        ++geoms;
      } else if (!inDefault && named(*e, "composite")) {
        const std::uint64_t made = countProduct(attribute(*e, "count"), limits::kMjcfBodies);
        if (made > limits::kMjcfBodies) {
          throw ConfigError(describe(*e) + ": count makes more than " +
                            std::to_string(limits::kMjcfBodies) + " bodies (limit)");
        }
        bodies += made;
        geoms += made;
      }
      if (e->Attribute("material") != nullptr) {
        materialReferences_.push_back(attribute(*e, "material"));
      }
      pushChildren(*e, inDefault);
    }
    if (bodies > limits::kMjcfBodies) {
      throw ConfigError("it has " + std::to_string(bodies) + " bodies, more than the limit of " +
                        std::to_string(limits::kMjcfBodies));
    }
    if (geoms > limits::kMjcfGeoms) {
      throw ConfigError("it has " + std::to_string(geoms) + " geoms, more than the limit of " +
                        std::to_string(limits::kMjcfGeoms));
    }
    for (XMLElement* e : dropped) {
      includedFrom_.erase(e);
      e->Parent()->DeleteChild(e);
    }
  }

  void checkSamples(const XMLElement& e, std::uint64_t samples) const {
    if (samples > limits::kHfieldSamples) {
      throw ConfigError(describe(e) + ": more than " + std::to_string(limits::kHfieldSamples) +
                        " height samples (limit)");
    }
  }

  /// Reads the file of a <mesh> or <hfield> where MuJoCo would, into the virtual file system
  /// under a name of its own (two files may share a name in different directories).
  void readFile(XMLElement& e) {
    std::string file = attribute(e, "file");
    const std::string what = describe(e);
    if (stripPath_) {
      const std::size_t slash = file.find_last_of("/\\");
      file = slash == std::string::npos ? file : file.substr(slash + 1);
    }
    const std::string path = fullName(dir_, meshDir_, file);
    const std::string label =
        what + " file " + quoteText(file) + (path != file ? " (" + escapeText(path) + ")" : "");
    std::string& name = fileNames_[path];
    if (name.empty()) {
      if (fileNames_.size() > limits::kMjcfFiles) {
        throw ConfigError(label + ": the document names more than " +
                          std::to_string(limits::kMjcfFiles) + " files (limit)");
      }
      std::string data;
      try {
        data = readRegularFileBounded(path, limits::kMeshBytes,
                                      named(e, "mesh") ? "the mesh file" : "the height field file");
      } catch (const ConfigError& error) {
        fileNames_.erase(path);
        throw ConfigError(label + ": " + error.what());
      }
      fileBytes_ += data.size();
      if (fileBytes_ > limits::kMjcfFileBytes) {
        throw ConfigError(label + ": the files the document names are larger than the limit of " +
                          std::to_string(limits::kMjcfFileBytes) + " bytes together");
      }
      if (named(e, "hfield")) {
        checkSamples(e, heightFieldSamples(data, extensionOf(file)));
      }
      name = "placement_samplers_file" + std::to_string(fileNames_.size()) + extensionOf(file);
      addFile(name, data);
      out_.renamed.emplace_back(name, path);
    }
    e.SetAttribute("file", name.c_str());
  }

  /// Plain definitions of the materials the file names but does not define, and no textures:
  /// robosuite's files take both from the arena they are merged into.
  void defineMissingMaterials(XMLElement& root) {
    for (XMLElement* m : materialElements_) {
      const std::string texture = attribute(*m, "texture");
      if (!texture.empty() && textures_.count(texture) == 0) {
        out_.warnings.push_back("material " + quoteText(attribute(*m, "name")) + " names texture " +
                                quoteText(texture) +
                                ", which the file does not define: left out (textures change "
                                "no geometry)");
      }
      m->DeleteAttribute("texture");
    }
    XMLElement* asset = nullptr;
    for (const std::string& name : materialReferences_) {
      if (name.empty() || !materials_.insert(name).second) {
        continue;
      }
      out_.warnings.push_back("material " + quoteText(name) +
                              " is not defined in the file (robosuite's arena defines its "
                              "materials): left out (materials change no geometry)");
      if (asset == nullptr) {
        asset = doc_.NewElement("asset");
        root.InsertEndChild(asset);
      }
      XMLElement* material = doc_.NewElement("material");
      material->SetAttribute("name", name.c_str());
      asset->InsertEndChild(material);
    }
  }

  std::string dir_;
  XMLDocument doc_;
  MjcfDocument out_;
  std::size_t documentBytes_ = 0;
  std::set<std::string> included_;
  std::map<const XMLNode*, std::string> includedFrom_;
  std::string meshDir_;
  bool stripPath_ = false;
  std::set<std::string> textures_;
  std::set<std::string> materials_;
  std::vector<XMLElement*> materialElements_;
  std::vector<std::string> materialReferences_;
  std::vector<XMLElement*> files_;
  std::map<std::string, std::string> fileNames_;  ///< path -> name in the virtual file system
  std::size_t fileBytes_ = 0;
};

}  // namespace

MjcfDocument prepareMjcf(const std::string& text, const std::string& path) {
  return Preparer(path).run(text);
}

std::string MjcfDocument::originalNames(std::string message) const {
  for (const auto& [name, path] : renamed) {
    for (std::size_t at = message.find(name); at != std::string::npos;
         at = message.find(name, at)) {
      // The path MuJoCo put before the name: back to a quote or a space.
      std::size_t begin = at;
      while (begin > 0 && message[begin - 1] != '\'' && message[begin - 1] != '"' &&
             message[begin - 1] != ' ') {
        --begin;
      }
      message.replace(begin, at + name.size() - begin, path);
      at = begin + path.size();
    }
  }
  return message;
}

}  // namespace placement_samplers::detail
