// Bad input that must be refused before it can hurt the process: trees walked without
// recursion, inputs a library cannot survive refused first, documented limits on bytes, values,
// links, triangles and nesting, finite poses for every accepted configuration, request limits,
// escaped names, and memory returned after large batches. Large inputs are generated here.

#include <gtest/gtest.h>
#include <pthread.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/config/config_node.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/input_files.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/process/malloc_tuning.hpp"
#include "placement_samplers/geometry/mesh_loader.hpp"
#include "cli/sample_scenes_cli.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "placement_samplers/text.hpp"
#include "placement_samplers/geometry/urdf_geometry.hpp"
#include "test_helpers.hpp"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PLACEMENT_SAMPLERS_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define PLACEMENT_SAMPLERS_ASAN 1
#endif

namespace placement_samplers {
namespace {

namespace fs = std::filesystem;
using test::buildFromYaml;
using test::configError;

/// A fresh directory removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = fs::temp_directory_path() / ("placement_samplers_limits_" + std::to_string(::getpid()) +
                                         "_" + std::to_string(counter++));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string file(const std::string& name, const std::string& text) const {
    const std::string p = (path_ / name).string();
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  std::string path(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

/// Runs @p f on a thread with a stack of @p bytes: a walk that recursed per level would
/// overflow it long before the limits.
void onSmallStack(std::size_t bytes, const std::function<void()>& f) {
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, bytes);
  pthread_t thread;
  auto* task = new std::function<void()>(f);
  const int started = pthread_create(
      &thread, &attr,
      [](void* arg) -> void* {
        std::unique_ptr<std::function<void()>> t(static_cast<std::function<void()>*>(arg));
        (*t)();
        return nullptr;
      },
      task);
  pthread_attr_destroy(&attr);
  ASSERT_EQ(started, 0);
  pthread_join(thread, nullptr);
}

/// A URDF chain of @p links links, each with a 0.1 m box, 1 mm above the previous one.
std::string urdfChain(std::size_t links) {
  std::string s = "<robot name=\"chain\">\n";
  for (std::size_t i = 0; i < links; ++i) {
    s += "<link name=\"l" + std::to_string(i) +
         "\"><collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision></link>\n";
  }
  for (std::size_t i = 0; i + 1 < links; ++i) {
    s += "<joint name=\"j" + std::to_string(i) + "\" type=\"fixed\"><parent link=\"l" +
         std::to_string(i) + "\"/><child link=\"l" + std::to_string(i + 1) +
         "\"/><origin xyz=\"0 0 0.001\"/></joint>\n";
  }
  return s + "</robot>\n";
}

/// A COLLADA document: one mesh of @p triangles triangles, instanced by @p instances nodes
/// side by side, each of them inside @p depth nested nodes.
std::string collada(int triangles, int instances, int depth) {
  std::ostringstream positions;
  std::ostringstream indices;
  for (int t = 0; t < triangles; ++t) {
    positions << t << " 0 0 " << t + 1 << " 0 0 " << t << " 1 0 ";
    indices << 3 * t << " " << 3 * t + 1 << " " << 3 * t + 2 << " ";
  }
  std::string nodes;
  for (int i = 0; i < instances; ++i) {
    std::string open;
    std::string close;
    for (int d = 0; d < depth; ++d) {
      open += "<node id=\"n" + std::to_string(i) + "_" + std::to_string(d) + "\">";
      close += "</node>";
    }
    nodes += open + "<instance_geometry url=\"#g\"/>" + close + "\n";
  }
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
      << "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
      << "<asset><unit meter=\"1\"/><up_axis>Z_UP</up_axis></asset>\n"
      << "<library_geometries><geometry id=\"g\"><mesh>\n"
      << "<source id=\"p\"><float_array id=\"pa\" count=\"" << 9 * triangles << "\">"
      << positions.str() << "</float_array>\n"
      << "<technique_common><accessor source=\"#pa\" count=\"" << 3 * triangles
      << "\" stride=\"3\"><param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
      << "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
      << "<vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
      << "<triangles count=\"" << triangles << "\"><input semantic=\"VERTEX\" source=\"#v\" "
      << "offset=\"0\"/><p>" << indices.str() << "</p></triangles>\n"
      << "</mesh></geometry></library_geometries>\n"
      << "<library_visual_scenes><visual_scene id=\"s\">\n"
      << nodes << "</visual_scene></library_visual_scenes>\n"
      << "<scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n";
  return out.str();
}

double threadCpuSeconds() {
  timespec t{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

long rssKilobytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) {
      return std::stol(line.substr(6));
    }
  }
  return -1;
}

// ---- Item 1: trees walked without recursion, libraries protected -------------------------

TEST(InputLimits, UrdfChainIsWalkedWithoutRecursion) {
  // 10,000 links (the limit) on a 1 MiB stack: urdfdom itself recurses per link (about 64 bytes
  // each, 640 kB); a walk of ours that recursed per link would need more than the rest.
  const std::string chain = urdfChain(limits::kUrdfLinks);
  std::size_t shapes = 0;
  double top = 0.0;
  onSmallStack(1024 * 1024, [&] {
    MeshLoader meshes;
    const std::vector<Shape> s = urdfCollisionShapes(chain, "", meshes);
    shapes = s.size();
    top = s.back().pose.translation().z();
  });
  EXPECT_EQ(shapes, limits::kUrdfLinks);
  EXPECT_NEAR(top, 0.001 * (limits::kUrdfLinks - 1), 1e-9);
}

TEST(InputLimits, UrdfLinksBytesAndNestingAreBounded) {
  MeshLoader meshes;
  EXPECT_EQ(
      configError([&] { urdfCollisionShapes(urdfChain(limits::kUrdfLinks + 1), "", meshes); }),
      "the URDF document has 10001 links, more than the limit of 10000");
  // The chain of the adversarial run: 30,000 links, refused before any walk.
  EXPECT_EQ(configError([&] { urdfCollisionShapes(urdfChain(30000), "", meshes); }),
            "the URDF document has 30000 links, more than the limit of 10000");
  const std::string big(limits::kUrdfBytes + 1, ' ');
  EXPECT_EQ(configError([&] { urdfCollisionShapes(big, "", meshes); }),
            "the URDF document has 8388609 bytes, more than the limit of 8388608 bytes (8 MiB)");
  // tinyxml2 recurses per element: 100,000 levels overflowed the stack.
  for (int depth : {257, 100000}) {
    std::string deep = "<robot name=\"r\"><link name=\"a\"/>";
    for (int i = 2; i <= depth; ++i) {
      deep += "<x>";
    }
    for (int i = 2; i <= depth; ++i) {
      deep += "</x>";
    }
    deep += "</robot>";
    EXPECT_EQ(configError([&] { urdfCollisionShapes(deep, "", meshes); }),
              "malformed URDF: XML elements nested more than 256 levels deep")
        << depth;
  }
  // At the limit, nesting is the parser's business (here: no collision geometry).
  std::string ok = "<robot name=\"r\"><link name=\"a\"/>";
  for (int i = 2; i <= 256; ++i) {
    ok += "<x>";
  }
  for (int i = 2; i <= 256; ++i) {
    ok += "</x>";
  }
  ok += "</robot>";
  EXPECT_EQ(configError([&] { urdfCollisionShapes(ok, "", meshes); }),
            "no collision geometry in robot 'r' (1 link)");
}

TEST(InputLimits, UrdfFileIsReadWithinItsLimit) {
  const TempDir dir;
  const std::string path = dir.path("big.urdf");
  { std::ofstream(path) << std::string(limits::kUrdfBytes + 1, ' '); }
  EXPECT_EQ(configError([&] { readTextFile(path); }),
            "the file is larger than the limit of 8388608 bytes (8 MiB): it has 8388609 bytes");
  const std::string yaml = dir.file("c.yaml", "objects:\n  r: {urdf_file: big.urdf}\n");
  BuildOptions options;
  options.baseDirectory = fs::path(yaml).parent_path().string();
  EXPECT_EQ(configError([&] { buildSceneConfig(loadYamlFile(yaml), options); }),
            "objects.r.urdf_file: object 'r': urdf_file 'big.urdf' (" + path +
                "): the file is larger than the limit of 8388608 bytes (8 MiB): it has 8388609 "
                "bytes");
}

TEST(InputLimits, ColladaNestingIsCheckedBeforeAssimp) {
  const TempDir dir;
  // COLLADA, library_visual_scenes, visual_scene: 3 levels, then the nodes.
  const std::string deep = dir.file("deep.dae", collada(1, 1, 10000));
  EXPECT_EQ(configError([&] { loadMeshFile(deep, Eigen::Vector3d::Ones(), "deep.dae"); }),
            "mesh 'deep.dae' (" + deep + "): XML elements nested more than 256 levels deep");
  const std::string limit = dir.file("limit.dae", collada(1, 1, 253));
  const Mesh mesh = loadMeshFile(limit, Eigen::Vector3d::Ones(), "limit.dae");
  EXPECT_EQ(mesh.triangles.size(), 1u);
  const std::string over = dir.file("over.dae", collada(1, 1, 254));
  EXPECT_EQ(configError([&] { loadMeshFile(over, Eigen::Vector3d::Ones(), "over.dae"); }),
            "mesh 'over.dae' (" + over + "): XML elements nested more than 256 levels deep");
}

TEST(InputLimits, MeshBytesFormatsAndTrianglesAreBounded) {
  const TempDir dir;
  const std::string big = dir.path("big.stl");
  { std::ofstream(big) << "solid x\n"; }
  fs::resize_file(big, limits::kMeshBytes + 1);  // sparse: nothing is written
  EXPECT_EQ(configError([&] { loadMeshFile(big, Eigen::Vector3d::Ones(), "big.stl"); }),
            "mesh 'big.stl' (" + big +
                "): the mesh file is larger than the limit of 16777216 bytes (16 MiB): it has "
                "16777217 bytes");
  const std::string ply = dir.file("m.ply", "ply\nformat ascii 1.0\nend_header\n");
  EXPECT_EQ(configError([&] { loadMeshFile(ply, Eigen::Vector3d::Ones(), "m.ply"); }),
            "mesh 'm.ply' (" + ply +
                "): unsupported mesh format '.ply' (expected .stl, .dae or "
                ".obj)");
  // A small file that instantiates one mesh many times: every instance counts.
  const std::string many = dir.file("many.dae", collada(1000, 251, 1));
  EXPECT_EQ(configError([&] { loadMeshFile(many, Eigen::Vector3d::Ones(), "many.dae"); }),
            "mesh 'many.dae' (" + many +
                "): more than 250000 triangles (the limit of all meshes of a configuration "
                "together is 250000)");
  // The limit holds for all meshes of a build together.
  const std::string a = dir.file("a.dae", collada(1000, 200, 1));
  MeshLoader loader;
  EXPECT_EQ(loader.load(a, Eigen::Vector3d::Ones())->triangles.size(), 200000u);
  EXPECT_EQ(loader.triangleCount(), 200000u);
  EXPECT_EQ(configError([&] { loader.load(a, Eigen::Vector3d(2, 2, 2)); }),
            "mesh '" + a +
                "': more than 50000 triangles (the limit of all meshes of a "
                "configuration together is 250000)");
  EXPECT_EQ(loader.load(a, Eigen::Vector3d::Ones())->triangles.size(), 200000u);  // cached
}

// ---- Item 2: bounded reading, read errors, empty files, alias expansion, warnings --------

TEST(InputLimits, EndlessAndUnreadableConfigurationFiles) {
  for (const char* device : {"/dev/zero", "/dev/urandom"}) {
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(configError([&] { loadYamlFile(device); }),
              std::string(device) +
                  ": the configuration file is larger than the limit of 1048576 bytes (1 MiB)");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  }
  const TempDir dir;
  const std::string directory = dir.path("");
  EXPECT_EQ(configError([&] { loadYamlFile(directory); }),
            directory + ": cannot read the configuration file: it is a directory");
  EXPECT_EQ(configError([&] { loadYamlFile("/proc/self/mem"); }),
            "/proc/self/mem: cannot read the configuration file: Input/output error");
  const std::string big = dir.path("big.yaml");
  { std::ofstream(big) << "seed: 1\n" << std::string(limits::kConfigBytes, '#') << "\n"; }
  EXPECT_EQ(configError([&] { loadYamlFile(big); }),
            big +
                ": the configuration file is larger than the limit of 1048576 bytes (1 MiB): "
                "it has 1048585 bytes");
  // At the limit exactly: read.
  const std::string limit = dir.path("limit.yaml");
  {
    std::ofstream out(limit);
    out << "seed: 1\n#" << std::string(limits::kConfigBytes - 10, 'x') << "\n";
  }
  ASSERT_EQ(fs::file_size(limit), limits::kConfigBytes);
  EXPECT_EQ(loadYamlFile(limit).at("seed").asUInt64(), 1u);
}

TEST(InputLimits, ReadFileBoundedReadsAtMostOneByteBeyondTheLimit) {
  const TempDir dir;
  const std::string path = dir.file("ten", "0123456789");
  EXPECT_EQ(readFileBounded(path, 10, "the file"), "0123456789");
  EXPECT_EQ(configError([&] { readFileBounded(path, 9, "the file"); }),
            "the file is larger than the limit of 9 bytes: it has 10 bytes");
  // A pipe has no size: the limit is found by reading.
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const std::string chunk(2000, 'y');  // within the pipe's buffer
  ASSERT_EQ(::write(fds[1], chunk.data(), chunk.size()), 2000);
  ::close(fds[1]);
  const std::string pipePath = "/dev/fd/" + std::to_string(fds[0]);
  EXPECT_EQ(configError([&] { readFileBounded(pipePath, 1000, "the configuration file"); }),
            "the configuration file is larger than the limit of 1000 bytes");
  ::close(fds[0]);
  EXPECT_EQ(configError([&] { readFileBounded(std::string("a\0b", 3), 10, "the file"); }),
            "cannot read the file: the path contains a NUL byte");
}

TEST(InputLimits, EmptyConfigurationIsAnError) {
  EXPECT_EQ(configError([] { parseYaml("", "e.yaml"); }),
            "e.yaml: the configuration file is empty (expected a map of parameters)");
  EXPECT_EQ(configError([] { parseYaml("# only a comment\n\n", "e.yaml"); }),
            "e.yaml: the configuration file is empty (expected a map of parameters)");
  EXPECT_EQ(configError([] { parseYaml("{}\n", "e.yaml"); }),
            "e.yaml: the configuration is an empty map (expected parameters)");
}

TEST(InputLimits, AliasesExpandWithinTheValueLimit) {
  // 342 bytes that expand to 10^9 values.
  std::string yaml = "a0: &a0 [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n";
  for (int i = 1; i <= 9; ++i) {
    const std::string prev = "*a" + std::to_string(i - 1);
    yaml += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [" + prev;
    for (int k = 1; k < 10; ++k) {
      yaml += ", " + prev;
    }
    yaml += "]\n";
  }
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(configError([&] { parseYaml(yaml, "bomb.yaml"); }),
            "bomb.yaml: more than 200000 values (maps, lists and scalars, each use of a YAML "
            "alias counted)");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
  // A tree built otherwise (rosparam) is held to the same limits by the builder.
  ConfigNode root = ConfigNode::makeRoot("/server", '/');
  ConfigNode& list = root.add("hide");
  list.setList();
  for (std::size_t i = 0; i < limits::kConfigValues; ++i) {
    list.append().setString("x");
  }
  EXPECT_EQ(configError([&] { buildSceneConfig(root); }),
            "/server: more than 200000 values (maps, lists and scalars)");
  ConfigNode deep = ConfigNode::makeRoot("/server", '/');
  ConfigNode* node = &deep.add("objects");
  for (int i = 0; i < limits::kConfigDepth; ++i) {
    node->setList();
    node = &node->append();
  }
  node->setInt(1);
  EXPECT_EQ(configError([&] { buildSceneConfig(deep); }).substr(0, 18), "/server/objects[0]");
  EXPECT_NE(configError([&] {
              buildSceneConfig(deep);
            }).find("[0]: nested too deep (more than 100 levels)"),
            std::string::npos);
}

TEST(InputLimits, LongScalarsDoNotOverflowTheStack) {
  // std::regex recursed once per character: a megabyte of digits killed the process.
  const std::string digits(900000, '1');
  EXPECT_EQ(configError([&] { buildFromYaml("seed: " + digits + "\n"); }),
            "seed: expected a non-negative integer, got a string ('" + std::string(1000, '1') +
                "... (900000 bytes)')");
  EXPECT_EQ(configError([&] { buildFromYaml("seed: 1." + digits + "\n"); }),
            "seed: expected a non-negative integer, got a number (1.11111)");
  // Each scalar form is still read as before.
  const ConfigNode n = parseYaml(
      "a: [1, +2, -3, 1., .5, 1e5, 1.E-2, -.5e+3, .e5, 1e, e5, --1, .inf, -.Inf, +.INF, .nan, "
      ".NaN, -.nan, true, False, TRUE, tRue, 0x10, 1_000]\n",
      "t.yaml");
  const auto& e = n.at("a").elements();
  const std::vector<ConfigNode::Type> expected = {
      ConfigNode::Type::Int,    ConfigNode::Type::Int,    ConfigNode::Type::Int,
      ConfigNode::Type::Double, ConfigNode::Type::Double, ConfigNode::Type::Double,
      ConfigNode::Type::Double, ConfigNode::Type::Double, ConfigNode::Type::String,
      ConfigNode::Type::String, ConfigNode::Type::String, ConfigNode::Type::String,
      ConfigNode::Type::Double, ConfigNode::Type::Double, ConfigNode::Type::Double,
      ConfigNode::Type::Double, ConfigNode::Type::Double, ConfigNode::Type::String,
      ConfigNode::Type::Bool,   ConfigNode::Type::Bool,   ConfigNode::Type::Bool,
      ConfigNode::Type::String, ConfigNode::Type::String, ConfigNode::Type::String};
  ASSERT_EQ(e.size(), expected.size());
  for (std::size_t i = 0; i < e.size(); ++i) {
    EXPECT_EQ(e[i].type(), expected[i]) << "element " << i;
  }
  EXPECT_EQ(e[7].asDouble(), -500.0);
}

TEST(InputLimits, UnplacedObjectsAreWarnedAbout) {
  const auto config = buildFromYaml(R"(
objects:
  top: {shape: box, size: [1, 1, 0.1]}
  cube: {shape: box, size: [0.04, 0.04, 0.04]}
  spare: {shape: sphere, radius: 0.02}
  ghost: {shape: sphere, radius: 0.02}
fixtures:
  - {name: table, object: top, position: [0, 0, 0]}
samplers:
  - {name: S, objects: [cube], x_range: [-0.1, 0.1], y_range: [-0.1, 0.1]}
hide: [ghost]
)");
  ASSERT_EQ(config->warnings.size(), 1u);
  EXPECT_EQ(config->warnings[0],
            "object 'spare' is placed by no sampler, not hidden and no fixture's geometry: it "
            "appears in no scene unless a request uses it for a fixture");
  const TempDir dir;
  const std::string path = dir.file("w.yaml", "objects:\n  spare: {shape: sphere, radius: 0.02}\n");
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(runSampleScenes({"--config", path, "--seed", "1"}, out, err), 0);
  EXPECT_EQ(err.str(), "sample_scenes: " + path +
                           ": warning: object 'spare' is placed by no sampler, not hidden and no "
                           "fixture's geometry: it appears in no scene unless a request uses it "
                           "for a fixture\n");
}

TEST(InputLimits, CliReadErrorsExitTwo) {
  const TempDir dir;
  const std::string empty = dir.file("empty.yaml", "");
  struct Case {
    std::string path;
    std::string message;
  };
  const std::string directory = dir.path("");
  const std::vector<Case> cases = {
      {directory, directory + ": cannot read the configuration file: it is a directory"},
      {"/proc/self/mem", "/proc/self/mem: cannot read the configuration file: Input/output error"},
      {"/dev/zero",
       "/dev/zero: the configuration file is larger than the limit of 1048576 bytes (1 MiB)"},
      {empty, empty + ": the configuration file is empty (expected a map of parameters)"},
  };
  for (const Case& c : cases) {
    std::ostringstream out;
    std::ostringstream err;
    EXPECT_EQ(runSampleScenes({"--config", c.path}, out, err), 2) << c.path;
    EXPECT_EQ(out.str(), "") << c.path;
    EXPECT_EQ(err.str(), "sample_scenes: " + c.message + "\n");
  }
}

TEST(InputLimits, CliOutOfMemoryIsAMessageNotAnAbort) {
#if defined(PLACEMENT_SAMPLERS_ASAN)
  GTEST_SKIP() << "AddressSanitizer reserves its shadow memory: no address-space limit";
#else
  // A configuration within every limit whose parsing still needs far more than the address
  // space left to the child: the CLI says so and exits 2.
  const TempDir dir;
  std::string list = "seed: [";
  while (list.size() < limits::kConfigBytes - 16) {
    list += "1,";
  }
  const std::string path = dir.file("heavy.yaml", list + "1]\n");
  const std::string errPath = dir.path("err.txt");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::ofstream errFile(errPath);
    std::ostringstream out;
    rlimit limit{};
    std::ifstream statm("/proc/self/statm");
    long pages = 0;
    statm >> pages;
    limit.rlim_cur = limit.rlim_max =
        static_cast<rlim_t>(pages) * ::sysconf(_SC_PAGESIZE) + (rlim_t{48} << 20);
    ::setrlimit(RLIMIT_AS, &limit);
    const int status = runSampleScenes({"--config", path}, out, errFile);
    errFile.flush();
    ::_exit(status);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "the child died of signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 2);
  std::ifstream in(errPath);
  std::stringstream err;
  err << in.rdbuf();
  EXPECT_EQ(err.str(), "sample_scenes: " + path + ": out of memory\n");
#endif
}

// ---- Item 3: request fixtures: near-linear checks, a limit, the clock covers preparation --

const std::string kTable = R"(
objects:
  table_top: {shape: box, size: [0.8, 0.8, 0.05]}
  cube: {shape: box, size: [0.042, 0.042, 0.042]}
fixtures:
  - {name: table, object: table_top, position: [0, 0, 0.775]}
samplers:
  - {name: S, objects: [cube], x_range: [-0.3, 0.3], y_range: [-0.3, 0.3]}
)";

std::vector<RequestFixture> boxes(std::size_t n) {
  std::vector<RequestFixture> fixtures(n);
  for (std::size_t i = 0; i < n; ++i) {
    fixtures[i].name = "f" + std::to_string(i);
    fixtures[i].shape = Shape::box(Eigen::Vector3d(0.01, 0.01, 0.01));
    fixtures[i].position = Eigen::Vector3d(5.0 + 0.02 * static_cast<double>(i % 1000),
                                           5.0 + 0.02 * static_cast<double>(i / 1000), 0.0);
  }
  return fixtures;
}

TEST(InputLimits, RequestFixturesAreLimited) {
  const SceneGenerator generator(buildFromYaml(kTable));
  SampleRequest request;
  request.fixtures = boxes(1001);
  try {
    generator.prepare(request);
    FAIL() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_STREQ(e.what(),
                 "the request has 1001 fixtures, more than max_fixtures_per_request (1000)");
  }
  request.fixtures = boxes(1000);
  const PreparedRequest prepared = generator.prepare(request);
  EXPECT_EQ(prepared.fixtures.size(), 1001u);
  const SceneGenerator none(buildFromYaml(kTable + "max_fixtures_per_request: 0\n"));
  request.fixtures = boxes(1);
  EXPECT_THROW(none.prepare(request), RequestError);
}

TEST(InputLimits, ManyRequestFixturesAreCheckedInNearLinearTime) {
  // 100,000 fixtures took 23 s with the quadratic duplicate check.
  const SceneGenerator generator(buildFromYaml(kTable + "max_fixtures_per_request: 100000\n"));
  SampleRequest request;
  request.fixtures = boxes(100000);
  // CPU time of this thread, not wall time: the machine may be busy with other work.
  const double start = threadCpuSeconds();
  const PreparedRequest prepared = generator.prepare(request);
  const double seconds = threadCpuSeconds() - start;
  EXPECT_EQ(prepared.fixtures.size(), 100001u);
  EXPECT_LT(seconds, 5.0);
  request.fixtures.back().name = "f7";
  try {
    generator.prepare(request);
    FAIL() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_STREQ(e.what(), "fixture 'f7': the name is used twice");
  }
}

TEST(InputLimits, TimeLimitCoversPreparationAndFixtures) {
  // In fcl mode 24,000 fixtures took 15 s to enter the broadphase, outside the limit.
  const SceneGenerator generator(
      buildFromYaml(kTable + "max_fixtures_per_request: 100000\ncollision_check: fcl\n"));
  SampleRequest request;
  request.fixtures = boxes(100000);
  request.maxSeconds = 0.2;
  const auto start = std::chrono::steady_clock::now();
  std::string message;
  try {
    const PreparedRequest prepared = generator.prepare(request);
    const std::vector<SceneResult> scenes = generator.sampleScenes(prepared, 1, 3);
    ASSERT_EQ(scenes.size(), 3u);
    for (const SceneResult& scene : scenes) {
      EXPECT_FALSE(scene.success);
    }
    message = scenes[0].message;
  } catch (const RequestError& e) {
    message = e.what();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 0.2 + 1.5);
  EXPECT_TRUE(message == "the request ran out of time while checking its 100000 fixtures" ||
              message ==
                  "not sampled: the request ran out of time while adding its 100001 "
                  "fixtures" ||
              message == "not sampled: the request ran out of time")
      << message;
}

// ---- Item 6: every accepted configuration yields finite poses -------------------------------

TEST(InputLimits, DerivedQuantitiesAreChecked) {
  EXPECT_EQ(configError([] { buildFromYaml("max_request_seconds: 1e10\n"); }),
            "max_request_seconds: expected a positive duration in [s] of at most 1e+06, got 1e+10");
  EXPECT_EQ(
      configError([] {
        buildFromYaml(
            "objects:\n  c: {shape: sphere, radius: 0.01}\nsamplers:\n  - {name: S, objects: [c], "
            "x_range: [-1e308, 1e308], ensure_object_boundary_in_range: false}\n");
      }),
      "samplers[0].x_range: sampler 'S': x_range must lie within [-1e+06, 1e+06] m, got "
      "[-1e+308, 1e+308]");
  EXPECT_EQ(
      configError([] { buildFromYaml("samplers:\n  - {name: S, rotation: [-1e308, 1e308]}\n"); }),
      "samplers[0].rotation: sampler 'S': rotation [-1e+308, 1e+308] is too wide: its width "
      "overflows a double");
  // A URDF whose joint origins add up beyond the limit (each one is finite).
  MeshLoader meshes;
  std::string far = "<robot name=\"r\">";
  for (int i = 0; i < 3; ++i) {
    far += "<link name=\"l" + std::to_string(i) +
           "\"><collision><geometry><sphere radius=\"1\"/></geometry></collision></link>";
  }
  far +=
      "<joint name=\"a\" type=\"fixed\"><parent link=\"l0\"/><child link=\"l1\"/>"
      "<origin xyz=\"0 0 1e308\"/></joint>"
      "<joint name=\"b\" type=\"fixed\"><parent link=\"l1\"/><child link=\"l2\"/>"
      "<origin xyz=\"0 0 1e308\"/></joint></robot>";
  const TempDir dir;
  const std::string urdf = dir.file("far.urdf", far);
  const std::string yaml = dir.file("far.yaml", "objects:\n  r: {urdf_file: far.urdf}\n");
  BuildOptions options;
  options.baseDirectory = fs::path(yaml).parent_path().string();
  const std::string error = configError([&] { buildSceneConfig(loadYamlFile(yaml), options); });
  EXPECT_EQ(error.rfind("objects.r: object 'r': its geometry (sphere 1) must lie within 1e+06 m "
                        "of its origin, got bottom ",
                        0),
            0u)
      << error;
}

TEST(InputLimits, ExtremeAcceptedConfigurationsGiveFinitePoses) {
  // Everything at its limit, and references stacked 40 deep: positions add up, stay finite.
  std::string yaml = "objects:\n";
  for (int i = 0; i < 40; ++i) {
    yaml += "  o" + std::to_string(i) +
            ": {shape: box, size: [1e6, 1e6, 1e6], top_offset: [0, 0, 1e6], "
            "bottom_offset: [0, 0, -1e6]}\n";
  }
  yaml += "samplers:\n";
  for (int i = 0; i < 40; ++i) {
    yaml += "  - {name: S" + std::to_string(i) + ", objects: [o" + std::to_string(i) +
            "], x_range: [-1e6, 1e6], y_range: [-1e6, 1e6], reference_pos: [1e6, -1e6, 1e6], "
            "z_offset: 1e6, rotation: [-1e6, 1e6], ensure_object_boundary_in_range: false, "
            "ensure_valid_placement: false" +
            (i > 0 ? ", sample_args: {reference: o" + std::to_string(i - 1) + "}" : "") + "}\n";
  }
  const SceneGenerator generator(buildFromYaml(yaml));
  SampleRequest request;
  request.reference = Reference::at(Eigen::Vector3d(1e6, 1e6, -1e6));
  const PreparedRequest prepared = generator.prepare(request);
  for (const SceneResult& scene : generator.sampleScenes(prepared, 7, 50)) {
    ASSERT_TRUE(scene.success) << scene.message;
    for (const ObjectPlacement& p : scene.placements) {
      EXPECT_TRUE(p.position.allFinite()) << p.name;
      EXPECT_TRUE(p.orientation.coeffs().allFinite()) << p.name;
    }
  }
}

TEST(InputLimits, RequestPositionsAreBounded) {
  const SceneGenerator generator(buildFromYaml(kTable));
  SampleRequest request;
  request.reference = Reference::at(Eigen::Vector3d(0, 1e300, 0));
  try {
    generator.prepare(request);
    FAIL() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_STREQ(e.what(), "reference_point must be finite and within [-1e+06, 1e+06] m");
  }
  request = SampleRequest();
  request.fixtures = boxes(1);
  request.fixtures[0].position.z() = -2e6;
  try {
    generator.prepare(request);
    FAIL() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_STREQ(e.what(), "fixture 'f0': position must be finite and within [-1e+06, 1e+06] m");
  }
  request.fixtures = boxes(1);
  request.fixtures[0].shape = Shape::box(Eigen::Vector3d(1e300, 1, 1));
  try {
    generator.prepare(request);
    FAIL() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_STREQ(e.what(), "fixture 'f0': box size x must be at most 1e+06 m, got 1e+300");
  }
  request = SampleRequest();
  request.maxSeconds = 1e10;
  try {
    generator.prepare(request);
    FAIL() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_STREQ(e.what(), "the time limit must be at most 1e+06 s, got 1e+10");
  }
}

// ---- Item 7: placements per answer, memory returned after large batches ---------------------

TEST(InputLimits, PlacementsPerAnswerAreLimited) {
  std::string yaml = "objects:\n";
  std::string names;
  for (int i = 0; i < 1000; ++i) {
    yaml += "  o" + std::to_string(i) + ": {shape: sphere, radius: 0.01}\n";
    names += (i > 0 ? ", o" : "o") + std::to_string(i);
  }
  yaml += "samplers:\n  - {name: S, objects: [" + names +
          "], x_range: [-1, 1], y_range: [-1, 1], ensure_valid_placement: false}\n";
  const SceneGenerator generator(buildFromYaml(yaml));
  const PreparedRequest prepared = generator.prepare(SampleRequest());
  EXPECT_EQ(generator.placementsPerScene(prepared), 1000u);
  EXPECT_NO_THROW(generator.checkAnswerSize(prepared, 1000));
  try {
    generator.sampleScenes(prepared, 1, 1001);
    FAIL() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_STREQ(e.what(),
                 "1001 scenes of 1000 placements each exceed max_placements_per_request "
                 "(1000000): ask for at most 1000 scenes per request");
  }
  const SceneGenerator small(buildFromYaml(yaml + "max_placements_per_request: 999\n"));
  const PreparedRequest one = small.prepare(SampleRequest());
  try {
    small.checkAnswerSize(one, 1);
    FAIL() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_STREQ(e.what(),
                 "1 scene of 1000 placements exceeds max_placements_per_request (999): ask for "
                 "at most 1 scene per request");
  }
  // A service request: scenes per request first, then the answer's size.
  const SceneGenerator limited(buildFromYaml(yaml + "max_scenes_per_request: 5\n"));
  const PreparedRequest five = limited.prepare(SampleRequest());
  EXPECT_NO_THROW(limited.checkRequestSize(five, 5));
  try {
    limited.checkRequestSize(five, 6);
    FAIL() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_STREQ(e.what(), "num_scenes 6 exceeds max_scenes_per_request (5)");
  }
  try {
    small.checkRequestSize(one, 1);
    FAIL() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_NE(std::string(e.what()).find("exceeds max_placements_per_request (999)"),
              std::string::npos);
  }
  // Scene indices stay below 2^64, for any caller.
  const std::uint64_t last = std::numeric_limits<std::uint64_t>::max();
  EXPECT_NO_THROW(checkSceneRange(last, 1));
  EXPECT_NO_THROW(checkSceneRange(last, 0));
  try {
    checkSceneRange(last - 1, 3);
    FAIL() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_STREQ(e.what(),
                 "first scene 18446744073709551614 + 3 scenes: scene indices must stay below 2^64");
  }
  // Hidden objects are placements too.
  const SceneGenerator hidden(buildFromYaml(
      "objects:\n  a: {shape: sphere, radius: 0.01}\n  b: {shape: sphere, radius: 0.01}\n"
      "samplers:\n  - {name: S, objects: [a], x_range: [-1, 1], y_range: [-1, 1]}\n"
      "hide: [b]\n"));
  EXPECT_EQ(hidden.placementsPerScene(hidden.prepare(SampleRequest())), 2u);
  // The CLI writes in blocks: no answer limit there, and the same scenes.
  const TempDir dir;
  const std::string path =
      dir.file("c.yaml",
               "max_placements_per_request: 1\nobjects:\n  a: {shape: sphere, radius: 0.01}\n"
               "  b: {shape: sphere, radius: 0.01}\nsamplers:\n"
               "  - {name: S, objects: [a, b], x_range: [-1, 1], y_range: [-1, 1]}\n");
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(runSampleScenes({"--config", path, "--scenes", "5", "--seed", "3"}, out, err), 0)
      << err.str();
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 5);
}

