// PLY meshes: one mesh decodes identically from ascii and both binary byte orders, every
// property type reads back in every format, each malformed file fails with its exact located
// message, and no byte-level corruption of a good file crashes the reader.
#include "pbrt_ext/util/ply.h"

#include "pbrt_ext/util/error.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <type_traits>
#include <utility>

namespace pbrt {
namespace {

const std::string kDataDir = PBRT_EXT_TEST_DATA_DIR;

std::string ReadFileBytes(const std::string &path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream contents;
    contents << file.rdbuf();
    return contents.str();
}

// The mesh tests/data/ply/make_test_files.py writes in three encodings.
void ExpectTestMesh(const PlyMesh &mesh) {
    std::vector<Point3f> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 1.5f, 0.25f}, {-0.5f, 0.5f, -1.25f}};
    std::vector<Normal3f> n = {{0, 0, 1}, {0, 0, 1}, {0, 1, 0}, {0, 1, 0}, {1, 0, 0}, {-1, 0, 0}};
    std::vector<Point2f> uv = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5f, 0.75f}, {0.25f, 0.125f}};
    EXPECT_EQ(mesh.p, p);
    EXPECT_EQ(mesh.n, n);
    EXPECT_EQ(mesh.uv, uv);
    EXPECT_EQ(mesh.triIndices, (std::vector<int>{3, 2, 4, 0, 3, 5}));
    // The file's quad (0 1 2 3) in bilinear-patch order.
    EXPECT_EQ(mesh.quadIndices, (std::vector<int>{0, 1, 3, 2}));
    // The file lists face_indices 7 (quad), 8, 9 (triangles): triangles' first.
    EXPECT_EQ(mesh.faceIndices, (std::vector<int>{8, 9, 7}));
}

TEST(PlyRead, AsciiWithCommentsAndSkippedElements) { ExpectTestMesh(ReadPly(kDataDir + "/ply/mesh_ascii.ply")); }

TEST(PlyRead, BinaryLittleEndianWithCrlfHeaderAndSkippedList) {
    ExpectTestMesh(ReadPly(kDataDir + "/ply/mesh_binary_le.ply"));
}

TEST(PlyRead, BinaryBigEndianWithFacesBeforeVertices) {
    ExpectTestMesh(ReadPly(kDataDir + "/ply/mesh_binary_be.ply"));
}

