#pragma once
// File names and headers as MuJoCo 2.2.2 reads them, and the printing of a rewritten MJCF
// document. Private to the core (mjcf_document.cpp).

#include <tinyxml2.h>

#include <cstdint>
#include <string>

namespace placement_samplers::detail {

/// The directory of @p path with its trailing '/', "" when it has none.
std::string directoryOf(const std::string& path);

bool isAbsolute(const std::string& path);

/// Where MuJoCo 2.2.2 looks for @p file of a document in @p modelDir with compiler directory
/// @p dir (meshdir): an absolute file as it is, else below an absolute dir, else below both.
std::string fullName(const std::string& modelDir, std::string dir, const std::string& file);

/// The extension of @p file with its dot ("" when none, or when implausibly long): MuJoCo
/// chooses the reader by it.
std::string extensionOf(const std::string& file);

/// Product of the whitespace-separated numbers of @p text, each taken as at least 1 and the
/// product capped at @p cap + 1: an upper bound of what a <composite count> makes.
std::uint64_t countProduct(const std::string& text, std::uint64_t cap);

/// Samples of a height field file: a PNG's width x height, or the rows x columns of MuJoCo's
/// binary format; 0 when the header is too short (MuJoCo refuses the file).
std::uint64_t heightFieldSamples(const std::string& data, const std::string& extension);

/// @p doc printed compactly, each element parsed from its text on its original line: MuJoCo's
/// messages ("Element 'geom', line 12") then point into the user's file. Elements made or
/// cloned afterwards (line 0) stay where they are.
std::string printKeepingLines(const tinyxml2::XMLDocument& doc);

}  // namespace placement_samplers::detail
