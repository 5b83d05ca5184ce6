#include "output/npz_format.hpp"

namespace placement_samplers {
namespace npz {
namespace {

constexpr std::uint32_t kMax32 = 0xFFFFFFFFu;
// Version needed to extract: 2.0 for stored members, 4.5 when zip64 records are used.
constexpr std::uint16_t kVersion = 20;
constexpr std::uint16_t kVersionZip64 = 45;
// Fixed time stamp (1980-01-01 00:00 in MS-DOS format): the same scenes give the same bytes.
constexpr std::uint16_t kDosTime = 0;
constexpr std::uint16_t kDosDate = (1 << 5) | 1;

void put16(std::string& out, std::uint16_t v) {
  out += static_cast<char>(v & 0xFF);
  out += static_cast<char>(v >> 8);
}

void put32(std::string& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) {
    out += static_cast<char>((v >> (8 * k)) & 0xFF);
  }
}

void put64(std::string& out, std::uint64_t v) {
  for (int k = 0; k < 8; ++k) {
    out += static_cast<char>((v >> (8 * k)) & 0xFF);
  }
}

std::uint64_t localHeaderSize(const ZipMember& member, bool zip64) {
  return 30 + member.name.size() + (zip64 ? 20 : 0);
}

}  // namespace

std::string npyHeader(const std::string& descr, const std::vector<std::uint64_t>& shape) {
  std::string dict = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': (";
  for (std::size_t i = 0; i < shape.size(); ++i) {
    dict += std::to_string(shape[i]);
    dict += shape.size() == 1 ? "," : (i + 1 < shape.size() ? ", " : "");
  }
  dict += "), }";
  // numpy pads with spaces and ends with a newline so that the data start is 64-byte aligned.
  const std::size_t unpadded = 10 + dict.size() + 1;
  dict.append((64 - unpadded % 64) % 64, ' ');
  dict += '\n';
  std::string out("\x93NUMPY\x01\x00", 8);
  put16(out, static_cast<std::uint16_t>(dict.size()));
  return out + dict;
}

std::uint64_t layOut(std::vector<ZipMember>& members, bool zip64) {
  std::uint64_t offset = 0;
  for (ZipMember& m : members) {
    m.headerOffset = offset;
    m.dataOffset = offset + localHeaderSize(m, zip64);
    offset = m.dataOffset + m.size;
  }
  return offset;
}

bool needsZip64(const std::vector<ZipMember>& members) {
  std::vector<ZipMember> copy = members;
  std::uint64_t end = layOut(copy, false);
  for (const ZipMember& m : copy) {
    end += 46 + m.name.size();
  }
  return end + 22 >= kMax32;
}

std::string localHeader(const ZipMember& member, bool zip64) {
  std::string out;
  put32(out, 0x04034b50);
  put16(out, zip64 ? kVersionZip64 : kVersion);
  put16(out, 0);  // flags
  put16(out, 0);  // stored
  put16(out, kDosTime);
  put16(out, kDosDate);
  put32(out, member.crc);
  put32(out, zip64 ? kMax32 : static_cast<std::uint32_t>(member.size));  // compressed
  put32(out, zip64 ? kMax32 : static_cast<std::uint32_t>(member.size));  // uncompressed
  put16(out, static_cast<std::uint16_t>(member.name.size()));
  put16(out, zip64 ? 20 : 0);
  out += member.name;
  if (zip64) {
    put16(out, 0x0001);  // zip64 extended information
    put16(out, 16);
    put64(out, member.size);
    put64(out, member.size);
  }
  return out;
}

std::string centralDirectory(const std::vector<ZipMember>& members, std::uint64_t offset,
                             bool zip64) {
  std::string out;
  for (const ZipMember& m : members) {
    put32(out, 0x02014b50);
    put16(out, (3 << 8) | (zip64 ? kVersionZip64 : kVersion));  // made by: Unix
    put16(out, zip64 ? kVersionZip64 : kVersion);
    put16(out, 0);
    put16(out, 0);
    put16(out, kDosTime);
    put16(out, kDosDate);
    put32(out, m.crc);
    put32(out, zip64 ? kMax32 : static_cast<std::uint32_t>(m.size));
    put32(out, zip64 ? kMax32 : static_cast<std::uint32_t>(m.size));
    put16(out, static_cast<std::uint16_t>(m.name.size()));
    put16(out, zip64 ? 28 : 0);
    put16(out, 0);               // comment
    put16(out, 0);               // disk
    put16(out, 0);               // internal attributes
    put32(out, 0100644u << 16);  // a regular file, rw-r--r--
    put32(out, zip64 ? kMax32 : static_cast<std::uint32_t>(m.headerOffset));
    out += m.name;
    if (zip64) {
      // In the order of the fields set to 0xFFFFFFFF: uncompressed, compressed, offset.
      put16(out, 0x0001);
      put16(out, 24);
      put64(out, m.size);
      put64(out, m.size);
      put64(out, m.headerOffset);
    }
  }
  const std::uint64_t directorySize = out.size();
  const std::uint64_t count = members.size();
  if (zip64) {
    const std::uint64_t recordOffset = offset + directorySize;
    put32(out, 0x06064b50);  // zip64 end of central directory record
    put64(out, 44);          // its size after this field
    put16(out, (3 << 8) | kVersionZip64);
    put16(out, kVersionZip64);
    put32(out, 0);
    put32(out, 0);
    put64(out, count);
    put64(out, count);
    put64(out, directorySize);
    put64(out, offset);
    put32(out, 0x07064b50);  // its locator
    put32(out, 0);
    put64(out, recordOffset);
    put32(out, 1);  // disks
  }
  put32(out, 0x06054b50);  // end of central directory
  put16(out, 0);
  put16(out, 0);
  put16(out, static_cast<std::uint16_t>(count));
  put16(out, static_cast<std::uint16_t>(count));
  put32(out, zip64 ? kMax32 : static_cast<std::uint32_t>(directorySize));
  put32(out, zip64 ? kMax32 : static_cast<std::uint32_t>(offset));
  put16(out, 0);  // comment
  return out;
}

bool decodeUtf8(const std::string& text, std::vector<std::uint32_t>& out) {
  out.clear();
  for (std::size_t i = 0; i < text.size();) {
    const auto lead = static_cast<unsigned char>(text[i]);
    int extra = 0;
    std::uint32_t cp = 0;
    if (lead < 0x80) {
      cp = lead;
    } else if (lead >= 0xC2 && lead < 0xE0) {
      extra = 1;
      cp = lead & 0x1F;
    } else if (lead >= 0xE0 && lead < 0xF0) {
      extra = 2;
      cp = lead & 0x0F;
    } else if (lead >= 0xF0 && lead < 0xF5) {
      extra = 3;
      cp = lead & 0x07;
    } else {
      return false;
    }
    if (i + extra >= text.size()) {  // a sequence cut short
      return false;
    }
    for (int k = 1; k <= extra; ++k) {
      const auto c = static_cast<unsigned char>(text[i + k]);
      if ((c & 0xC0) != 0x80) {
        return false;
      }
      cp = (cp << 6) | (c & 0x3F);
    }
    // Overlong forms, surrogates and code points above U+10FFFF are not UTF-8.
    if ((extra == 2 && cp < 0x800) || (extra == 3 && (cp < 0x10000 || cp > 0x10FFFF)) ||
        (cp >= 0xD800 && cp <= 0xDFFF)) {
      return false;
    }
    out.push_back(cp);
    i += 1 + extra;
  }
  return true;
}

}  // namespace npz
}  // namespace placement_samplers
