// NpzWriter: the zip's structure (headers, sizes, offsets, CRC-32 of every member), the .npy
// headers, the rows as written, zip64 records, errors; and numpy reading what it wrote.

#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "placement_samplers/output/npz_writer.hpp"
#include "placement_samplers/output/scene_arrays.hpp"

namespace placement_samplers {
namespace {

std::string tempPath(const std::string& name) {
  return ::testing::TempDir() + "npz_writer_test_" + std::to_string(::getpid()) + "_" + name;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::uint64_t le(const std::string& bytes, std::uint64_t at, int size) {
  std::uint64_t v = 0;
  for (int k = size - 1; k >= 0; --k) {
    v = (v << 8) | static_cast<unsigned char>(bytes.at(at + k));
  }
  return v;
}

/// One member as its central directory entry and local header describe it.
struct Entry {
  std::uint64_t headerOffset = 0;
  std::uint64_t size = 0;
  std::uint32_t crc = 0;
  std::string data;  ///< the member's bytes (.npy header and array)
};

/// Parses the zip @p bytes, checking what a reader relies on; fails the test otherwise.
std::map<std::string, Entry> parseZip(const std::string& bytes, bool zip64) {
  std::map<std::string, Entry> entries;
  const std::uint64_t end = bytes.size() - 22;
  EXPECT_EQ(le(bytes, end, 4), 0x06054b50u);
  std::uint64_t count = le(bytes, end + 10, 2);
  std::uint64_t directorySize = le(bytes, end + 12, 4);
  std::uint64_t directory = le(bytes, end + 16, 4);
  if (zip64) {
    EXPECT_EQ(directory, 0xFFFFFFFFu);
    const std::uint64_t locator = end - 20;
    EXPECT_EQ(le(bytes, locator, 4), 0x07064b50u);
    const std::uint64_t record = le(bytes, locator + 8, 8);
    EXPECT_EQ(record, locator - 56);
    EXPECT_EQ(le(bytes, record, 4), 0x06064b50u);
    count = le(bytes, record + 32, 8);
    directorySize = le(bytes, record + 40, 8);
    directory = le(bytes, record + 48, 8);
    EXPECT_EQ(directory + directorySize, record);
  } else {
    EXPECT_EQ(directory + directorySize, end);
  }
  std::uint64_t at = directory;
  for (std::uint64_t i = 0; i < count; ++i) {
    EXPECT_EQ(le(bytes, at, 4), 0x02014b50u);
    EXPECT_EQ(le(bytes, at + 10, 2), 0u) << "stored, not compressed";
    Entry e;
    e.crc = static_cast<std::uint32_t>(le(bytes, at + 16, 4));
    e.size = le(bytes, at + 24, 4);
    EXPECT_EQ(le(bytes, at + 20, 4), e.size);
    const std::uint64_t nameLength = le(bytes, at + 28, 2);
    const std::uint64_t extraLength = le(bytes, at + 30, 2);
    e.headerOffset = le(bytes, at + 42, 4);
    const std::string name = bytes.substr(at + 46, nameLength);
    if (zip64) {
      EXPECT_EQ(e.size, 0xFFFFFFFFu);
      EXPECT_EQ(extraLength, 28u);
      EXPECT_EQ(le(bytes, at + 46 + nameLength, 2), 1u);
      e.size = le(bytes, at + 46 + nameLength + 4, 8);
      EXPECT_EQ(le(bytes, at + 46 + nameLength + 12, 8), e.size);
      e.headerOffset = le(bytes, at + 46 + nameLength + 20, 8);
    } else {
      EXPECT_EQ(extraLength, 0u);
    }
    // The local header agrees with the directory.
    const std::uint64_t h = e.headerOffset;
    EXPECT_EQ(le(bytes, h, 4), 0x04034b50u);
    EXPECT_EQ(le(bytes, h + 14, 4), e.crc) << name;
    EXPECT_EQ(le(bytes, h + 26, 2), nameLength);
    EXPECT_EQ(bytes.substr(h + 30, nameLength), name);
    const std::uint64_t localExtra = le(bytes, h + 28, 2);
    if (zip64) {
      EXPECT_EQ(le(bytes, h + 22, 4), 0xFFFFFFFFu);
      EXPECT_EQ(le(bytes, h + 30 + nameLength + 4, 8), e.size);
    } else {
      EXPECT_EQ(le(bytes, h + 22, 4), e.size);
    }
    e.data = bytes.substr(h + 30 + nameLength + localExtra, e.size);
    EXPECT_EQ(e.data.size(), e.size) << name;
    EXPECT_EQ(crc32_z(0, reinterpret_cast<const Bytef*>(e.data.data()), e.data.size()), e.crc)
        << name;
    entries[name] = e;
    at += 46 + nameLength + extraLength + le(bytes, at + 32, 2);
  }
  EXPECT_EQ(at, directory + directorySize);
  return entries;
}

/// The .npy header's dict and the array bytes after it.
std::pair<std::string, std::string> splitNpy(const std::string& data) {
  EXPECT_EQ(data.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::uint64_t length = le(data, 8, 2);
  EXPECT_EQ((10 + length) % 64, 0u);
  return {data.substr(10, length), data.substr(10 + length)};
}

SceneResult scene(std::uint64_t index, bool success, int placed) {
  SceneResult s;
  s.index = index;
  s.seed = 7;
  s.success = success;
  const char* names[] = {"cube", "m\xc3\xbcsli"};
  for (int i = 0; i < placed; ++i) {
    ObjectPlacement p;
    p.name = names[i];
    p.position = Eigen::Vector3d(0.1 * index + i, -0.2, 0.8 + i);
    p.orientation = Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5);
    p.attempts = static_cast<std::uint32_t>(3 + i + index);
    s.placements.push_back(p);
  }
  return s;
}

void writeSample(const std::string& path, const NpzOptions& options) {
  NpzWriter writer(path, {"cube", "m\xc3\xbcsli"}, 3, 7, options);
  writer.write({scene(10, true, 2), scene(11, false, 1)});
  writer.write({scene(12, true, 2)});
  writer.finish();
  EXPECT_EQ(writer.fileSize(), readFile(path).size());
}

void checkSample(bool zip64) {
  const std::string path = tempPath(zip64 ? "zip64.npz" : "plain.npz");
  NpzOptions options;
  options.forceZip64 = zip64;
  writeSample(path, options);
  const std::map<std::string, Entry> entries = parseZip(readFile(path), zip64);
  ASSERT_EQ(entries.size(), 7u);

  auto [namesDict, names] = splitNpy(entries.at("names.npy").data);
  EXPECT_EQ(namesDict.substr(0, namesDict.find('}') + 1),
            "{'descr': '<U5', 'fortran_order': False, 'shape': (2,), }");
  ASSERT_EQ(names.size(), 40u);
  EXPECT_EQ(le(names, 0, 4), static_cast<std::uint64_t>('c'));
  EXPECT_EQ(le(names, 16, 4), 0u);     // "cube" padded
  EXPECT_EQ(le(names, 24, 4), 0xFCu);  // u-umlaut as one code point
  auto [positionDict, position] = splitNpy(entries.at("position.npy").data);
  EXPECT_EQ(positionDict.substr(0, positionDict.find('}') + 1),
            "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 2, 3), }");
  ASSERT_EQ(position.size(), 3u * 2 * 3 * 8);
  double values[18];
  std::memcpy(values, position.data(), sizeof(values));
  EXPECT_EQ(values[0], 0.1 * 10);
  EXPECT_EQ(values[5], 0.8 + 1);
  EXPECT_EQ(values[6], 0.1 * 11);
  EXPECT_TRUE(std::isnan(values[9]) && std::isnan(values[10]) && std::isnan(values[11]))
      << "the object a failed scene did not place";
  EXPECT_EQ(values[12], 0.1 * 12);
  auto [attemptsDict, attempts] = splitNpy(entries.at("attempts.npy").data);
  EXPECT_EQ(attemptsDict.substr(0, attemptsDict.find('}') + 1),
            "{'descr': '<u4', 'fortran_order': False, 'shape': (3, 2), }");
  EXPECT_EQ(le(attempts, 0, 4), 13u);
  EXPECT_EQ(le(attempts, 12, 4), 0u);
  auto [successDict, success] = splitNpy(entries.at("success.npy").data);
  EXPECT_EQ(success, std::string("\x01\x00\x01", 3));
  auto [sceneDict, scenes] = splitNpy(entries.at("scene.npy").data);
  EXPECT_EQ(le(scenes, 16, 8), 12u);
  auto [seedDict, seed] = splitNpy(entries.at("seed.npy").data);
  EXPECT_EQ(seedDict.substr(0, seedDict.find('}') + 1),
            "{'descr': '<u8', 'fortran_order': False, 'shape': (), }");
  EXPECT_EQ(le(seed, 0, 8), 7u);
  std::remove(path.c_str());
}

TEST(NpzWriter, ZipStructureAndCrc) { checkSample(false); }

TEST(NpzWriter, Zip64Records) { checkSample(true); }

TEST(NpzWriter, SameScenesSameBytes) {
  const std::string a = tempPath("a.npz");
  const std::string b = tempPath("b.npz");
  writeSample(a, {});
  writeSample(b, {});
  EXPECT_EQ(readFile(a), readFile(b));
  std::remove(a.c_str());
  std::remove(b.c_str());
}

// numpy itself reads both layouts (python3-numpy is a test dependency of the package).
TEST(NpzWriter, NumpyLoadsBothLayouts) {
  for (const bool zip64 : {false, true}) {
    const std::string path = tempPath(zip64 ? "np64.npz" : "np.npz");
    NpzOptions options;
    options.forceZip64 = zip64;
    writeSample(path, options);
    const std::string script =
        "import sys, numpy as np\n"
        "d = np.load(sys.argv[1])\n"
        "assert sorted(d.files) == ['attempts', 'names', 'orientation', 'position', 'scene', "
        "'seed', 'success'], d.files\n"
        "assert list(d['names']) == ['cube', 'm\\u00fcsli'], d['names']\n"
        "assert d['position'][2, 0, 0] == 0.1 * 12 and np.isnan(d['position'][1, 1]).all()\n"
        "assert d['orientation'][0, 0].tolist() == [0.5, -0.5, 0.5, 0.5]\n"
        "assert d['success'].tolist() == [True, False, True]\n"
        "assert d['scene'].tolist() == [10, 11, 12] and int(d['seed']) == 7\n"
        "assert d['attempts'].tolist() == [[13, 14], [14, 0], [15, 16]], d['attempts']\n";
    const std::string scriptPath = tempPath("check.py");
    std::ofstream(scriptPath) << script;
    EXPECT_EQ(std::system(
                  (std::string(PLACEMENT_SAMPLERS_PYTHON) + " " + scriptPath + " " + path).c_str()),
              0)
        << (zip64 ? "zip64" : "plain");
    std::remove(path.c_str());
    std::remove(scriptPath.c_str());
  }
}

TEST(NpzWriter, Errors) {
  try {
    NpzWriter writer("/nonexistent-dir/x.npz", {"cube"}, 1, 0);
    FAIL() << "expected an OutputError";
  } catch (const OutputError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent-dir/x.npz: cannot create: No such file or directory");
  }
  // /dev/full takes no byte: the first write fails as a full disk does.
  try {
    NpzWriter writer("/dev/full", {"cube"}, 1, 0);
    FAIL() << "expected an OutputError";
  } catch (const OutputError& e) {
    EXPECT_STREQ(e.what(), "/dev/full: cannot write: No space left on device");
  }
  EXPECT_EQ(::access("/dev/full", F_OK), 0) << "a device is never removed";
  const std::string path = tempPath("short.npz");
  {
    NpzWriter writer(path, {"cube"}, 2, 0);
    writer.write({scene(0, true, 1)});
    EXPECT_THROW(writer.write({scene(1, true, 1), scene(2, true, 1)}), OutputError);
    try {
      writer.finish();
      FAIL() << "expected an OutputError";
    } catch (const OutputError& e) {
      EXPECT_EQ(std::string(e.what()), path + ": 1 of 2 scenes written");
    }
    EXPECT_THROW(writer.write({scene(1, true, 2)}), std::invalid_argument)
        << "m\xc3\xbcsli is not among the names";
  }
  EXPECT_NE(::access(path.c_str(), F_OK), 0) << "an unfinished file is removed";
}

// The rows NpzWriter writes, in the caller's buffers (the Python module's numpy arrays): a
// scene's placements by name (in any order), NaN and 0 where a failed scene placed nothing,
// the physics members only where asked for.
TEST(SceneColumns, FillsTheRowsOfANpzFile) {
  SceneResult swapped = scene(4, true, 2);
  std::swap(swapped.placements[0], swapped.placements[1]);
  swapped.simulated = true;
  swapped.stable = true;
  swapped.physics.resize(2);
  swapped.physics[0].moved = 0.25;  // of the second name
  swapped.physics[1].fallen = true;
  const std::vector<SceneResult> scenes = {scene(3, false, 1), swapped};
  const SceneColumns columns({"cube", "m\xc3\xbcsli"}, PhysicsMode::Check);
  std::vector<double> position(12, -1.0), orientation(16, -1.0), moved(4, -1.0), turned(4, -1.0);
  std::vector<std::uint32_t> attempts(4, 99);
  std::vector<std::uint8_t> success(2, 9), stable(2, 9), fallen(4, 9);
  std::vector<std::uint64_t> index(2, 0);
  SceneArrayRows rows;
  rows.position = position.data();
  rows.orientation = orientation.data();
  rows.attempts = attempts.data();
  rows.success = success.data();
  rows.scene = index.data();
  rows.stable = stable.data();
  rows.moved = moved.data();
  rows.turned = turned.data();
  rows.fallen = fallen.data();
  columns.fill(scenes, rows);
  EXPECT_EQ(success, (std::vector<std::uint8_t>{0, 1}));
  EXPECT_EQ(index, (std::vector<std::uint64_t>{3, 4}));
  EXPECT_EQ(stable, (std::vector<std::uint8_t>{0, 1}));
  EXPECT_EQ(attempts, (std::vector<std::uint32_t>{6, 0, 7, 8}));
  EXPECT_EQ(position[0], 0.1 * 3);
  EXPECT_TRUE(std::isnan(position[3]) && std::isnan(orientation[4]));  // not placed
  EXPECT_EQ(position[6], 0.1 * 4);  // cube, second in the scene, first column
  EXPECT_EQ(position[9], 0.1 * 4 + 1);
  EXPECT_TRUE(std::isnan(moved[0]) && std::isnan(moved[1]));  // scene 3 was not simulated
  EXPECT_EQ(moved[3], 0.25);
  EXPECT_EQ(fallen, (std::vector<std::uint8_t>{0, 0, 1, 0}));
  SceneResult stranger = scene(5, true, 1);
  stranger.placements[0].name = "stranger";
  EXPECT_THROW(columns.fill({stranger}, rows), std::invalid_argument);
}

}  // namespace
}  // namespace placement_samplers