TEST(PlyRead, PositionsOnlyLeaveOptionalArraysEmpty) {
    PlyMesh mesh = ReadPly(kDataDir + "/ply/triangle.ply");
    EXPECT_EQ(mesh.p, (std::vector<Point3f>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
    EXPECT_EQ(mesh.triIndices, (std::vector<int>{0, 1, 2}));
    EXPECT_TRUE(mesh.n.empty());
    EXPECT_TRUE(mesh.uv.empty());
    EXPECT_TRUE(mesh.quadIndices.empty());
    EXPECT_TRUE(mesh.faceIndices.empty());
}

TEST(PlyRead, IncompleteNormalsOrUVsAreIgnored) {
    PlyMesh mesh = ParsePly("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                            "property float y\nproperty float z\nproperty float nx\nproperty float u\n"
                            "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                            "0 0 0 1 1\n1 0 0 1 1\n0 1 0 1 1\n3 0 1 2\n",
                            "incomplete.ply");
    EXPECT_EQ(mesh.p.size(), 3u);
    EXPECT_TRUE(mesh.n.empty());
    EXPECT_TRUE(mesh.uv.empty());
}

TEST(PlyRead, ElementsWithoutPropertiesAreSkipped) {
    for (std::string format : {"ascii", "binary_little_endian"}) {
        SCOPED_TRACE(format);
        std::string ply = "ply\nformat " + format + " 1.0\nelement vertex 3\nproperty uchar x\n"
                          "property uchar y\nproperty uchar z\nelement nothing 1000000\n"
                          "element face 1\nproperty list uchar uchar vertex_indices\nend_header\n";
        ply += format == "ascii" ? "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
                                 : std::string("\0\0\0\1\0\0\0\1\0\3\0\1\2", 13);
        PlyMesh mesh = ParsePly(ply, "m.ply");
        EXPECT_EQ(mesh.p, (std::vector<Point3f>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
        EXPECT_EQ(mesh.triIndices, (std::vector<int>{0, 1, 2}));
    }
}

// ---- Every property type in every format --------------------------------------------------------

// Appends values to a PLY body in one of the three encodings.
class BodyWriter {
  public:
    explicit BodyWriter(std::string format) : format(std::move(format)) {}

    template <typename T>
    void Put(T v) {
        if (format == "ascii") {
            std::ostringstream s;
            s.precision(17);
            s << +v << ' ';  // + prints (u)int8_t as a number
            body += s.str();
            return;
        }
        char bytes[sizeof(T)];
        std::memcpy(bytes, &v, sizeof(T));
        if ((format == "binary_big_endian") != (std::endian::native == std::endian::big))
            std::reverse(bytes, bytes + sizeof(T));
        body.append(bytes, sizeof(T));
    }
    void EndLine() {
        if (format == "ascii") body += '\n';
    }

    std::string format, body;
};

// x of type T at its extremes; for integer T the face list uses T for its count and items too.
template <typename T>
void CheckPropertyType(const std::string &typeName) {
    constexpr bool integer = std::is_integral_v<T>;
    const T xs[3] = {T(0), T(100), integer ? std::numeric_limits<T>::max() : T(-2.5)};
    const std::string list = integer ? typeName + " " + typeName : "uchar int";
    for (std::string format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
        SCOPED_TRACE(typeName + " in " + format);
        BodyWriter w(format);
        for (int i = 0; i < 3; ++i) {
            w.Put(xs[i]);
            w.Put(float(i));
            w.Put(0.f);
            w.EndLine();
        }
        if constexpr (integer) {
            w.Put(T(3));
            for (T index : {T(2), T(1), T(0)}) w.Put(index);
        } else {
            w.Put(uint8_t(3));
            for (int index : {2, 1, 0}) w.Put(index);
        }
        w.EndLine();
        std::string ply = "ply\nformat " + format + " 1.0\nelement vertex 3\nproperty " + typeName +
                          " x\nproperty float y\nproperty float z\nelement face 1\nproperty list " +
                          list + " vertex_indices\nend_header\n" + w.body;
        PlyMesh mesh = ParsePly(ply, "types.ply");
        ASSERT_EQ(mesh.p.size(), 3u);
        for (int i = 0; i < 3; ++i) {
            EXPECT_EQ(mesh.p[i].x, float(xs[i]));
            EXPECT_EQ(mesh.p[i].y, float(i));
        }
        EXPECT_EQ(mesh.triIndices, (std::vector<int>{2, 1, 0}));
    }
}

TEST(PlyRead, EveryPropertyTypeInEveryFormat) {
    CheckPropertyType<int8_t>("char");
    CheckPropertyType<uint8_t>("uchar");
    CheckPropertyType<int16_t>("short");
    CheckPropertyType<uint16_t>("ushort");
    CheckPropertyType<int32_t>("int");
    CheckPropertyType<uint32_t>("uint");
    CheckPropertyType<float>("float");
    CheckPropertyType<double>("double");
    CheckPropertyType<int8_t>("int8");
    CheckPropertyType<uint8_t>("uint8");
    CheckPropertyType<int16_t>("int16");
    CheckPropertyType<uint16_t>("uint16");
    CheckPropertyType<int32_t>("int32");
    CheckPropertyType<uint32_t>("uint32");
    CheckPropertyType<float>("float32");
    CheckPropertyType<double>("float64");
}

// ---- Malformed files: exact messages ------------------------------------------------------------

struct BadFile {
    const char *name;
    int line, column;
    const char *message;
};

// clang-format off
const BadFile kBadFiles[] = {
    {"bad_magic", 1, 1, "not a PLY file; expected \"ply\" on the first line"},
    {"unknown_format", 2, 8, "unknown format \"binary_middle_endian\"; expected ascii, binary_little_endian or binary_big_endian"},
    {"bad_version", 2, 14, "unsupported PLY version \"2.0\"; expected 1.0"},
    {"unknown_type", 5, 10, "unknown property type \"int128\"; expected char, uchar, short, ushort, int, uint, float, double, int8, uint8, int16, uint16, int32, uint32, float32 or float64"},
    {"missing_y", 3, 1, "element \"vertex\" has no \"y\" property; expected x, y and z"},
    {"no_faces", 7, 1, "no faces; expected a non-empty \"face\" element"},
    {"no_vertex_indices", 7, 1, "element \"face\" has no \"vertex_indices\" property; expected \"property list uchar int vertex_indices\""},
    {"float_indices", 8, 1, "property \"vertex_indices\" is not a list of integers; expected e.g. \"property list uchar int vertex_indices\""},
    {"float_count", 8, 15, "list count type \"float\" is not an integer type; expected e.g. uchar"},
    {"missing_end_header", 9, 1, "unexpected end of file in the header; expected end_header"},
    {"missing_format", 8, 1, "end_header before any format line; expected e.g. \"format binary_little_endian 1.0\""},
    {"property_before_element", 2, 1, "property before any element; expected \"element <name> <count>\" first"},
    {"unknown_keyword", 9, 1, "unknown header keyword \"edn_header\"; expected format, element, property, comment, obj_info or end_header"},
    {"bad_element_count", 3, 16, "invalid element count \"-3\"; expected a non-negative integer"},
    {"duplicate_element", 7, 9, "duplicate element \"vertex\"; expected each element once"},
    {"duplicate_property", 6, 16, "duplicate property \"x\" in element \"vertex\"; expected each property once"},
    {"malformed_property", 6, 1, "malformed line; expected \"property <type> <name>\""},
    {"list_position", 6, 1, "property \"z\" is a list; expected a scalar"},
    {"truncated_ascii", 14, 1, "face[0]: unexpected end of file; expected 1 instances of \"face\" as the header declares"},
    {"bad_value", 11, 3, "vertex[1]: invalid float value \"zero\"; expected a number"},
    {"nonfinite", 12, 3, "vertex[2]: non-finite value in property \"y\"; expected a finite number"},
    {"uchar_overflow", 13, 1, "face[0]: invalid uchar value \"300\"; expected an integer in [0, 255]"},
    {"index_out_of_range", 13, 7, "face[0]: vertex index 3 is out of range; expected 0 to 2"},
    {"negative_index", 13, 5, "face[0]: vertex index -1 is out of range; expected 0 to 2"},
    {"pentagon", 13, 1, "face[0]: 5 vertices; expected 3 or 4 (only triangles and quads are supported)"},
    {"trailing_data", 14, 1, "unexpected data after the last element; expected the element counts declared in the header"},
    // Binary bodies have no lines: the message names the offending value's byte offset.
    {"truncated_binary", 0, 0, "face[0] at byte 214: unexpected end of file; expected 1 instances of \"face\" as the header declares"},
    {"huge_count", 3, 1, "element \"vertex\" declares 1000000000 instances; expected at most what the remaining 36 bytes can hold"},
    {"binary_index_out_of_range", 0, 0, "face[0] at byte 214: vertex index 7 is out of range; expected 0 to 2"},
    {"binary_negative_count", 0, 0, "face[0] at byte 204: negative list length -3; expected 0 or more"},
    {"duplicate_format", 3, 1, "duplicate format line; expected exactly one"},
    {"malformed_format", 2, 1, "malformed line; expected \"format <ascii|binary_little_endian|binary_big_endian> 1.0\""},
    {"malformed_element", 3, 1, "malformed line; expected \"element <name> <count>\""},
    {"malformed_list", 8, 1, "malformed line; expected \"property list <count type> <item type> <name>\""},
    {"word_element_count", 3, 16, "invalid element count \"three\"; expected a non-negative integer"},
    {"scalar_indices", 8, 1, "property \"vertex_indices\" is not a list of integers; expected e.g. \"property list uchar int vertex_indices\""},
    {"list_face_indices", 9, 1, "property \"face_indices\" is not an integer scalar; expected e.g. \"property int face_indices\""},
    {"float_face_indices", 9, 1, "property \"face_indices\" is not an integer scalar; expected e.g. \"property int face_indices\""},
    {"face_index_out_of_range", 14, 9, "face[0]: face_indices value 4294967295 is out of range; expected 0 to 2147483647"},
    // Without a vertex element the error is at end_header, where the header ends without one.
    {"no_vertex_element", 5, 1, "no vertices; expected a non-empty \"vertex\" element"},
    {"empty_vertex", 3, 1, "no vertices; expected a non-empty \"vertex\" element"},
    {"empty_face", 7, 1, "no faces; expected a non-empty \"face\" element"},
    {"too_many_vertices", 3, 1, "too many vertices; expected at most 2147483647"},
    {"empty", 1, 1, "not a PLY file; expected \"ply\" on the first line"},
    // The header's last line lacks its newline, and no body follows.
    {"header_only", 3, 1, "element \"vertex\" declares 3 instances; expected at most what the remaining 0 bytes can hold"},
    {"uchar_negative", 13, 1, "face[0]: invalid uchar value \"-1\"; expected an integer in [0, 255]"},
    {"fractional_index", 13, 5, "face[0]: invalid int value \"1.5\"; expected an integer in [-2147483648, 2147483647]"},
    {"bare_property", 6, 1, "malformed line; expected \"property <type> <name>\""},
    {"binary_nonfinite", 0, 0, "vertex[1] at byte 185: non-finite value in property \"y\"; expected a finite number"},
    {"binary_truncated_skip", 0, 0, "face[0] at byte 253: unexpected end of file; expected 1 instances of \"face\" as the header declares"},
};
// clang-format on

TEST(PlyErrors, EachMalformedFileHasItsLocatedMessage) {
    for (const BadFile &bad : kBadFiles) {
        std::string path = kDataDir + "/bad/ply_" + bad.name + ".ply";
        // fmt, not +: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string at -O3.
        std::string where = bad.line ? fmt::format(":{}:{}", bad.line, bad.column) : "";
        std::string expected = fmt::format("{}{}: error: {}", path, where, bad.message);
        try {
            ReadPly(path);
            ADD_FAILURE() << path << " was accepted";
        } catch (const ParseError &e) {
            EXPECT_EQ(std::string(e.what()), expected);
            EXPECT_EQ(e.loc.line, bad.line);
        }
    }
}

TEST(PlyErrors, MissingFileIsAParseError) {
    std::string path = kDataDir + "/ply/no_such_file.ply";
    try {
        ReadPly(path);
        ADD_FAILURE() << "missing file was accepted";
    } catch (const ParseError &e) {
        EXPECT_EQ(std::string(e.what()),
                  path + ": error: cannot open the PLY file: No such file or directory");
    }
}

// Only a regular file has a size to read: a directory or a device is refused before any read.
TEST(PlyErrors, DirectoryAndDeviceAreParseErrors) {
    const std::pair<std::string, std::string> cases[] = {
        {kDataDir + "/ply", "Is a directory"},
        {"/dev/zero", "not a regular file (a device or pipe may never end); expected a file"}};
    for (const auto &[path, why] : cases) {
        try {
            ReadPly(path);
            ADD_FAILURE() << path << " was accepted";
        } catch (const ParseError &e) {
            EXPECT_EQ(std::string(e.what()), path + ": error: cannot open the PLY file: " + why);
        }
    }
}

// A sysfs file reports a size of 4096 bytes and then reads fewer: the read itself fails.
TEST(PlyErrors, ShortReadIsAParseError) {
    const std::string path = "/sys/devices/system/cpu/online";
    if (!std::filesystem::is_regular_file(path)) GTEST_SKIP() << path << " is not available";
    try {
        ReadPly(path);
        ADD_FAILURE() << path << " was accepted";
    } catch (const ParseError &e) {
        EXPECT_EQ(std::string(e.what()), path + ": error: cannot read the PLY file");
    }
}

// ---- Robustness: corrupted good files never crash -----------------------------------------------

// Anything decoded from corrupted input must still be a consistent mesh.
void ExpectConsistent(const PlyMesh &mesh) {
    size_t nv = mesh.p.size();
    EXPECT_TRUE(mesh.n.empty() || mesh.n.size() == nv);
    EXPECT_TRUE(mesh.uv.empty() || mesh.uv.size() == nv);
    EXPECT_EQ(mesh.triIndices.size() % 3, 0u);
    EXPECT_EQ(mesh.quadIndices.size() % 4, 0u);
    for (const std::vector<int> *indices : {&mesh.triIndices, &mesh.quadIndices})
        for (int i : *indices) EXPECT_TRUE(i >= 0 && size_t(i) < nv) << i;
    EXPECT_TRUE(mesh.faceIndices.empty() ||
                mesh.faceIndices.size() == mesh.triIndices.size() / 3 + mesh.quadIndices.size() / 4);
}

// One random corruption: overwrite, insert or delete a few bytes, or truncate.
std::string Mutate(std::string s, std::mt19937 &rng) {
    auto pick = [&](size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng); };
    auto randomByte = [&] { return char(pick(256)); };
    switch (pick(4)) {
    case 0:
        for (size_t k = pick(4) + 1; k > 0; --k) s[pick(s.size())] = randomByte();
        break;
    case 1: s.insert(s.begin() + pick(s.size() + 1), randomByte()); break;
    case 2: s.erase(pick(s.size()), pick(8) + 1); break;
    default: s.resize(pick(s.size())); break;
    }
    return s;
}

TEST(PlyRobustness, CorruptedFilesThrowParseErrorOrDecodeConsistently) {
    constexpr int kMutationsPerFile = 4000;
    int accepted = 0, rejected = 0;
    for (const char *name : {"mesh_ascii", "mesh_binary_le", "mesh_binary_be", "triangle"}) {
        std::string good = ReadFileBytes(kDataDir + "/ply/" + name + ".ply");
        ASSERT_FALSE(good.empty()) << name;
        std::mt19937 rng(12345);
        for (int i = 0; i < kMutationsPerFile; ++i) {
            std::string bad = Mutate(good, rng);
            try {
                ExpectConsistent(ParsePly(bad, name));
                ++accepted;
            } catch (const ParseError &) {
                ++rejected;
            }
        }
    }
    // Both outcomes occur, so the mutations exercise the header and the body.
    EXPECT_GT(accepted, 0);
    EXPECT_GT(rejected, 0);
}

}  // namespace
}  // namespace pbrt
