#include "eomgen/report/stl_mesh.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "support/expect_throw.hpp"

namespace eomgen {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

using Triangle = std::array<float, 9>;

constexpr std::size_t max_triangles = 1000;
constexpr std::uintmax_t max_bytes = 1 << 20;

// two triangles whose floats are exact in binary and in their decimal text below: halves,
// a negative zero, a power of two beyond the decimal digits' reach, a subnormal
const std::vector<Triangle> two_triangles = {
    Triangle{0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f},
    Triangle{-2.5f, 0.5f, -0.0f, 1024.0f, 0.125f, 3.0f, 6.103515625e-05f, -7.0f, 1e-40f},
};

std::vector<float> flat(const std::vector<Triangle>& triangles) {
  std::vector<float> out;
  for (const Triangle& t : triangles) out.insert(out.end(), t.begin(), t.end());
  return out;
}

void append_u32(std::string& bytes, std::uint32_t value) {
  for (int k = 0; k < 4; ++k) bytes.push_back(static_cast<char>((value >> (8 * k)) & 0xffu));
}

void append_float(std::string& bytes, float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  append_u32(bytes, bits);
}

// a binary STL: the 80-byte header (padded with zeros), the count (the number of triangles
// unless given), and per triangle a normal, the vertices and a zero attribute count
std::string binary_stl(const std::vector<Triangle>& triangles, const std::string& header = "binary STL of eomgen's test",
                       std::int64_t count = -1) {
  std::string bytes = header;
  bytes.resize(80, '\0');
  append_u32(bytes, count < 0 ? static_cast<std::uint32_t>(triangles.size()) : static_cast<std::uint32_t>(count));
  for (const Triangle& t : triangles) {
    for (const float n : {0.0f, 0.0f, 1.0f}) append_float(bytes, n);
    for (const float x : t) append_float(bytes, x);
    bytes += std::string(2, '\0');
  }
  return bytes;
}

// the same two triangles as ASCII STL, with the given line ending, numbers written in
// several ways strtod reads
std::string ascii_two_triangles(const std::string& eol) {
  // one keyword group a line: the second facet starts on line 9, its last vertex is on line 13
  return "solid two triangles" + eol + "  facet normal 0 0 1" + eol + "    outer loop" + eol +
         "      vertex 0 0 0" + eol + "      vertex 1.0 0 0" + eol + "      vertex 0 1e0 0" + eol +
         "    endloop" + eol + "  endfacet" + eol + "  facet normal 0.0 0.0 -1.0" + eol + "    outer loop" + eol +
         "      vertex -2.5 .5 -0.0" + eol + "      vertex 1.024E+03 +0.125 3." + eol +
         "      vertex 6.103515625e-05 -7 1e-40" + eol + "    endloop" + eol + "  endfacet" + eol +
         "endsolid two triangles" + eol;
}

// the bytes of each float, so that -0.0f and 0.0f differ
std::vector<std::uint32_t> bits(const std::vector<float>& values) {
  std::vector<std::uint32_t> out;
  for (const float x : values) {
    std::uint32_t b;
    std::memcpy(&b, &x, sizeof b);
    out.push_back(b);
  }
  return out;
}

class StlMesh : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("eomgen_stl_mesh_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  std::string write(const std::string& name, const std::string& bytes) const {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path.string();
  }

  TriangleMesh read(const std::string& bytes) const { return read_stl(write("mesh.stl", bytes), max_triangles, max_bytes); }

  fs::path dir_;
};

TEST_F(StlMesh, BinaryGivesItsFloatsExactlyInFileOrder) {
  const TriangleMesh mesh = read(binary_stl(two_triangles));
  EXPECT_EQ(mesh.triangles(), 2u);
  EXPECT_EQ(bits(mesh.vertices), bits(flat(two_triangles)));
  EXPECT_TRUE(std::signbit(mesh.vertices[11]));  // -0.0f stays negative
}

TEST_F(StlMesh, BinaryWhoseHeaderStartsWithSolidIsReadAsBinary) {
  const TriangleMesh mesh = read(binary_stl(two_triangles, "solid exported by a CAD program"));
  EXPECT_EQ(bits(mesh.vertices), bits(flat(two_triangles)));
  // and with whitespace before it, as ASCII files may have
  EXPECT_EQ(bits(read(binary_stl(two_triangles, "  \nsolid x")).vertices), bits(flat(two_triangles)));
}

TEST_F(StlMesh, AsciiGivesTheSameFloatsAsBinary) {
  const TriangleMesh mesh = read(ascii_two_triangles("\n"));
  EXPECT_EQ(mesh.triangles(), 2u);
  EXPECT_EQ(bits(mesh.vertices), bits(flat(two_triangles)));
}

