#include "eomgen/report/stl_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string_view>
#include <system_error>

namespace eomgen {
namespace {

// the bytes of a float are its IEEE binary32 bit pattern, assembled and taken apart byte by byte
// in little-endian order: the host's byte order never shows
static_assert(std::numeric_limits<float>::is_iec559 && sizeof(float) == 4, "STL stores IEEE binary32 floats");

// binary STL: an 80-byte header, the triangle count (uint32), then 50 bytes per triangle
// (normal, three vertices, each 3 floats, and a 2-byte attribute count)
constexpr std::uintmax_t count_offset = 80;
constexpr std::uintmax_t header_bytes = 84;
constexpr std::uintmax_t triangle_bytes = 50;
constexpr std::size_t first_vertex_offset = 12;  // after the normal

std::uint32_t little_endian_u32(const char* p) {
  const auto byte = [p](int k) { return static_cast<std::uint32_t>(static_cast<unsigned char>(p[k])); };
  return byte(0) | byte(1) << 8 | byte(2) << 16 | byte(3) << 24;
}

float float_from_bits(std::uint32_t bits) {
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

std::uint32_t bits_of(float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

// an ASCII keyword, in any case
bool is_keyword(std::string_view token, std::string_view keyword) {
  if (token.size() != keyword.size()) return false;
  for (std::size_t k = 0; k < token.size(); ++k)
    if (lower(token[k]) != keyword[k]) return false;
  return true;
}

// the whole file, no more than its size when checked (should it grow meanwhile)
std::string file_bytes(const std::string& path, std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found) throw MeshError("it cannot be opened: there is no such file");
  if (ec) throw MeshError(fmt::format("it cannot be opened ({})", ec.message()));
  if (!fs::is_regular_file(status)) throw MeshError("it cannot be opened: it is not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw MeshError(fmt::format("it cannot be opened ({})", ec.message()));
  if (size > max_bytes || size > std::numeric_limits<std::size_t>::max())
    throw MeshError(fmt::format("it is too large: {} bytes, at most {} read", size, max_bytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshError("it cannot be opened for reading");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (in.bad()) throw MeshError("it cannot be read");
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return bytes;
}

// the offset of the first byte no text holds (a control character other than whitespace), or npos
std::size_t first_binary_byte(std::string_view bytes) {
  for (std::size_t k = 0; k < bytes.size(); ++k) {
    const auto c = static_cast<unsigned char>(bytes[k]);
    if ((c < 0x20 && !is_blank(bytes[k])) || c == 0x7f) return k;
  }
  return std::string_view::npos;
}

bool starts_with_solid(std::string_view bytes) {
  std::size_t at = 0;
  while (at < bytes.size() && is_blank(bytes[at])) ++at;
  return is_keyword(bytes.substr(at, 5), "solid");
}

// a token of a file for a message: printable ASCII only, at most 24 characters
std::string quoted(std::string_view token) {
  constexpr std::size_t most = 24;
  std::string out = "'";
  for (std::size_t k = 0; k < token.size() && k < most; ++k) {
    const auto c = static_cast<unsigned char>(token[k]);
    out += (c >= 0x20 && c < 0x7f) ? token[k] : '?';
  }
  out += token.size() > most ? "...'" : "'";
  return out;
}

TriangleMesh binary_triangles(std::string_view bytes, std::uint32_t n, std::size_t max_triangles) {
  if (n > max_triangles)
    throw MeshError(fmt::format("it has {} triangles, more than the {} read at most", n, max_triangles));
  if (n == 0) throw MeshError("it holds no triangle (a binary STL stating 0)");
  // n <= max_triangles, and the size was checked to be 84 + 50 n: the reservation is bounded twice
  TriangleMesh mesh;
  mesh.vertices.reserve(static_cast<std::size_t>(n) * 9);
  for (std::size_t t = 0; t < n; ++t) {
    const char* vertex = bytes.data() + header_bytes + triangle_bytes * t + first_vertex_offset;
    for (std::size_t k = 0; k < 9; ++k) {
      const float x = float_from_bits(little_endian_u32(vertex + 4 * k));
      if (!std::isfinite(x))
        throw MeshError(fmt::format("the {} coordinate of vertex {} of triangle {} is not finite ({})", "xyz"[k % 3],
                                    k / 3 + 1, t + 1, x));
      mesh.vertices.push_back(x);
    }
  }
  return mesh;
}

// whether a decimal number that from_chars found outside float's range lies below 1 in
// magnitude (it underflowed: its float is a zero) rather than above (it overflowed); its order
// of magnitude is that of its first nonzero digit plus its exponent
bool below_one(std::string_view number) {
  std::size_t at = (!number.empty() && number[0] == '-') ? 1 : 0;
  long long before_point = 0;  // significant digits before the point
  long long zeros_after_point = 0;
  bool significant = false;
  bool after_point = false;
  for (; at < number.size() && ((number[at] >= '0' && number[at] <= '9') || number[at] == '.'); ++at) {
    const char c = number[at];
    if (c == '.') {
      after_point = true;
    } else if (!after_point) {
      if (significant || c != '0') {
        significant = true;
        ++before_point;
      }
    } else if (!significant) {
      if (c == '0') {
        ++zeros_after_point;
      } else {
        significant = true;
      }
    }
  }
  long long exponent = 0;
  if (at < number.size() && (number[at] == 'e' || number[at] == 'E')) {
    ++at;
    const bool negative = at < number.size() && number[at] == '-';
    if (at < number.size() && (number[at] == '-' || number[at] == '+')) ++at;
    // saturated: an exponent this large is out of range either way
    for (; at < number.size() && number[at] >= '0' && number[at] <= '9'; ++at)
      exponent = std::min(exponent * 10 + (number[at] - '0'), 1'000'000'000LL);
    if (negative) exponent = -exponent;
  }
  const long long magnitude = before_point > 0 ? before_point - 1 : -(zeros_after_point + 1);
  return magnitude + exponent < 0;
}

enum class Number { ok, not_a_number, not_finite };

// a decimal number as strtod reads it in the "C" locale, rounded once to the nearest float
Number parse_float(std::string_view token, float& value) {
  std::string_view number = token;
  if (!number.empty() && number[0] == '+') {
    number.remove_prefix(1);
    if (!number.empty() && number[0] == '-') return Number::not_a_number;
  }
  const char* end = number.data() + number.size();
  float parsed = 0;
  const auto [stop, ec] = std::from_chars(number.data(), end, parsed, std::chars_format::general);
  if (ec == std::errc::invalid_argument || stop != end) return Number::not_a_number;
  if (ec == std::errc::result_out_of_range) {
    if (!below_one(number)) return Number::not_finite;
    value = number[0] == '-' ? -0.0f : 0.0f;
    return Number::ok;
  }
  // from_chars also reads "inf", "infinity" and "nan"
  if (!std::isfinite(parsed)) return Number::not_finite;
  value = parsed;
  return Number::ok;
}

// ASCII STL: solid NAME, then per triangle
//   facet normal NX NY NZ / outer loop / vertex X Y Z (three times) / endloop / endfacet
// then endsolid NAME; several solids in a row are read as one mesh. Tokens are separated by any
// whitespace; a line ends at LF, CRLF or CR. A name is the rest of its keyword's line, up to a
// keyword that follows it there (a file may be one line).
class AsciiReader {
 public:
  AsciiReader(std::string_view text, std::size_t max_triangles) : text_(text), max_triangles_(max_triangles) {}

  TriangleMesh read() {
    Token token = next();
    if (!is_keyword(token.text, "solid")) fail(token, "'solid'");
    while (true) {
      token = facets(after_name(token, "facet", "endsolid"));
      if (token.text.empty()) break;
      if (!is_keyword(token.text, "solid")) fail(token, "'solid' or the end of the file");
    }
    if (mesh_.vertices.empty()) throw MeshError("it holds no triangle (an ASCII STL without a facet)");
    return std::move(mesh_);
  }

 private:
  struct Token {
    std::string_view text;  // empty at the end of the file
    std::size_t line;
  };

  Token next() {
    while (at_ < text_.size() && is_blank(text_[at_])) {
      if (text_[at_] == '\n' || (text_[at_] == '\r' && (at_ + 1 == text_.size() || text_[at_ + 1] != '\n'))) ++line_;
      ++at_;
    }
    const std::size_t start = at_;
    while (at_ < text_.size() && !is_blank(text_[at_])) ++at_;
    return {text_.substr(start, at_ - start), line_};
  }

  // the first token after the name that follows `keyword` on its line
  Token after_name(const Token& keyword, std::string_view stop, std::string_view other_stop = {}) {
    Token token = next();
    while (!token.text.empty() && token.line == keyword.line && !is_keyword(token.text, stop) &&
           !is_keyword(token.text, other_stop))
      token = next();
    return token;
  }

  [[noreturn]] static void fail(const Token& token, std::string_view expected) {
    throw MeshError(fmt::format("line {}: expected {}, found {}", token.line, expected,
                                token.text.empty() ? std::string("the end of the file") : quoted(token.text)));
  }

  // the facets of one solid from its first token, up to its endsolid; returns the token after
  // endsolid's name
  Token facets(Token token) {
    while (true) {
      if (is_keyword(token.text, "endsolid")) return after_name(token, "solid");
      if (!is_keyword(token.text, "facet")) fail(token, "'facet' or 'endsolid'");
      if (triangles_ == max_triangles_)
        throw MeshError(fmt::format("it has more than the {} triangles read at most (another facet at line {})",
                                    max_triangles_, token.line));
      const std::size_t facet_line = token.line;
      // the normal is not read (the viewer computes its own): up to three tokens before 'outer'
      token = next();
      if (is_keyword(token.text, "normal")) {
        token = next();
        for (int k = 0; k < 3 && !token.text.empty() && !is_keyword(token.text, "outer"); ++k) token = next();
      }
      if (!is_keyword(token.text, "outer")) fail(token, "'outer loop'");
      token = next();
      if (!is_keyword(token.text, "loop")) fail(token, "'outer loop'");
      std::size_t vertices = 0;
      while (true) {
        token = next();
        if (is_keyword(token.text, "endloop")) break;
        if (!is_keyword(token.text, "vertex")) fail(token, vertices < 3 ? "'vertex X Y Z'" : "'endloop'");
        if (vertices == 3)
          throw MeshError(fmt::format("line {}: the facet of line {} has more than 3 vertices", token.line,
                                      facet_line));
        for (const char* name : {"X", "Y", "Z"}) mesh_.vertices.push_back(coordinate(name));
        ++vertices;
      }
      if (vertices != 3)
        throw MeshError(fmt::format("line {}: the facet of line {} has {} vertices, 3 expected", token.line,
                                    facet_line, vertices));
      token = next();
      if (!is_keyword(token.text, "endfacet")) fail(token, "'endfacet'");
      ++triangles_;
      token = next();
    }
  }

  float coordinate(const char* name) {
    const Token token = next();
    float value = 0;
    switch (parse_float(token.text, value)) {
      case Number::ok: return value;
      case Number::not_a_number:
        throw MeshError(fmt::format("line {}: expected 'vertex X Y Z', found {} for {}", token.line,
                                    token.text.empty() ? std::string("the end of the file") : quoted(token.text),
                                    name));
      case Number::not_finite:
        throw MeshError(fmt::format("line {}: the coordinate {} is not finite as a float", token.line,
                                    quoted(token.text)));
    }
    EOMGEN_UNREACHABLE("read_stl: a number neither read nor refused");
  }

  std::string_view text_;
  std::size_t max_triangles_;
  std::size_t at_ = 0;
  std::size_t line_ = 1;
  std::size_t triangles_ = 0;
  TriangleMesh mesh_;
};

}  // namespace

TriangleMesh read_stl(const std::string& path, std::size_t max_triangles, std::uintmax_t max_bytes) {
  const std::string bytes = file_bytes(path, max_bytes);
  if (bytes.empty()) throw MeshError("it is empty");
  // binary when the size is the one its count states, whatever its header says ("solid" often)
  const bool has_count = bytes.size() >= header_bytes;
  const std::uint32_t n = has_count ? little_endian_u32(bytes.data() + count_offset) : 0;
  const std::uintmax_t expected = header_bytes + triangle_bytes * n;
  if (has_count && bytes.size() == expected) return binary_triangles(bytes, n, max_triangles);
  // else ASCII, all text; the header of a binary file of the wrong size may say "solid" too
  const std::size_t binary_byte = first_binary_byte(bytes);
  const bool solid = starts_with_solid(bytes);
  if (solid && binary_byte == std::string_view::npos) return AsciiReader(bytes, max_triangles).read();
  const std::string binary =
      has_count ? fmt::format("84 + 50 x {} bytes expected, {} found", n, bytes.size())
                : fmt::format("at least 84 bytes expected, {} found", bytes.size());
  // a file too short for its count is a truncated binary one if it holds bytes no text does
  if (has_count && bytes.size() < expected && binary_byte != std::string_view::npos)
    throw MeshError(fmt::format("it is truncated: {}", binary));
  const std::string ascii =
      solid ? fmt::format("a byte 0x{:02x} at offset {}", static_cast<unsigned char>(bytes[binary_byte]), binary_byte)
            : std::string("no 'solid' at its start");
  throw MeshError(fmt::format("it is neither binary STL ({}) nor ASCII STL ({})", binary, ascii));
}

std::string little_endian_base64(const std::vector<float>& values) {
  static constexpr char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string bytes;
  bytes.reserve(values.size() * 4);
  for (const float value : values) {
    const std::uint32_t bits = bits_of(value);
    for (int k = 0; k < 4; ++k) bytes.push_back(static_cast<char>((bits >> (8 * k)) & 0xffu));
  }
  // 3 bytes -> 4 characters of 6 bits; a last group of 1 or 2 bytes is padded with '='
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t k = 0; k < bytes.size(); k += 3) {
    const std::size_t left = bytes.size() - k;
    const auto byte = [&](std::size_t j) {
      return j < left ? static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[k + j])) : 0u;
    };
    const std::uint32_t group = byte(0) << 16 | byte(1) << 8 | byte(2);
    out += alphabet[(group >> 18) & 63];
    out += alphabet[(group >> 12) & 63];
    out += left > 1 ? alphabet[(group >> 6) & 63] : '=';
    out += left > 2 ? alphabet[group & 63] : '=';
  }
  return out;
}

}  // namespace eomgen
