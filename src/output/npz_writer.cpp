#include "placement_samplers/output/npz_writer.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <cerrno>
#include <cmath>
#include <cstring>

#include "output/npz_format.hpp"
#include "placement_samplers/output/scene_arrays.hpp"
#include "placement_samplers/text.hpp"

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "the .npz arrays are declared little-endian and copied as they are in memory");

namespace placement_samplers {
namespace {

// The members, in the file's order; the physics ones only when the scenes are simulated.
enum Member {
  kNames,
  kPosition,
  kOrientation,
  kAttempts,
  kSuccess,
  kScene,
  kSeed,
  kStable,
  kMoved,
  kTurned,
  kFallen,
  kSampledPosition,
  kSampledOrientation,
  kRestPose,
  kMembers
};
constexpr const char* kMemberNames[kMembers] = {"names.npy",
                                                "position.npy",
                                                "orientation.npy",
                                                "attempts.npy",
                                                "success.npy",
                                                "scene.npy",
                                                "seed.npy",
                                                "stable.npy",
                                                "moved.npy",
                                                "turned.npy",
                                                "fallen.npy",
                                                "sampled_position.npy",
                                                "sampled_orientation.npy",
                                                "rest_pose.npy"};

}  // namespace

struct NpzWriter::Impl {
  std::string path;
  std::string shownPath;
  int fd = -1;
  bool regular = false;  // a regular file: removed when not finished (never a device or FIFO)
  bool finished = false;
  bool zip64 = false;
  std::uint64_t numScenes = 0;
  std::uint64_t rows = 0;                    // scenes written so far
  std::unique_ptr<SceneColumns> columns;     // the names' columns and the physics members
  std::vector<npz::ZipMember> members;       // the file's members, in order
  int slot[kMembers] = {};                   // each member's index in members, -1 when left out
  std::uint64_t arrayOffset[kMembers] = {};  // where each member's array starts (after .npy header)
  std::uint64_t directoryOffset = 0;
  std::uint64_t fileSize = 0;
  // One block's rows per member, kept between calls so that their memory is reused.
  std::vector<double> position;
  std::vector<double> orientation;
  std::vector<std::uint32_t> attempts;
  std::vector<std::uint8_t> success;
  std::vector<std::uint64_t> scene;
  std::vector<std::uint8_t> stable;
  std::vector<double> moved;
  std::vector<double> turned;
  std::vector<std::uint8_t> fallen;
  std::vector<double> sampledPosition;
  std::vector<double> sampledOrientation;
  std::vector<std::int16_t> restPose;
  bool restPoses = false;

  // Also when the constructor throws: the file is closed and a partial one removed.
  ~Impl() {
    if (fd >= 0) {
      ::close(fd);
    }
    if (!finished && regular) {
      ::unlink(path.c_str());
    }
  }

  [[noreturn]] void fail(const std::string& what, int error) const {
    throw OutputError(shownPath + ": " + what + ": " + std::strerror(error));
  }

  /// Writes @p size bytes at @p offset, whatever pieces the system takes at a time.
  void writeAt(const void* data, std::size_t size, std::uint64_t offset) const {
    const char* p = static_cast<const char*>(data);
    while (size > 0) {
      const ssize_t done = ::pwrite(fd, p, size, static_cast<off_t>(offset));
      if (done < 0) {
        if (errno == EINTR) {
          continue;
        }
        fail("cannot write", errno);
      }
      if (done == 0) {
        fail("cannot write", ENOSPC);
      }
      p += done;
      size -= static_cast<std::size_t>(done);
      offset += static_cast<std::uint64_t>(done);
    }
  }

  /// Appends @p size bytes to member @p m at row offset @p offset, updating its CRC.
  void append(Member m, const void* data, std::size_t size, std::uint64_t offset) {
    writeAt(data, size, arrayOffset[m] + offset);
    npz::ZipMember& member = members[static_cast<std::size_t>(slot[m])];
    member.crc =
        static_cast<std::uint32_t>(crc32_z(member.crc, static_cast<const Bytef*>(data), size));
  }
};

NpzWriter::NpzWriter(const std::string& path, const std::vector<std::string>& names,
                     std::uint64_t numScenes, std::uint64_t seed, const NpzOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.path = path;
  d.shownPath = escapeText(path);
  d.numScenes = numScenes;
  d.columns = std::make_unique<SceneColumns>(names, options.physics);
  const std::uint64_t n = names.size();

  // names: numpy unicode (UTF-32) when every name is UTF-8, else bytes.
  std::vector<std::vector<std::uint32_t>> decoded(names.size());
  bool unicode = true;
  std::size_t width = 1;
  for (std::size_t i = 0; i < names.size(); ++i) {
    unicode = unicode && npz::decodeUtf8(names[i], decoded[i]);
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    width = std::max(width, unicode ? decoded[i].size() : names[i].size());
  }
  std::string namesData(n * width * (unicode ? 4 : 1), '\0');
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (unicode) {
      std::memcpy(&namesData[i * width * 4], decoded[i].data(), decoded[i].size() * 4);
    } else {
      std::memcpy(&namesData[i * width], names[i].data(), names[i].size());
    }
  }