TEST_F(StlMesh, AsciiReadsCrlfCrAndAnyWhitespace) {
  EXPECT_EQ(bits(read(ascii_two_triangles("\r\n")).vertices), bits(flat(two_triangles)));
  EXPECT_EQ(bits(read(ascii_two_triangles("\r")).vertices), bits(flat(two_triangles)));
  EXPECT_EQ(bits(read(ascii_two_triangles(" \t\f\v\n\n")).vertices), bits(flat(two_triangles)));
  // a whole file on one line, no final newline: a name ends at the next keyword
  const TriangleMesh one = read(
      "solid\tpart one facet normal 0 0 1 outer loop vertex 1 2 3 vertex 4 5 6 vertex 7 8 9 endloop endfacet "
      "endsolid part one solid two endsolid two");
  EXPECT_EQ(one.vertices, (std::vector<float>{1, 2, 3, 4, 5, 6, 7, 8, 9}));
}

TEST_F(StlMesh, AsciiLineNumbersCountCrlfAsOneLine) {
  std::string text = ascii_two_triangles("\r\n");
  text.replace(text.find("vertex 6.1"), 6, "vertx");
  EXPECT_THROW_MESSAGE(read(text), MeshError, "line 13: expected 'vertex X Y Z', found 'vertx'");
}

TEST_F(StlMesh, AsciiKeywordsInAnyCaseAndSeveralSolids) {
  const TriangleMesh mesh = read(
      "SOLID upper\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 1 2 3\nVertex 4 5 6\nvertex 7 8 9\nENDLOOP\nENDFACET\n"
      "ENDSOLID upper\nsolid second\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\n"
      "endloop\nendfacet\nendsolid second\n");
  EXPECT_EQ(mesh.vertices, (std::vector<float>{1, 2, 3, 4, 5, 6, 7, 8, 9, 0, 0, 0, 0, 0, 1, 0, 1, 0}));
}

TEST_F(StlMesh, AsciiIgnoresTheNormalWhateverItHolds) {
  const TriangleMesh mesh = read(
      "solid n\nfacet normal nan -inf 1e999\nouter loop\nvertex 1 2 3\nvertex 4 5 6\nvertex 7 8 9\nendloop\nendfacet\n"
      "facet normal\nouter loop\nvertex 1 2 3\nvertex 4 5 6\nvertex 7 8 9\nendloop\nendfacet\nendsolid n\n");
  EXPECT_EQ(mesh.triangles(), 2u);
}

TEST_F(StlMesh, AsciiNumbersBelowFloatsRangeAreZeros) {
  const TriangleMesh mesh = read(
      "solid z\nfacet normal 0 0 1\nouter loop\nvertex 1e-50 -1e-50 0.0000000000000000000000000000000000000000000000001\n"
      "vertex 1e-400 -1e-99999999999999999999 0\nvertex 0e999999 1 2\nendloop\nendfacet\nendsolid z\n");
  EXPECT_EQ(bits(mesh.vertices), bits({0.0f, -0.0f, 0.0f, 0.0f, -0.0f, 0.0f, 0.0f, 1.0f, 2.0f}));
}

TEST_F(StlMesh, TruncatedBinaryIsRefused) {
  std::string bytes = binary_stl(two_triangles);
  bytes.resize(150);
  EXPECT_THROW_MESSAGE(read(bytes), MeshError, "it is truncated: 84 + 50 x 2 bytes expected, 150 found");
  // a header that starts with "solid" does not make it ASCII
  bytes = binary_stl(two_triangles, "solid x");
  bytes.resize(150);
  EXPECT_THROW_MESSAGE(read(bytes), MeshError, "it is truncated: 84 + 50 x 2 bytes expected, 150 found");
}

TEST_F(StlMesh, BinaryWithALyingCountIsRefusedBeforeAnyAllocation) {
  EXPECT_THROW_MESSAGE(read_stl(write("lying.stl", binary_stl(two_triangles, "", 0xffffffff)),
                                std::numeric_limits<std::size_t>::max(), max_bytes),
                       MeshError, "it is truncated: 84 + 50 x 4294967295 bytes expected, 184 found");
}

