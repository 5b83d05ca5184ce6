#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace placement_samplers {

/// Reads the file at @p path, at most @p maxBytes bytes. Reads at most one byte more than the
/// limit, so an endless source (/dev/zero, /dev/urandom, a pipe) costs no more than that.
/// Pipes and devices are read like files; directories are refused.
/// @param what how messages call the file's contents ("the configuration file", "the URDF file")
/// @throw ConfigError, not prefixed with the path (the caller knows it): the file does not exist,
///        is a directory, cannot be opened or read (with the system's reason), or is larger
///        than @p maxBytes ("... is larger than the limit of N bytes")
std::string readFileBounded(const std::string& path, std::size_t maxBytes, const char* what);

/// readFileBounded for files that must be regular files (an MJCF document, the files it
/// names): opened without blocking and refused unless regular, so a FIFO, a device or a
/// directory never makes the caller wait or read without end.
/// @throw ConfigError as readFileBounded, and "not a regular file"
std::string readRegularFileBounded(const std::string& path, std::size_t maxBytes, const char* what);

/// The deepest element nesting of the XML document @p text (the root element is level 1),
/// scanning at most until it exceeds @p stopAbove: comments, CDATA sections, processing
/// instructions, the DOCTYPE and quoted attribute values are skipped. A cheap linear scan,
/// done before a parser that recurses per element level (tinyxml2, assimp) sees the document;
/// malformed text gives some depth and is left to the parser to refuse.
int xmlNestingDepth(std::string_view text, int stopAbove);

}  // namespace placement_samplers