  std::string headers[kMembers];
  std::uint64_t payload[kMembers];
  headers[kNames] = npz::npyHeader((unicode ? "<U" : "|S") + std::to_string(width), {n});
  payload[kNames] = namesData.size();
  headers[kPosition] = npz::npyHeader("<f8", {numScenes, n, 3});
  payload[kPosition] = numScenes * n * 3 * sizeof(double);
  headers[kOrientation] = npz::npyHeader("<f8", {numScenes, n, 4});
  payload[kOrientation] = numScenes * n * 4 * sizeof(double);
  headers[kAttempts] = npz::npyHeader("<u4", {numScenes, n});
  payload[kAttempts] = numScenes * n * sizeof(std::uint32_t);
  headers[kSuccess] = npz::npyHeader("|b1", {numScenes});
  payload[kSuccess] = numScenes;
  headers[kScene] = npz::npyHeader("<u8", {numScenes});
  payload[kScene] = numScenes * sizeof(std::uint64_t);
  headers[kSeed] = npz::npyHeader("<u8", {});
  payload[kSeed] = sizeof(std::uint64_t);
  headers[kStable] = npz::npyHeader("|b1", {numScenes});
  payload[kStable] = numScenes;
  headers[kMoved] = npz::npyHeader("<f8", {numScenes, n});
  payload[kMoved] = numScenes * n * sizeof(double);
  headers[kTurned] = headers[kMoved];
  payload[kTurned] = payload[kMoved];
  headers[kFallen] = npz::npyHeader("|b1", {numScenes, n});
  payload[kFallen] = numScenes * n;
  headers[kSampledPosition] = headers[kPosition];
  payload[kSampledPosition] = payload[kPosition];
  headers[kSampledOrientation] = headers[kOrientation];
  payload[kSampledOrientation] = payload[kOrientation];
  headers[kRestPose] = npz::npyHeader("<i2", {numScenes, n});
  payload[kRestPose] = numScenes * n * sizeof(std::int16_t);

  d.restPoses = options.restPoses;
  const int physicsEnd = options.physics == PhysicsMode::None    ? kStable
                         : options.physics == PhysicsMode::Check ? kSampledPosition
                                                                 : kRestPose;
  for (int m = 0; m < kMembers; ++m) {
    const bool used = m < physicsEnd || (m == kRestPose && options.restPoses);
    d.slot[m] = used ? static_cast<int>(d.members.size()) : -1;
    if (used) {
      npz::ZipMember member;
      member.name = kMemberNames[m];
      member.size = headers[m].size() + payload[m];
      d.members.push_back(member);
    }
  }
  d.zip64 = options.forceZip64 || npz::needsZip64(d.members);
  d.directoryOffset = npz::layOut(d.members, d.zip64);
  d.fileSize =
      d.directoryOffset + npz::centralDirectory(d.members, d.directoryOffset, d.zip64).size();

  // Non-blocking: opening a FIFO for writing waits for a reader otherwise (ENXIO instead).
  const std::string notSeekable =
      d.shownPath +
      ": is a FIFO or socket: an .npz file is written at offsets, so it must be a regular file";
  d.fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NONBLOCK, 0666);
  if (d.fd < 0) {
    if (errno == ENXIO) {
      throw OutputError(notSeekable);
    }
    d.fail("cannot create", errno);
  }
  struct stat status {};
  const bool known = ::fstat(d.fd, &status) == 0;
  if (known && (S_ISFIFO(status.st_mode) || S_ISSOCK(status.st_mode))) {
    throw OutputError(notSeekable);
  }
  const int flags = ::fcntl(d.fd, F_GETFL);
  if (flags != -1) {
    ::fcntl(d.fd, F_SETFL, flags & ~O_NONBLOCK);  // a device's writes wait as usual
  }
  d.regular = known && S_ISREG(status.st_mode);
  // Reserve the whole file now: a full disk shows at once, not after hours of sampling.
  if (::posix_fallocate(d.fd, 0, static_cast<off_t>(d.fileSize)) == ENOSPC) {
    throw OutputError(d.shownPath + ": not enough disk space for " + std::to_string(d.fileSize) +
                      " bytes: " + std::strerror(ENOSPC));
  }
  for (int m = 0; m < kMembers; ++m) {
    if (d.slot[m] < 0) {
      continue;
    }
    npz::ZipMember& member = d.members[static_cast<std::size_t>(d.slot[m])];
    const std::string local = npz::localHeader(member, d.zip64);
    d.writeAt(local.data(), local.size(), member.headerOffset);
    d.arrayOffset[m] = member.dataOffset + headers[m].size();
    member.crc = 0;
    d.append(static_cast<Member>(m), headers[m].data(), headers[m].size(),
             member.dataOffset - d.arrayOffset[m]);
  }
  d.append(kNames, namesData.data(), namesData.size(), 0);
  d.append(kSeed, &seed, sizeof(seed), 0);
}

