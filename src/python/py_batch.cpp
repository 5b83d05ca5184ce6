// sample_scenes(): the command-line tool's scenes (`sample_scenes --output FILE.npz`) as
// numpy arrays, sampled with the GIL released.

#include <pybind11/pybind11.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "placement_samplers/config/config_builder.hpp"
#include "placement_samplers/errors.hpp"
#include "placement_samplers/limits.hpp"
#include "placement_samplers/output/scene_arrays.hpp"
#include "placement_samplers/sampling/random.hpp"
#include "placement_samplers/sampling/scene_generator.hpp"
#include "python/numpy_support.hpp"
#include "python/py_batch.hpp"

namespace placement_samplers::python {
namespace {

/// Scenes per block, as the command-line tool: bounded working memory for the results.
constexpr std::uint64_t kBlock = 8192;
constexpr std::uint64_t kBlockPlacements = 1 << 20;

PyObject* numpyBool() {
  static PyObject* type = py::object(py::module_::import("numpy").attr("bool_")).release().ptr();
  return type;
}

/// A Python configuration (dicts, lists, strings, numbers, booleans, None) as the tree the
/// YAML reader makes.
void convert(py::handle value, ConfigNode& out, int depth, std::size_t& values) {
  if (++values > limits::kConfigValues) {
    throw ConfigError("the configuration has more than " + std::to_string(limits::kConfigValues) +
                      " values");
  }
  if (depth > limits::kConfigDepth) {
    out.fail("nested too deep (more than " + std::to_string(limits::kConfigDepth) + " levels)");
  }
  PyObject* v = value.ptr();
  if (v == Py_None) {
    out.setNull();
  } else if (PyBool_Check(v) || PyObject_IsInstance(v, numpyBool()) == 1) {
    out.setBool(PyObject_IsTrue(v) == 1);
  } else if (PyFloat_Check(v)) {
    out.setDouble(PyFloat_AS_DOUBLE(v));
  } else if (PyUnicode_Check(v)) {
    out.setString(value.cast<std::string>());
  } else if (PyIndex_Check(v)) {
    py::int_ integer = py::reinterpret_steal<py::int_>(PyNumber_Index(v));
    if (!integer) {
      throw py::error_already_set();
    }
    int overflow = 0;
    const long long i = PyLong_AsLongLongAndOverflow(integer.ptr(), &overflow);
    if (overflow != 0) {
      out.setString(py::str(integer).cast<std::string>());  // as the YAML reader: a large seed
    } else {
      out.setInt(i);
    }
  } else if (PyDict_Check(v)) {
    out.setMap();
    for (auto item : py::reinterpret_borrow<py::dict>(value)) {
      if (!PyUnicode_Check(item.first.ptr())) {
        out.fail("expected string keys, got " + py::repr(item.first).cast<std::string>());
      }
      convert(item.second, out.add(item.first.cast<std::string>()), depth + 1, values);
    }
  } else if (PyList_Check(v) || PyTuple_Check(v) || py::hasattr(value, "tolist")) {
    py::object list = PyList_Check(v) || PyTuple_Check(v)
                          ? py::reinterpret_borrow<py::object>(value)
                          : value.attr("tolist")();
    if (!PyList_Check(list.ptr()) && !PyTuple_Check(list.ptr())) {
      return convert(list, out, depth, values);  // a numpy scalar
    }
    out.setList();
    for (py::handle element : list) {
      convert(element, out.append(), depth + 1, values);
    }
  } else {
    out.fail("expected a dict, list, string, number, boolean or None, got " +
             py::repr(value).cast<std::string>());
  }
}

struct Config {
  std::shared_ptr<SceneConfig> scene;
  std::string shown;  ///< how messages name it
};

Config loadConfig(py::handle given) {
  Config config;
  BuildOptions options;
  ConfigNode tree;
  if (PyDict_Check(given.ptr())) {
    config.shown = "<dict>";
    tree = ConfigNode::makeRoot();
    std::size_t values = 0;
    convert(given, tree, 1, values);
  } else {
    const std::string path = py::module_::import("os").attr("fspath")(given).cast<std::string>();
    config.shown = path;
    tree = loadYamlFile(path);
    // Relative mesh and URDF paths are relative to the configuration file, as for the CLI.
    options.baseDirectory = std::filesystem::path(path).parent_path().string();
  }
  try {
    config.scene = buildSceneConfig(tree, options);
  } catch (const ConfigError& e) {
    throw ConfigError(config.shown + ": " + e.what());
  }
  return config;
}

/// names as NpzWriter stores them: unicode when every name is UTF-8, else bytes.
py::object namesArray(const std::vector<std::string>& names) {
  std::size_t width = 1;
  bool unicode = true;
  py::list items;
  for (const std::string& name : names) {
    PyObject* text =
        PyUnicode_DecodeUTF8(name.data(), static_cast<Py_ssize_t>(name.size()), "strict");
    if (text == nullptr) {
      PyErr_Clear();
      unicode = false;
    } else {
      width = std::max(width, static_cast<std::size_t>(PyUnicode_GET_LENGTH(text)));
      Py_DECREF(text);
    }
  }
  for (const std::string& name : names) {
    if (unicode) {
      items.append(py::str(name));
    } else {
      width = std::max(width, name.size());
      items.append(py::bytes(name));
    }
  }
  const std::string dtype = (unicode ? "<U" : "|S") + std::to_string(width);
  return py::module_::import("numpy").attr("array")(items, py::arg("dtype") = dtype);
}

}  // namespace

py::dict sampleScenes(py::object configGiven, std::uint64_t seed, std::uint64_t scenes,
                      std::uint64_t firstScene, unsigned threads) {
  const Config config = loadConfig(configGiven);
  py::module_ warnings = py::module_::import("warnings");
  for (const std::string& warning : config.scene->warnings) {
    warnings.attr("warn")(config.shown + ": " + warning);
  }
  const SceneGenerator generator(config.scene);
  SampleRequest request;
  request.maxSceneSeconds = generator.config().maxRequestSeconds;  // as the CLI
  const PreparedRequest prepared = generator.prepare(request);
  if (seed == 0) {
    seed = generator.config().seed != 0 ? generator.config().seed : randomSeed();
  }
  checkSceneRange(firstScene, scenes);
  std::vector<std::string> names;
  for (const ObjectPtr& object : prepared.sampler->objects()) {
    names.push_back(object->name);
  }
  const auto k = static_cast<std::int64_t>(scenes);
  const auto n = static_cast<std::int64_t>(names.size());
  const PhysicsMode physics = prepared.physics.mode;
  SceneArrayRows rows;
  py::dict out;
  auto add = [&](const char* key, const char* dtype, std::vector<std::int64_t> shape, void** data) {
    PyObject* array = newArray(dtype, shape, data);
    if (array == nullptr) {
      throw py::error_already_set();
    }
    out[key] = py::reinterpret_steal<py::object>(array);
  };
  out["names"] = namesArray(names);
  add("position", "float64", {k, n, 3}, reinterpret_cast<void**>(&rows.position));
  add("orientation", "float64", {k, n, 4}, reinterpret_cast<void**>(&rows.orientation));
  add("attempts", "uint32", {k, n}, reinterpret_cast<void**>(&rows.attempts));
  add("success", "bool", {k}, reinterpret_cast<void**>(&rows.success));
  add("scene", "uint64", {k}, reinterpret_cast<void**>(&rows.scene));
  std::uint64_t* seedData = nullptr;
  add("seed", "uint64", {}, reinterpret_cast<void**>(&seedData));
  *seedData = seed;
  if (physics != PhysicsMode::None) {
    add("stable", "bool", {k}, reinterpret_cast<void**>(&rows.stable));
    add("moved", "float64", {k, n}, reinterpret_cast<void**>(&rows.moved));
    add("turned", "float64", {k, n}, reinterpret_cast<void**>(&rows.turned));
    add("fallen", "bool", {k, n}, reinterpret_cast<void**>(&rows.fallen));
  }
  if (physics == PhysicsMode::Settle) {
    add("sampled_position", "float64", {k, n, 3}, reinterpret_cast<void**>(&rows.sampledPosition));
    add("sampled_orientation", "float64", {k, n, 4},
        reinterpret_cast<void**>(&rows.sampledOrientation));
  }
  if (drawsRestPoses(prepared)) {  // last, as in the .npz file
    add("rest_pose", "int16", {k, n}, reinterpret_cast<void**>(&rows.restPose));
  }
  const SceneColumns columns(names, physics);
  {
    py::gil_scoped_release release;
    const std::uint64_t perScene =
        std::max<std::uint64_t>(generator.placementsPerScene(prepared), 1);
    const std::uint64_t block = std::clamp<std::uint64_t>(kBlockPlacements / perScene, 1, kBlock);
    std::vector<SceneResult> results;
    for (std::uint64_t done = 0; done < scenes; done += block) {
      const std::uint64_t count = std::min(block, scenes - done);
      generator.sampleSceneRange(prepared, seed, firstScene + done, count, threads, results);
      const auto row = static_cast<std::size_t>(done);
      const auto cells = static_cast<std::size_t>(n) * row;
      SceneArrayRows at = rows;
      at.position += cells * 3;
      at.orientation += cells * 4;
      at.attempts += cells;
      at.success += row;
      at.scene += row;
      if (physics != PhysicsMode::None) {
        at.stable += row;
        at.moved += cells;
        at.turned += cells;
        at.fallen += cells;
      }
      if (physics == PhysicsMode::Settle) {
        at.sampledPosition += cells * 3;
        at.sampledOrientation += cells * 4;
      }
      if (rows.restPose != nullptr) {
        at.restPose += cells;
      }
      columns.fill(results, at);
    }
  }
  return out;
}

}  // namespace placement_samplers::python