TEST_F(StlMesh, BinaryOfTheWrongSizeIsRefused) {
  EXPECT_THROW_MESSAGE(read(binary_stl(two_triangles) + std::string(7, '\0')), MeshError,
                       "it is neither binary STL (84 + 50 x 2 bytes expected, 191 found) nor ASCII STL "
                       "(no 'solid' at its start)");
  EXPECT_THROW_MESSAGE(read(binary_stl(two_triangles, "solid x", 1)), MeshError,
                       "it is neither binary STL (84 + 50 x 1 bytes expected, 184 found) nor ASCII STL "
                       "(a byte 0x00 at offset 7)");
  EXPECT_THROW_MESSAGE(read("not an STL"), MeshError,
                       "it is neither binary STL (at least 84 bytes expected, 10 found) nor ASCII STL "
                       "(no 'solid' at its start)");
  EXPECT_THROW_MESSAGE(read(""), MeshError, "it is empty");
}

TEST_F(StlMesh, TooManyTrianglesAreRefused) {
  const std::string binary = write("binary.stl", binary_stl(two_triangles));
  EXPECT_THROW_MESSAGE(read_stl(binary, 1, max_bytes), MeshError, "it has 2 triangles, more than the 1 read at most");
  EXPECT_EQ(read_stl(binary, 2, max_bytes).triangles(), 2u);
  const std::string ascii = write("ascii.stl", ascii_two_triangles("\n"));
  EXPECT_THROW_MESSAGE(read_stl(ascii, 1, max_bytes), MeshError,
                       "it has more than the 1 triangles read at most (another facet at line 9)");
  EXPECT_EQ(read_stl(ascii, 2, max_bytes).triangles(), 2u);
}

TEST_F(StlMesh, FileOverMaxBytesIsRefusedBeforeItIsRead) {
  const std::string path = write("big.stl", binary_stl(two_triangles));
  EXPECT_THROW_MESSAGE(read_stl(path, max_triangles, 183), MeshError, "it is too large: 184 bytes, at most 183 read");
  EXPECT_EQ(read_stl(path, max_triangles, 184).triangles(), 2u);
}

TEST_F(StlMesh, MissingFileAndDirectoryAreRefused) {
  EXPECT_THROW_MESSAGE(read_stl((dir_ / "missing.stl").string(), max_triangles, max_bytes), MeshError,
                       "it cannot be opened: there is no such file");
  EXPECT_THROW_MESSAGE(read_stl(dir_.string(), max_triangles, max_bytes), MeshError,
                       "it cannot be opened: it is not a regular file");
}

TEST_F(StlMesh, NonFiniteBinaryCoordinatesAreRefused) {
  std::vector<Triangle> triangles = two_triangles;
  triangles[1][4] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW_MESSAGE(read(binary_stl(triangles)), MeshError,
                       "the y coordinate of vertex 2 of triangle 2 is not finite (nan)");
  triangles = two_triangles;
  triangles[0][6] = -std::numeric_limits<float>::infinity();
  EXPECT_THROW_MESSAGE(read(binary_stl(triangles)), MeshError,
                       "the x coordinate of vertex 3 of triangle 1 is not finite (-inf)");
}

TEST_F(StlMesh, AsciiCoordinatesNotFiniteAsFloatAreRefused) {
  const auto with_z = [](const std::string& z) {
    return "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 " + z +
           "\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
  };
  // 1e39 is finite as a double, not as a float; 3.4028235e38 rounds to FLT_MAX, 3.4028236e38 up
  EXPECT_THROW_MESSAGE(read(with_z("1e39")), MeshError, "line 5: the coordinate '1e39' is not finite as a float");
  EXPECT_THROW_MESSAGE(read(with_z("-3.4028236e38")), MeshError,
                       "line 5: the coordinate '-3.4028236e38' is not finite as a float");
  EXPECT_EQ(read(with_z("3.4028235e38")).vertices[5], std::numeric_limits<float>::max());
  EXPECT_THROW_MESSAGE(read(with_z("1e999999999999999999999")), MeshError,
                       "line 5: the coordinate '1e999999999999999999999' is not finite as a float");
  EXPECT_THROW_MESSAGE(read(with_z(std::string(400, '9'))), MeshError,
                       HasSubstr("is not finite as a float"));
  EXPECT_THROW_MESSAGE(read(with_z("nan")), MeshError, "line 5: the coordinate 'nan' is not finite as a float");
  EXPECT_THROW_MESSAGE(read(with_z("-Infinity")), MeshError,
                       "line 5: the coordinate '-Infinity' is not finite as a float");
}

