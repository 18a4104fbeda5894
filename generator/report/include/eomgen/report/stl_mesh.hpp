#pragma once
// The triangles of an STL file, for the animation page to draw a mesh visual (a URDF
// `<mesh filename="...stl">`, issue 29), and the floats as the page carries them (base64 of
// little-endian binary32). Normals are not read: the viewer computes its own.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "eomgen/base/error.hpp"

namespace eomgen {

/// Triangles as read from an STL file: 9 floats per triangle (three vertices x, y, z), in file
/// order, every one finite.
struct TriangleMesh {
  std::vector<float> vertices;  // dim 9 * triangles()
  /// The number of triangles, vertices.size() / 9.
  std::size_t triangles() const { return vertices.size() / 9; }
};

/// Why an STL file cannot be drawn. what() is one sentence without the path, for the caller to
/// put after it: "it is truncated: 84 + 50 x 12 bytes expected, 500 found",
/// "line 12: expected 'vertex X Y Z', found 'endloop'".
class MeshError : public Error {
 public:
  using Error::Error;
};

/// Reads the binary or ASCII STL file at \p path. The file is binary when its size is
/// 84 + 50 n for the triangle count n at offset 80 (a binary header may start with "solid"),
/// else ASCII when it starts with "solid" after optional whitespace and holds text. ASCII
/// keywords are read in any case and between any whitespace (CRLF too); decimal numbers as C's
/// strtod reads them in the "C" locale (`1e-3`, `-0.5`, `.5`, `+2`), whatever the locale. A number
/// below float's range reads as a zero. The same file gives the same floats.
/// \param[in] path           the file
/// \param[in] max_triangles  the most triangles read
/// \param[in] max_bytes      the largest file read (its size is checked before it is read)
/// \return its triangles, at least one
/// @throws MeshError if the file cannot be opened or is not a regular file
/// @throws MeshError if it is larger than max_bytes
/// @throws MeshError if it has more than max_triangles triangles (stated in a binary header, or
///         counted in ASCII)
/// @throws MeshError if it is neither: a binary file whose size is not 84 + 50 n for its stated
///         n (truncated, or too long), and not ASCII
/// @throws MeshError if ASCII does not parse, saying at which line ("line 12: expected ...")
/// @throws MeshError if an ASCII facet does not have exactly 3 vertices
/// @throws MeshError if a vertex coordinate is not finite as a float (NaN or infinity in a
///         binary file, `1e39` or `nan` in ASCII)
/// @throws MeshError if it holds no triangle
TriangleMesh read_stl(const std::string& path, std::size_t max_triangles, std::uintmax_t max_bytes);

/// \p values as little-endian IEEE binary32 bytes (4 per value), base64-encoded (RFC 4648,
/// standard alphabet, '=' padding): the same text on every platform. {1.0f} gives "AACAPw==",
/// {} gives "".
std::string little_endian_base64(const std::vector<float>& values);

}  // namespace eomgen
