#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace placement_samplers {
namespace npz {

/// The .npy header (magic, version 1.0, the dict padded to a multiple of 64 bytes) of an array
/// of numpy dtype @p descr ("<f8", "<U12", ...), C order, @p shape ({} = a scalar).
std::string npyHeader(const std::string& descr, const std::vector<std::uint64_t>& shape);

/// One stored (uncompressed) zip member at a fixed place in the file.
struct ZipMember {
  std::string name;
  std::uint64_t headerOffset = 0;  ///< where its local header starts [bytes]
  std::uint64_t dataOffset = 0;    ///< where its data starts [bytes]
  std::uint64_t size = 0;          ///< its data's size [bytes]
  std::uint32_t crc = 0;           ///< CRC-32 of its data, once known
};

/// Places @p members one after the other from offset 0 (sets headerOffset and dataOffset).
/// @return the offset of the central directory [bytes]
std::uint64_t layOut(std::vector<ZipMember>& members, bool zip64);

/// Whether a file of these members needs zip64 headers (some offset or size above 4 GB).
bool needsZip64(const std::vector<ZipMember>& members);

/// The local file header of @p member (its CRC as given: rewritten once known).
std::string localHeader(const ZipMember& member, bool zip64);

/// The central directory, the zip64 end records when @p zip64, and the end record, for a
/// directory starting at @p offset.
std::string centralDirectory(const std::vector<ZipMember>& members, std::uint64_t offset,
                             bool zip64);

/// Byte offset of the CRC-32 field in a local header.
constexpr std::uint64_t kLocalCrcOffset = 14;

/// @p text (UTF-8) as UTF-32 code points. @return false when it is not valid UTF-8
bool decodeUtf8(const std::string& text, std::vector<std::uint32_t>& out);

}  // namespace npz
}  // namespace placement_samplers