TEST_F(StlMesh, AsciiThatDoesNotParseSaysWhereAndWhat) {
  const auto with_z = [](const std::string& z) {
    return "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 " + z +
           "\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
  };
  for (const std::string number : {"1,5", "0x1p3", "1e", "--1", "+-1", "1.2.3", "1e5x", "e5", "."})
    EXPECT_THROW_MESSAGE(read(with_z(number)), MeshError,
                         "line 5: expected 'vertex X Y Z', found '" + number + "' for Z");
  EXPECT_THROW_MESSAGE(
      read("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0\nendloop\nendfacet\nendsolid s\n"), MeshError,
      "line 5: expected 'vertex X Y Z', found 'endloop' for Z");
  EXPECT_THROW_MESSAGE(read("solid s\nfacet normal 0 0 1\nloop\n"), MeshError,
                       "line 3: expected 'outer loop', found 'loop'");
  EXPECT_THROW_MESSAGE(read("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"), MeshError,
                       "line 5: expected 'vertex X Y Z', found the end of the file");
  EXPECT_THROW_MESSAGE(read("solid s\nface\n"), MeshError, "line 2: expected 'facet' or 'endsolid', found 'face'");
  EXPECT_THROW_MESSAGE(read("solid s\n"), MeshError, "line 2: expected 'facet' or 'endsolid', found the end of the file");
  EXPECT_THROW_MESSAGE(read("solidity\n"), MeshError, "line 1: expected 'solid', found 'solidity'");
  EXPECT_THROW_MESSAGE(read("solid s\nendsolid s\ntrailing words\n"), MeshError,
                       "line 3: expected 'solid' or the end of the file, found 'trailing'");
  EXPECT_THROW_MESSAGE(
      read("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendsolid s\n"),
      MeshError, "line 8: expected 'endfacet', found 'endsolid'");
  // a long token is cut short in the message, and bytes that are not printable are '?'
  EXPECT_THROW_MESSAGE(read("solid s\n" + std::string(100, 'x') + "\n"), MeshError,
                       "line 2: expected 'facet' or 'endsolid', found 'xxxxxxxxxxxxxxxxxxxxxxxx...'");
  EXPECT_THROW_MESSAGE(read("solid s\nfac\xc3\xa9t\n"), MeshError,
                       "line 2: expected 'facet' or 'endsolid', found 'fac??t'");
}

TEST_F(StlMesh, FacetWithoutExactlyThreeVerticesIsRefused) {
  EXPECT_THROW_MESSAGE(
      read("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid s\n"),
      MeshError, "line 6: the facet of line 2 has 2 vertices, 3 expected");
  EXPECT_THROW_MESSAGE(
      read("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 1 1 0\n"
           "endloop\nendfacet\nendsolid s\n"),
      MeshError, "line 7: the facet of line 2 has more than 3 vertices");
  EXPECT_THROW_MESSAGE(read("solid s\nfacet normal 0 0 1\nouter loop\nendloop\nendfacet\nendsolid s\n"), MeshError,
                       "line 4: the facet of line 2 has 0 vertices, 3 expected");
}

TEST_F(StlMesh, MeshWithoutTrianglesIsRefused) {
  EXPECT_THROW_MESSAGE(read("solid empty\nendsolid empty\n"), MeshError,
                       "it holds no triangle (an ASCII STL without a facet)");
  EXPECT_THROW_MESSAGE(read("  solid\r\nendsolid"), MeshError, "it holds no triangle (an ASCII STL without a facet)");
  EXPECT_THROW_MESSAGE(read(binary_stl({})), MeshError, "it holds no triangle (a binary STL stating 0)");
}

TEST_F(StlMesh, SameFileGivesSameFloats) {
  const std::string path = write("mesh.stl", ascii_two_triangles("\n"));
  EXPECT_EQ(little_endian_base64(read_stl(path, max_triangles, max_bytes).vertices),
            little_endian_base64(read_stl(path, max_triangles, max_bytes).vertices));
}

