#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace placement_samplers {

/// @p text made safe to print in a message: control characters (a NUL byte included), DEL,
/// backslashes and bytes that are not valid UTF-8 become escapes (\n, \t, \r, \0, \\, \xNN);
/// valid UTF-8 is kept. Beyond @p maxShown bytes the text is cut and "... (N bytes)" appended.
/// Every message that shows a name, key, value or path taken from input uses it (or quoteText()),
/// so a NUL byte cannot cut a message and a terminal escape cannot reach a console.
std::string escapeText(std::string_view text, std::size_t maxShown = 1000);

/// The length of the valid UTF-8 sequence of 2 to 4 bytes that starts at byte @p i of @p text
/// (no overlong form, no surrogate, at most U+10FFFF), or 0 when there is none there.
std::size_t utf8Sequence(std::string_view text, std::size_t i);

/// escapeText(@p text) between single quotes: 'name'.
std::string quoteText(std::string_view text);

/// @p count and @p noun, the noun in the plural unless the count is 1: "1 fixture",
/// "2 fixtures", "0 attempts". @p noun is the singular of a noun whose plural adds "s".
std::string countText(std::uint64_t count, std::string_view noun);

/// "[a, b]": a range [m] or [rad] as errors print it (stream formatting, 6 significant digits).
std::string rangeText(double a, double b);

}  // namespace placement_samplers