TEST(InputLimits, FreedMemoryIsReturnedAfterLargeBatches) {
#if defined(PLACEMENT_SAMPLERS_ASAN) || !defined(__GLIBC__)
  GTEST_SKIP() << "measures glibc's allocator";
#else
  // The node's way: a service thread samples a large batch on two threads, copies it into an
  // answer of small strings while other small blocks stay allocated between them (here one in
  // a hundred scenes), and frees the rest. glibc then keeps the freed memory (617 MB of 630 MB
  // in a trial); trimAfterBatch() must leave at most kKeptFreeBytes.
  ASSERT_TRUE(keepFreedMemoryForBatches());
  std::string yaml = "max_placements_per_request: 2000000\nobjects:\n";
  std::string names;
  for (int i = 0; i < 1000; ++i) {
    yaml += "  object_number_" + std::to_string(i) + ": {shape: sphere, radius: 0.01}\n";
    names += (i > 0 ? ", object_number_" : "object_number_") + std::to_string(i);
  }
  yaml += "samplers:\n  - {name: SamplerWithALongName, objects: [" + names +
          "], x_range: [-1, 1], y_range: [-1, 1], ensure_valid_placement: false}\n";
  const SceneGenerator generator(buildFromYaml(yaml));
  struct Message {
    std::string name;
    std::string sampler;
    double pose[7];
  };
  std::vector<std::unique_ptr<std::string>> kept;
  const long before = rssKilobytes();
  long peak = 0;
  std::thread service([&] {
    const PreparedRequest prepared = generator.prepare(SampleRequest());
    std::vector<SceneResult> scenes = generator.sampleScenes(prepared, 1, 1500, 2);
    std::vector<std::vector<Message>> answer;
    for (const SceneResult& scene : scenes) {
      answer.emplace_back();
      for (const ObjectPlacement& p : scene.placements) {
        answer.back().push_back(Message{std::string(p.name), std::string(p.sampler), {}});
      }
      if (answer.size() % 100 == 0) {
        kept.push_back(std::make_unique<std::string>(100, 'k'));
      }
    }
    peak = rssKilobytes();
  });
  service.join();
  const long freed = rssKilobytes();
  EXPECT_TRUE(trimAfterBatch(1500 * 1000));
  const long after = rssKilobytes();
  std::cout << "[ figures  ] RSS before " << before << " kB, peak " << peak << " kB, after freeing "
            << freed << " kB, after trimAfterBatch " << after << " kB\n";
  EXPECT_GT(peak - before, 256 * 1024) << "the batch must be larger than what may be kept";
  EXPECT_LE(after - before, static_cast<long>(kKeptFreeBytes >> 10));
  EXPECT_FALSE(trimAfterBatch(kTrimAfterPlacements - 1));
  EXPECT_FALSE(trimAfterInput(kTrimAfterInputBytes - 1));
  EXPECT_TRUE(trimAfterInput(kTrimAfterInputBytes));
#endif
}

