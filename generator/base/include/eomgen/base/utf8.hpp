#pragma once
// UTF-8 as RFC 3629 defines it. Model text, file names and names reach JSON, SVG titles and C++
// string literals, which all need it; this is the one place that says what well-formed is.
#include <cstddef>
#include <string_view>

namespace eomgen {

/// The length (1 to 4) of the well-formed UTF-8 sequence that starts at text[i], or 0 where
/// none does: a stray continuation byte, a truncated or overlong sequence, a surrogate, a code
/// point above U+10FFFF.
std::size_t utf8_sequence_length(std::string_view text, std::size_t i);

/// Where text stops being well-formed UTF-8, or std::string_view::npos.
std::size_t invalid_utf8_at(std::string_view text);

}  // namespace eomgen
