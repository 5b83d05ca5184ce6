#include "geometry/mjcf_document.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <stdexcept>
#include <string_view>
#include <utility>

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

std::string directoryOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

bool isAbsolute(const std::string& path) { return !path.empty() && path[0] == '/'; }

/// Where MuJoCo 2.2.2 looks for @p file of a document in @p modelDir with compiler directory
/// @p dir (meshdir): an absolute file as it is, else below an absolute dir, else below both.
std::string fullName(const std::string& modelDir, std::string dir, const std::string& file) {
  if (isAbsolute(file)) {
    return file;
  }
  if (!dir.empty() && dir.back() != '/') {
    dir += '/';
  }
  return isAbsolute(dir) ? dir + file : modelDir + dir + file;
}

/// The extension of @p file with its dot ("" when none, or when implausibly long): MuJoCo
/// chooses the reader by it.
std::string extensionOf(const std::string& file) {
  const std::size_t dot = file.find_last_of('.');
  const std::size_t slash = file.find_last_of("/\\");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash) ||
      file.size() - dot > 16) {
    return "";
  }
  return file.substr(dot);
}

/// Product of the whitespace-separated numbers of @p text, each taken as at least 1 and the
/// product capped at @p cap: an upper bound of what a <composite count> makes.
std::uint64_t countProduct(const std::string& text, std::uint64_t cap) {
  std::uint64_t product = 1;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t begin = text.find_first_not_of(" \t\r\n", at);
    if (begin == std::string::npos) {
      break;
    }
    const std::size_t end = std::min(text.find_first_of(" \t\r\n", begin), text.size());
    std::uint64_t value = 0;
    for (std::size_t k = begin; k < end && value <= cap; ++k) {
      const char c = text[k];
      value = c >= '0' && c <= '9' ? value * 10 + static_cast<std::uint64_t>(c - '0') : value;
    }
    product = std::min(cap + 1, product * std::min(std::max<std::uint64_t>(value, 1), cap + 1));
    at = end;
  }
  return product;
}

std::uint32_t bigEndian32(const std::string& data, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    v = (v << 8) | static_cast<unsigned char>(data[at + k]);
  }
  return v;
}

std::int32_t littleEndian32(const std::string& data, std::size_t at) {
  std::int32_t v = 0;
  std::memcpy(&v, data.data() + at, 4);
  return v;
}

/// Samples of a height field file: a PNG's width x height, or the rows x columns of MuJoCo's
/// binary format; 0 when the header is too short (MuJoCo refuses the file).
std::uint64_t heightFieldSamples(const std::string& data, const std::string& extension) {
  std::string lower = extension;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower == ".png") {
    return data.size() < 24 ? 0 : std::uint64_t{bigEndian32(data, 16)} * bigEndian32(data, 20);
  }
  if (data.size() < 8) {
    return 0;
  }
  const std::int64_t rows = littleEndian32(data, 0);
  const std::int64_t columns = littleEndian32(data, 4);
  return rows > 0 && columns > 0 ? static_cast<std::uint64_t>(rows * columns) : 0;
}

/// Prints the document compactly, each element of the main file on its original line: MuJoCo's
/// messages ("Element 'geom', line 12") then point into the user's file.
class LinePreservingPrinter : public tinyxml2::XMLPrinter {
 public:
  LinePreservingPrinter() : XMLPrinter(nullptr, true) {}

  bool VisitEnter(const XMLElement& element, const tinyxml2::XMLAttribute* attribute) override {
    const char* text = CStr();
    const int size = CStrSize() - 1;  // without the terminating NUL
    for (; scanned_ < size; ++scanned_) {
      line_ += text[scanned_] == '\n' ? 1 : 0;
    }
    // Elements that were cloned from an included file have line 0: they stay where they are.
    for (; line_ < element.GetLineNum(); ++line_) {
      Putc('\n');  // whitespace, inside the still open tag of the parent at worst
      ++scanned_;
    }
    return XMLPrinter::VisitEnter(element, attribute);
  }

 private:
  int line_ = 1;
  int scanned_ = 0;
};

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
    LinePreservingPrinter printer;
    doc_.Print(&printer);
    addFile(kDocumentName,
            std::string(printer.CStr(), static_cast<std::size_t>(printer.CStrSize() - 1)));
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