// ---- Item 9: messages --------------------------------------------------------------------------

TEST(InputLimits, EscapeText) {
  EXPECT_EQ(escapeText("cube_1"), "cube_1");
  EXPECT_EQ(escapeText(std::string("a\0b", 3)), "a\\0b");
  EXPECT_EQ(escapeText("a\nb\tc\rd\x01\x1b[31m\x7f\\"), "a\\nb\\tc\\rd\\x01\\x1b[31m\\x7f\\\\");
  EXPECT_EQ(escapeText("caf\xc3\xa9 \xe2\x82\xac"), "caf\xc3\xa9 \xe2\x82\xac");  // UTF-8 kept
  EXPECT_EQ(escapeText("\xc3(\xff\xed\xa0\x80"), "\\xc3(\\xff\\xed\\xa0\\x80");   // invalid
  EXPECT_EQ(escapeText(std::string(12, 'x'), 10), "xxxxxxxxxx... (12 bytes)");
  EXPECT_EQ(quoteText(std::string("\0", 1)), "'\\0'");
}

TEST(InputLimits, NamesWithControlCharactersAreShownEscaped) {
  EXPECT_EQ(
      configError([] { buildFromYaml("objects:\n  \"cu\\0be\": {shape: sphere, radius: 0.1}\n"); }),
      "objects.cu\\0be: object names must match [A-Za-z0-9_-]+");
  EXPECT_EQ(configError([] {
              buildFromYaml(
                  "objects:\n  cube: {shape: sphere, radius: 0.1}\n"
                  "samplers:\n  - {name: \"S\\0x\", objects: [\"cube\\e[2J\"]}\n");
            }),
            "samplers[0].objects[0]: unknown object 'cube\\x1b[2J' (not under objects)");
  EXPECT_EQ(configError([] { buildFromYaml("frame_id: \"w\\0rld\"\nsed\\0: 1\n"); }),
            "configuration: unknown key 'sed\\\\0' (expected one of: frame_id, tf_prefix, seed, "
            "collision_check, collision_margin, max_attempts, objects, fixtures, samplers, hide, "
            "threads, max_scenes_per_request, max_request_seconds, max_fixtures_per_request, "
            "max_placements_per_request, tf_static, tf_rate, physics, physics_seconds, "
            "physics_timestep, physics_position_tolerance, physics_rotation_tolerance, "
            "physics_retry, physics_max_draws, physics_max_memory_mb, ground_z, density)");
  const SceneGenerator generator(buildFromYaml(kTable));
  SampleRequest request;
  request.sampler = std::string("Shelf\0Sampler", 13);
  try {
    generator.prepare(request);
    FAIL() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_STREQ(e.what(), "unknown sampler 'Shelf\\0Sampler' (configured: root, S)");
  }
  request = SampleRequest();
  request.fixtures = boxes(1);
  request.fixtures[0].name = std::string("box\0\n", 5);
  try {
    generator.prepare(request);
    FAIL() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_STREQ(e.what(), "fixture name 'box\\0\\n' must match [A-Za-z0-9_-]+");
  }
}

TEST(InputLimits, DeepYamlSaysItIsNestedTooDeep) {
  // yaml-cpp gives up at about 500 levels with "bad file"; ours stops at 100.
  for (int depth : {150, 600, 5000}) {
    const std::string yaml = "objects: " + std::string(static_cast<std::size_t>(depth), '[') +
                             std::string(static_cast<std::size_t>(depth), ']') + "\n";
    const std::string error = configError([&] { parseYaml(yaml, "deep.yaml"); });
    EXPECT_EQ(error.rfind("deep.yaml: nested too deep at line 1, column ", 0), 0u) << error;
    EXPECT_NE(error.find(" (more than 100 levels)"), std::string::npos) << error;
  }
  std::string block;
  for (int i = 0; i < 600; ++i) {
    block += std::string(static_cast<std::size_t>(2 * i), ' ') + "k:\n";
  }
  const std::string error = configError([&] { parseYaml(block, "block.yaml"); });
  EXPECT_EQ(error.rfind("block.yaml: nested too deep at line ", 0), 0u) << error;
}

}  // namespace
}  // namespace placement_samplers