// any bytes give triangles or a MeshError: no crash, no hang, no other exception (a test
// failure names the seed). Random files, every prefix of a valid file, and valid files with
// bytes changed at random.
TEST_F(StlMesh, AnyBytesGiveTrianglesOrMeshError) {
  const auto survives = [&](const std::string& bytes) {
    try {
      const TriangleMesh mesh = read(bytes);
      for (const float x : mesh.vertices) EXPECT_TRUE(std::isfinite(x));
      EXPECT_GT(mesh.triangles(), 0u);
      EXPECT_LE(mesh.triangles(), max_triangles);
      EXPECT_EQ(mesh.vertices.size() % 9, 0u);
    } catch (const MeshError& e) {
      EXPECT_THAT(e.what(), ::testing::Not(HasSubstr(dir_.string())));  // the message has no path
    }
  };
  const std::string ascii = ascii_two_triangles("\r\n");
  const std::string binary = binary_stl(two_triangles, "solid x");
  for (const std::string* valid : {&ascii, &binary})
    for (std::size_t size = 0; size <= valid->size(); ++size) survives(valid->substr(0, size));
  const std::string alphabet = "solid facet normal outer loop vertex endloop endfacet endsolid 0123456789.eE+- \r\n\t";
  for (std::uint32_t seed = 1; seed <= 300; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> byte(0, 255);
    // random bytes, any length, sometimes at a binary STL's size for their count
    std::string bytes(std::uniform_int_distribution<std::size_t>(0, 400)(random), '\0');
    for (char& c : bytes) c = static_cast<char>(byte(random));
    survives(bytes);
    if (bytes.size() >= 84) {
      const auto n = static_cast<std::uint32_t>((bytes.size() - 84) / 50);
      bytes.resize(84 + 50 * n);
      for (int k = 0; k < 4; ++k) bytes[80 + k] = static_cast<char>((n >> (8 * k)) & 0xffu);
      survives(bytes);
    }
    // text from STL's words and characters
    std::string text = "solid ";
    for (std::size_t k = std::uniform_int_distribution<std::size_t>(0, 600)(random); k > 0; --k)
      text += alphabet[std::uniform_int_distribution<std::size_t>(0, alphabet.size() - 1)(random)];
    survives(text);
    // valid files with a few bytes changed
    for (const std::string* valid : {&ascii, &binary}) {
      std::string changed = *valid;
      for (int k = std::uniform_int_distribution<int>(1, 4)(random); k > 0; --k)
        changed[std::uniform_int_distribution<std::size_t>(0, changed.size() - 1)(random)] =
            static_cast<char>(byte(random));
      survives(changed);
    }
  }
}

TEST(StlMeshBase64, KnownFloats) {
  EXPECT_EQ(little_endian_base64({}), "");
  // 1.0f is 0x3f800000: bytes 00 00 80 3f
  EXPECT_EQ(little_endian_base64({1.0f}), "AACAPw==");
  // -2.5f is -1.25 x 2^1: sign 1, exponent 0x80, fraction 0x200000, so 0xc0200000; the bytes
  // 00 00 00 00 00 00 20 c0 are "AAAA" "AAAA" and 0x20 0xc0 = 001000 001100 0000(00) -> "IMA="
  EXPECT_EQ(little_endian_base64({0.0f, -2.5f}), "AAAAAAAAIMA=");
  // -0.0f keeps its sign bit; 0.1f is 0x3dcccccd; infinity is 0x7f800000
  EXPECT_EQ(little_endian_base64({-0.0f, 0.1f, std::numeric_limits<float>::infinity()}), "AAAAgM3MzD0AAIB/");
}

TEST(StlMeshBase64, PadsOneTwoOrNoBytesOfTheLastGroup) {
  // 4 bytes: a last group of 1 byte, "=="; 8 bytes: 2 bytes, "="; 12 bytes: none
  EXPECT_EQ(little_endian_base64({1.0f}), "AACAPw==");
  EXPECT_EQ(little_endian_base64({1.0f, 2.0f}), "AACAPwAAAEA=");
  EXPECT_EQ(little_endian_base64({1.0f, 2.0f, 3.0f}), "AACAPwAAAEAAAEBA");
}

TEST(StlMeshBase64, UsesTheWholeAlphabet) {
  // RFC 4648's table, value 0 to 63
  std::string expected;
  for (char c = 'A'; c <= 'Z'; ++c) expected += c;
  for (char c = 'a'; c <= 'z'; ++c) expected += c;
  for (char c = '0'; c <= '9'; ++c) expected += c;
  expected += "+/";
  // the 48 bytes whose 6-bit groups are 0, 1, ..., 63, packed as 12 little-endian floats
  std::vector<float> values;
  std::vector<unsigned char> bytes;
  for (std::uint32_t v = 0; v < 64; v += 4) {
    const std::uint32_t group = v << 18 | (v + 1) << 12 | (v + 2) << 6 | (v + 3);
    bytes.push_back(static_cast<unsigned char>(group >> 16));
    bytes.push_back(static_cast<unsigned char>(group >> 8));
    bytes.push_back(static_cast<unsigned char>(group));
  }
  for (std::size_t k = 0; k < bytes.size(); k += 4) {
    const std::uint32_t bits = bytes[k] | bytes[k + 1] << 8 | bytes[k + 2] << 16 | static_cast<std::uint32_t>(bytes[k + 3]) << 24;
    float x;
    std::memcpy(&x, &bits, sizeof x);
    values.push_back(x);
  }
  EXPECT_EQ(little_endian_base64(values), expected);
}

}  // namespace
}  // namespace eomgen