NpzWriter::~NpzWriter() = default;

void NpzWriter::write(const std::vector<SceneResult>& scenes) {
  Impl& d = *impl_;
  const std::size_t k = scenes.size();
  if (k > d.numScenes - d.rows) {
    throw OutputError(d.shownPath + ": " + countText(d.rows + k, "scene") +
                      " written into a file laid out for " + std::to_string(d.numScenes));
  }
  const std::size_t n = d.columns->names().size();
  const bool physics = d.columns->physics() != PhysicsMode::None;
  const bool settle = d.columns->physics() == PhysicsMode::Settle;
  d.position.resize(k * n * 3);
  d.orientation.resize(k * n * 4);
  d.attempts.resize(k * n);
  if (d.restPoses) {
    d.restPose.resize(k * n);
  }
  d.success.resize(k);
  d.scene.resize(k);
  if (physics) {
    d.stable.resize(k);
    d.moved.resize(k * n);
    d.turned.resize(k * n);
    d.fallen.resize(k * n);
  }
  if (settle) {
    d.sampledPosition.resize(k * n * 3);
    d.sampledOrientation.resize(k * n * 4);
  }
  SceneArrayRows rows;
  rows.position = d.position.data();
  rows.orientation = d.orientation.data();
  rows.attempts = d.attempts.data();
  rows.success = d.success.data();
  rows.scene = d.scene.data();
  rows.stable = d.stable.data();
  rows.moved = d.moved.data();
  rows.turned = d.turned.data();
  rows.fallen = d.fallen.data();
  rows.sampledPosition = d.sampledPosition.data();
  rows.sampledOrientation = d.sampledOrientation.data();
  rows.restPose = d.restPoses ? d.restPose.data() : nullptr;
  d.columns->fill(scenes, rows);
  const std::uint64_t row = d.rows;
  d.append(kPosition, d.position.data(), d.position.size() * sizeof(double),
           row * n * 3 * sizeof(double));
  d.append(kOrientation, d.orientation.data(), d.orientation.size() * sizeof(double),
           row * n * 4 * sizeof(double));
  d.append(kAttempts, d.attempts.data(), d.attempts.size() * sizeof(std::uint32_t),
           row * n * sizeof(std::uint32_t));
  if (d.restPoses) {
    d.append(kRestPose, d.restPose.data(), d.restPose.size() * sizeof(std::int16_t),
             row * n * sizeof(std::int16_t));
  }
  d.append(kSuccess, d.success.data(), k, row);
  d.append(kScene, d.scene.data(), k * sizeof(std::uint64_t), row * sizeof(std::uint64_t));
  if (physics) {
    d.append(kStable, d.stable.data(), k, row);
    d.append(kMoved, d.moved.data(), k * n * sizeof(double), row * n * sizeof(double));
    d.append(kTurned, d.turned.data(), k * n * sizeof(double), row * n * sizeof(double));
    d.append(kFallen, d.fallen.data(), k * n, row * n);
  }
  if (settle) {
    d.append(kSampledPosition, d.sampledPosition.data(), k * n * 3 * sizeof(double),
             row * n * 3 * sizeof(double));
    d.append(kSampledOrientation, d.sampledOrientation.data(), k * n * 4 * sizeof(double),
             row * n * 4 * sizeof(double));
  }
  d.rows += k;
}

void NpzWriter::finish() {
  Impl& d = *impl_;
  if (d.rows != d.numScenes) {
    throw OutputError(d.shownPath + ": " + std::to_string(d.rows) + " of " +
                      std::to_string(d.numScenes) + " scenes written");
  }
  for (const npz::ZipMember& m : d.members) {
    const std::uint32_t crc = m.crc;  // little-endian, as the field
    d.writeAt(&crc, sizeof(crc), m.headerOffset + npz::kLocalCrcOffset);
  }
  const std::string directory = npz::centralDirectory(d.members, d.directoryOffset, d.zip64);
  d.writeAt(directory.data(), directory.size(), d.directoryOffset);
  const int fd = d.fd;
  d.fd = -1;
  // close() reports what the file system could not store (NFS, quotas).
  if (::close(fd) != 0) {
    d.fail("cannot write", errno);
  }
  d.finished = true;
}

std::uint64_t NpzWriter::fileSize() const { return impl_->fileSize; }

}  // namespace placement_samplers
