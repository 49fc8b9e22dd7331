// PLY decoding: the header becomes a list of typed elements, each property tagged with its role
// in the mesh; the body is then walked once with a cursor for the file's encoding. Every read is
// bounds-checked, so no input can make the reader run past the buffer, loop without consuming
// bytes, or allocate more than a small multiple of the file's size.
#include "pbrt_ext/util/ply.h"

#include "pbrt_ext/util/error.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/resourcelimits.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <climits>
#include <cstring>
#include <fstream>
#include <memory>
#include <optional>

namespace pbrt {
namespace {

// Scalar types in the order of their sizes' table below.
enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct PlyTypeName {
    std::string_view name;
    PlyType type;
};
constexpr PlyTypeName kPlyTypeNames[] = {
    {"char", PlyType::Int8},     {"uchar", PlyType::UInt8},    {"short", PlyType::Int16},
    {"ushort", PlyType::UInt16}, {"int", PlyType::Int32},      {"uint", PlyType::UInt32},
    {"float", PlyType::Float32}, {"double", PlyType::Float64}, {"int8", PlyType::Int8},
    {"uint8", PlyType::UInt8},   {"int16", PlyType::Int16},    {"uint16", PlyType::UInt16},
    {"int32", PlyType::Int32},   {"uint32", PlyType::UInt32},  {"float32", PlyType::Float32},
    {"float64", PlyType::Float64}};

int SizeOf(PlyType t) {
    constexpr int sizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
    return sizes[int(t)];
}
bool IsInteger(PlyType t) { return t < PlyType::Float32; }
std::string_view NameOf(PlyType t) { return kPlyTypeNames[int(t)].name; }

// The range of an integer type, for validating ascii values.
std::pair<int64_t, int64_t> IntegerRange(PlyType t) {
    switch (t) {
    case PlyType::Int8: return {INT8_MIN, INT8_MAX};
    case PlyType::UInt8: return {0, UINT8_MAX};
    case PlyType::Int16: return {INT16_MIN, INT16_MAX};
    case PlyType::UInt16: return {0, UINT16_MAX};
    case PlyType::Int32: return {INT32_MIN, INT32_MAX};
    default: return {0, UINT32_MAX};
    }
}

// What the mesh takes from a property; Skip for everything it does not use.
enum class Role { Skip, Px, Py, Pz, Nx, Ny, Nz, U, V, VertexIndices, FaceIndex };

struct PlyProperty {
    std::string name;
    PlyType type;                      // of the value, or of a list's items
    std::optional<PlyType> countType;  // set for lists
    FileLoc loc;
    Role role = Role::Skip;
};

struct PlyElement {
    std::string name;
    int64_t count = 0;
    std::vector<PlyProperty> properties;
    FileLoc loc;
};

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyHeader {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
    size_t bodyOffset = 0;
    int bodyLine = 1;
    FileLoc endLoc;  // of end_header: where whole-header problems are reported
};

// ---- Header ------------------------------------------------------------------------------------

struct Word {
    std::string_view text;
    int column;
};

std::vector<Word> SplitWords(std::string_view line) {
    std::vector<Word> words;
    size_t i = 0;
    while (i < line.size()) {
        if (line[i] == ' ' || line[i] == '\t') {
            ++i;
            continue;
        }
        size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
        words.push_back({line.substr(start, i - start), int(start) + 1});
    }
    return words;
}

template <typename T>
bool ParseWhole(std::string_view s, T *value) {
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), *value);
    return ec == std::errc() && end == s.data() + s.size();
}

class HeaderReader {
  public:
    HeaderReader(std::string_view contents, const std::string &filename)
        : contents(contents), filename(filename) {}

    PlyHeader Read() {
        if (!NextLine() || line != "ply")
            Fail(1, "not a PLY file; expected \"ply\" on the first line");
        bool haveFormat = false;
        while (NextLine()) {
            std::vector<Word> words = SplitWords(line);
            if (words.empty() || words[0].text == "comment" || words[0].text == "obj_info")
                continue;
            std::string_view keyword = words[0].text;
            if (keyword == "format") {
                if (haveFormat) Fail(1, "duplicate format line; expected exactly one");
                ReadFormat(words);
                haveFormat = true;
            } else if (keyword == "element") {
                ReadElement(words);
            } else if (keyword == "property") {
                ReadProperty(words);
            } else if (keyword == "end_header") {
                if (!haveFormat)
                    Fail(1, "end_header before any format line; expected e.g. "
                            "\"format binary_little_endian 1.0\"");
                header.bodyOffset = offset;
                header.bodyLine = lineNumber + 1;
                header.endLoc = Loc(1);
                return std::move(header);
            } else {
                Fail(1, "unknown header keyword \"{}\"; expected format, element, property, "
                        "comment, obj_info or end_header", keyword);
            }
        }
        Fail(1, "unexpected end of file in the header; expected end_header");
    }

  private:
    // Advances to the next line (without its "\n" or "\r\n"); false at the end of the file.
    bool NextLine() {
        if (offset >= contents.size()) {
            ++lineNumber;
            return false;
        }
        size_t newline = contents.find('\n', offset);
        size_t end = newline == std::string_view::npos ? contents.size() : newline;
        line = contents.substr(offset, end - offset);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        offset = newline == std::string_view::npos ? contents.size() : newline + 1;
        ++lineNumber;
        return true;
    }

    FileLoc Loc(int column) const { return FileLoc{filename, lineNumber, column}; }
    // Messages go through fmt: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
    template <typename... Args>
    [[noreturn]] void Fail(int column, fmt::format_string<Args...> format, Args &&...args) const {
        throw ParseError(Loc(column), fmt::format(format, std::forward<Args>(args)...));
    }
    void ExpectWords(const std::vector<Word> &words, size_t n, const char *usage) const {
        if (words.size() != n) Fail(1, "malformed line; expected {}", usage);
    }

    void ReadFormat(const std::vector<Word> &words) {
        ExpectWords(words, 3, "\"format <ascii|binary_little_endian|binary_big_endian> 1.0\"");
        if (words[1].text == "ascii")
            header.format = PlyFormat::Ascii;
        else if (words[1].text == "binary_little_endian")
            header.format = PlyFormat::BinaryLittleEndian;
        else if (words[1].text == "binary_big_endian")
            header.format = PlyFormat::BinaryBigEndian;
        else
            Fail(words[1].column, "unknown format \"{}\"; expected ascii, binary_little_endian or "
                                  "binary_big_endian", words[1].text);
        if (words[2].text != "1.0")
            Fail(words[2].column, "unsupported PLY version \"{}\"; expected 1.0", words[2].text);
    }

    void ReadElement(const std::vector<Word> &words) {
        ExpectWords(words, 3, "\"element <name> <count>\"");
        PlyElement element;
        element.name = words[1].text;
        element.loc = Loc(1);
        for (const PlyElement &e : header.elements)
            if (e.name == element.name)
                Fail(words[1].column, "duplicate element \"{}\"; expected each element once",
                     element.name);
        if (!ParseWhole(words[2].text, &element.count) || element.count < 0)
            Fail(words[2].column, "invalid element count \"{}\"; expected a non-negative integer",
                 words[2].text);
        header.elements.push_back(std::move(element));
    }

    PlyType ReadType(const Word &word) const {
        for (const PlyTypeName &t : kPlyTypeNames)
            if (t.name == word.text) return t.type;
        Fail(word.column, "unknown property type \"{}\"; expected char, uchar, short, ushort, int, "
                          "uint, float, double, int8, uint8, int16, uint16, int32, uint32, float32 "
                          "or float64", word.text);
    }

    void ReadProperty(const std::vector<Word> &words) {
        if (header.elements.empty())
            Fail(1, "property before any element; expected \"element <name> <count>\" first");
        PlyProperty property;
        property.loc = Loc(1);
        if (words.size() >= 2 && words[1].text == "list") {
            ExpectWords(words, 5, "\"property list <count type> <item type> <name>\"");
            property.countType = ReadType(words[2]);
            if (!IsInteger(*property.countType))
                Fail(words[2].column, "list count type \"{}\" is not an integer type; expected e.g. uchar",
                     words[2].text);
            property.type = ReadType(words[3]);
            property.name = words[4].text;
        } else {
            ExpectWords(words, 3, "\"property <type> <name>\"");
            property.type = ReadType(words[1]);
            property.name = words[2].text;
        }
        PlyElement &element = header.elements.back();
        for (const PlyProperty &p : element.properties)
            if (p.name == property.name)
                Fail(words.back().column, "duplicate property \"{}\" in element \"{}\"; expected each "
                                          "property once", property.name, element.name);
        element.properties.push_back(std::move(property));
    }

    std::string_view contents;
    const std::string &filename;
    size_t offset = 0;
    int lineNumber = 0;
    std::string_view line;
    PlyHeader header;
};

// ---- Roles: what the mesh needs from the header --------------------------------------------------

PlyElement *FindElement(PlyHeader &header, std::string_view name) {
    for (PlyElement &e : header.elements)
        if (e.name == name) return &e;
    return nullptr;
}

PlyProperty *FindProperty(PlyElement &element, std::string_view name) {
    for (PlyProperty &p : element.properties)
        if (p.name == name) return &p;
    return nullptr;
}

[[noreturn]] void FailAtProperty(const PlyProperty &p, const std::string &message) {
    throw ParseError(p.loc, fmt::format("property \"{}\" {}", p.name, message));
}

// Tags the properties named by names with roles if all of them exist; they must be scalars.
bool AssignRoles(PlyElement &element, std::initializer_list<std::string_view> names,
                 std::initializer_list<Role> roles) {
    std::vector<PlyProperty *> found;
    for (std::string_view name : names)
        if (PlyProperty *p = FindProperty(element, name)) found.push_back(p);
    if (found.size() != names.size()) return false;
    auto role = roles.begin();
    for (PlyProperty *p : found) {
        if (p->countType) FailAtProperty(*p, "is a list; expected a scalar");
        p->role = *role++;
    }
    return true;
}

void AssignVertexRoles(PlyElement &vertex) {
    for (std::string_view name : {"x", "y", "z"})
        if (!FindProperty(vertex, name))
            throw ParseError(vertex.loc, fmt::format("element \"vertex\" has no \"{}\" property; "
                                                     "expected x, y and z", name));
    AssignRoles(vertex, {"x", "y", "z"}, {Role::Px, Role::Py, Role::Pz});
    AssignRoles(vertex, {"nx", "ny", "nz"}, {Role::Nx, Role::Ny, Role::Nz});
    for (auto [u, v] : {std::pair{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"},
                        {"texture_s", "texture_t"}})
        if (AssignRoles(vertex, {u, v}, {Role::U, Role::V})) break;
}

void AssignFaceRoles(PlyElement &face) {
    PlyProperty *indices = FindProperty(face, "vertex_indices");
    if (!indices)
        throw ParseError(face.loc, "element \"face\" has no \"vertex_indices\" property; "
                                   "expected \"property list uchar int vertex_indices\"");
    if (!indices->countType || !IsInteger(indices->type))
        FailAtProperty(*indices, "is not a list of integers; expected e.g. "
                                 "\"property list uchar int vertex_indices\"");
    indices->role = Role::VertexIndices;
    if (PlyProperty *faceIndex = FindProperty(face, "face_indices")) {
        if (faceIndex->countType || !IsInteger(faceIndex->type))
            FailAtProperty(*faceIndex, "is not an integer scalar; expected e.g. \"property int face_indices\"");
        faceIndex->role = Role::FaceIndex;
    }
}

// Finds the vertex and face elements (pbrt-v4 requires both to be non-empty) and tags roles.
void AssignRoles(PlyHeader &header) {
    PlyElement *vertex = FindElement(header, "vertex");
    PlyElement *face = FindElement(header, "face");
    if (!vertex || vertex->count == 0)
        throw ParseError(vertex ? vertex->loc : header.endLoc,
                         "no vertices; expected a non-empty \"vertex\" element");
    if (!face || face->count == 0)
        throw ParseError(face ? face->loc : header.endLoc,
                         "no faces; expected a non-empty \"face\" element");
    if (vertex->count > INT_MAX)
        throw ParseError(vertex->loc, "too many vertices; expected at most 2147483647");
    AssignVertexRoles(*vertex);
    AssignFaceRoles(*face);
}

// Rejects element counts the body cannot possibly hold before anything is allocated for them:
// every property takes at least a binary value (a list, its count) or an ascii token and its
// separator per instance, so the body bounds the total. Only the file's last ascii token may
// lack its separator.
void CheckCountsFit(const PlyHeader &header, size_t bodySize) {
    bool ascii = header.format == PlyFormat::Ascii;
    uint64_t left = bodySize;
    for (const PlyElement &e : header.elements) {
        uint64_t minSize = 0;
        for (const PlyProperty &p : e.properties)
            minSize += ascii ? 2 : SizeOf(p.countType.value_or(p.type));
        if (minSize == 0) continue;
        if (uint64_t(e.count) > (left + (ascii ? 1 : 0)) / minSize)
            throw ParseError(e.loc, fmt::format("element \"{}\" declares {} instances; expected at "
                                                "most what the remaining {} bytes can hold",
                                                e.name, e.count, left));
        left -= std::min(left, uint64_t(e.count) * minSize);
    }
}

bool HasRole(const PlyElement &element, Role role) {
    return std::any_of(element.properties.begin(), element.properties.end(),
                       [role](const PlyProperty &p) { return p.role == role; });
}

// The mesh's memory, checked before it is allocated: the body may be a small fraction of it
// (three one-byte coordinates become a 12-byte point). Per vertex a point and, where the file
// has them, a normal and uv; per face up to four indices and a face index.
void CheckMeshMemory(const PlyHeader &header) {
    for (const PlyElement &e : header.elements) {
        uint64_t bytesPerInstance = 0;
        if (e.name == "vertex")
            bytesPerInstance = sizeof(Point3f) + (HasRole(e, Role::Nx) ? sizeof(Normal3f) : 0) +
                               (HasRole(e, Role::U) ? sizeof(Point2f) : 0);
        else if (e.name == "face")
            bytesPerInstance = 4 * sizeof(int) + (HasRole(e, Role::FaceIndex) ? sizeof(int) : 0);
        else
            continue;  // skipped while reading
        CheckMemory(e.loc, fmt::format("element \"{}\" of {} instances", e.name, e.count),
                    SaturatingProduct({uint64_t(e.count), bytesPerInstance}));
    }
}

// ---- Body cursors ----------------------------------------------------------------------------------

// Which instance of which element is being read, for messages such as "face[12]: ...".
struct BodyPosition {
    const PlyElement *element = nullptr;
    int64_t instance = 0;
    std::string Describe() const { return fmt::format("{}[{}]", element->name, instance); }
    std::string Truncated() const {
        return fmt::format("unexpected end of file; expected {} instances of \"{}\" as the header "
                           "declares", element->count, element->name);
    }
};

// Binary values; a failure has no line, so it names the byte offset in the file instead.
class BinaryCursor {
  public:
    BinaryCursor(std::string_view body, size_t bodyOffset, bool swapBytes, const std::string &filename)
        : begin(reinterpret_cast<const unsigned char *>(body.data())), p(begin),
          end(begin + body.size()), valueStart(begin), bodyOffset(bodyOffset), swapBytes(swapBytes), filename(filename) {}

    double Read(PlyType t) {
        valueStart = p;
        switch (t) {
        case PlyType::Int8: return Load<int8_t>();
        case PlyType::UInt8: return Load<uint8_t>();
        case PlyType::Int16: return Load<int16_t>();
        case PlyType::UInt16: return Load<uint16_t>();
        case PlyType::Int32: return Load<int32_t>();
        case PlyType::UInt32: return Load<uint32_t>();
        case PlyType::Float32: return Load<float>();
        case PlyType::Float64: return Load<double>();
        }
        return 0;
    }

    void Skip(PlyType t, int64_t n) {
        valueStart = p;
        if (uint64_t(end - p) < uint64_t(n) * SizeOf(t)) Fail(position.Truncated());
        p += n * SizeOf(t);
    }

    // Binary writers may pad the end of the file; only ascii checks for leftovers.
    void ExpectEnd() const {}

    [[noreturn]] void Fail(const std::string &message) const {
        throw ParseError(FileLoc{filename, 0, 0},
                         fmt::format("{} at byte {}: {}", position.Describe(),
                                     bodyOffset + (valueStart - begin), message));
    }

    BodyPosition position;

  private:
    // A fixed-size copy per type, which compiles to a plain load (and byte swap).
    template <typename T>
    double Load() {
        if (size_t(end - p) < sizeof(T)) Fail(position.Truncated());
        unsigned char bytes[sizeof(T)];
        std::memcpy(bytes, p, sizeof(T));
        p += sizeof(T);
        if (swapBytes) std::reverse(bytes, bytes + sizeof(T));
        T value;
        std::memcpy(&value, bytes, sizeof(T));
        return double(value);
    }

    const unsigned char *begin, *p, *end, *valueStart;
    size_t bodyOffset;
    bool swapBytes;
    const std::string &filename;
};

// Whitespace-separated ascii values; a failure is located at the offending token.
class AsciiCursor {
  public:
    AsciiCursor(std::string_view body, int firstLine, const std::string &filename)
        : p(body.data()), end(body.data() + body.size()), lineStart(p), line(firstLine),
          filename(filename) {}

    double Read(PlyType t) {
        std::string_view token = NextToken();
        if (IsInteger(t)) {
            auto [lo, hi] = IntegerRange(t);
            int64_t v;
            if (!ParseWhole(token, &v) || v < lo || v > hi)
                Fail(fmt::format("invalid {} value \"{}\"; expected an integer in [{}, {}]",
                                 NameOf(t), token, lo, hi));
            return double(v);
        }
        double v;
        if (!ParseWhole(token, &v))
            Fail(fmt::format("invalid {} value \"{}\"; expected a number", NameOf(t), token));
        return v;
    }

    void Skip(PlyType t, int64_t n) {
        for (int64_t i = 0; i < n; ++i) Read(t);
    }

    void ExpectEnd() {
        SkipWhitespace();
        tokenStart = p;
        if (p != end)
            throw ParseError(TokenLoc(), "unexpected data after the last element; expected the "
                                         "element counts declared in the header");
    }

    [[noreturn]] void Fail(const std::string &message) const {
        throw ParseError(TokenLoc(), fmt::format("{}: {}", position.Describe(), message));
    }

    BodyPosition position;

  private:
    void SkipWhitespace() {
        for (; p != end && (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n'); ++p)
            if (*p == '\n') {
                ++line;
                lineStart = p + 1;
            }
    }

    std::string_view NextToken() {
        SkipWhitespace();
        tokenStart = p;
        if (p == end)
            Fail(position.Truncated());
        while (p != end && *p != ' ' && *p != '\t' && *p != '\r' && *p != '\n') ++p;
        return std::string_view(tokenStart, p - tokenStart);
    }

    FileLoc TokenLoc() const { return FileLoc{filename, line, int(tokenStart - lineStart) + 1}; }

    const char *p, *end, *lineStart, *tokenStart = nullptr;
    int line;
    const std::string &filename;
};

// ---- Body ----------------------------------------------------------------------------------------

// Collects faces as they are read; face_indices may come before or after vertex_indices.
struct FaceBuilder {
    int vertices[4];
    int64_t nVertices = 0;
    int faceIndex = 0;
    std::vector<int> triFaceIndices, quadFaceIndices;

    void Finish(PlyMesh *mesh, bool hasFaceIndices) {
        if (nVertices == 3) {
            for (int i = 0; i < 3; ++i) mesh->triIndices.push_back(vertices[i]);
        } else {
            // pbrt-v4 stores quads as bilinear patches, whose vertices go row by row.
            for (int i : {0, 1, 3, 2}) mesh->quadIndices.push_back(vertices[i]);
        }
        if (hasFaceIndices) (nVertices == 3 ? triFaceIndices : quadFaceIndices).push_back(faceIndex);
    }
};

template <typename Cursor>
class BodyReader {
  public:
    BodyReader(Cursor &in, PlyMesh *mesh) : in(in), mesh(mesh) {}

    void Read(const PlyHeader &header) {
        // Faces may precede the vertices in the file, so indices are checked against the header.
        // CheckCountsFit has bounded the counts by the file's size, CheckMeshMemory the memory.
        for (const PlyElement &element : header.elements) {
            if (element.name == "vertex") AllocateVertices(element);
            if (element.name == "face") mesh->triIndices.reserve(3 * element.count);
        }
        for (const PlyElement &element : header.elements) {
            in.position.element = &element;
            bool isFace = element.name == "face";
            bool hasFaceIndices = isFace && HasRole(element, Role::FaceIndex);
            if (element.properties.empty()) continue;
            for (int64_t i = 0; i < element.count; ++i) {
                in.position.instance = i;
                for (const PlyProperty &property : element.properties) ReadProperty(property, i);
                if (isFace) faces.Finish(mesh, hasFaceIndices);
            }
        }
        in.ExpectEnd();
        mesh->faceIndices = std::move(faces.triFaceIndices);
        mesh->faceIndices.insert(mesh->faceIndices.end(), faces.quadFaceIndices.begin(),
                                 faces.quadFaceIndices.end());
    }

  private:
    void AllocateVertices(const PlyElement &vertex) {
        nVertices = vertex.count;
        mesh->p.resize(nVertices);
        if (HasRole(vertex, Role::Nx)) mesh->n.resize(nVertices);
        if (HasRole(vertex, Role::U)) mesh->uv.resize(nVertices);
    }

    void ReadProperty(const PlyProperty &property, int64_t i) {
        if (property.role == Role::VertexIndices) return ReadFaceVertices(property);
        if (property.countType) {
            int64_t n = ReadCount(*property.countType);
            return in.Skip(property.type, n);
        }
        if (property.role == Role::Skip) return in.Skip(property.type, 1);
        double value = in.Read(property.type);
        if (property.role == Role::FaceIndex) {
            faces.faceIndex = ToInt(value, INT_MAX, "face_indices value");
            return;
        }
        float v = float(value);
        if (!IsFinite(v))
            in.Fail(fmt::format("non-finite value in property \"{}\"; expected a finite number",
                                property.name));
        switch (property.role) {
        case Role::Px: mesh->p[i].x = v; break;
        case Role::Py: mesh->p[i].y = v; break;
        case Role::Pz: mesh->p[i].z = v; break;
        case Role::Nx: mesh->n[i].x = v; break;
        case Role::Ny: mesh->n[i].y = v; break;
        case Role::Nz: mesh->n[i].z = v; break;
        case Role::U: mesh->uv[i].x = v; break;
        case Role::V: mesh->uv[i].y = v; break;
        default: break;
        }
    }

    int64_t ReadCount(PlyType countType) {
        double n = in.Read(countType);
        if (n < 0) in.Fail(fmt::format("negative list length {}; expected 0 or more", int64_t(n)));
        return int64_t(n);
    }

    void ReadFaceVertices(const PlyProperty &property) {
        int64_t n = ReadCount(*property.countType);
        if (n != 3 && n != 4)
            in.Fail(fmt::format("{} vertices; expected 3 or 4 (only triangles and quads are "
                                "supported)", n));
        faces.nVertices = n;
        for (int64_t k = 0; k < n; ++k)
            faces.vertices[k] = ToInt(in.Read(property.type), nVertices - 1, "vertex index");
    }

    // value is an integer read from an integer-typed property; it must lie in [0, max].
    int ToInt(double value, int64_t max, const char *what) {
        if (value < 0 || value > double(max))
            in.Fail(fmt::format("{} {} is out of range; expected 0 to {}", what, int64_t(value), max));
        return int(value);
    }

    Cursor &in;
    PlyMesh *mesh;
    int64_t nVertices = 0;
    FaceBuilder faces;
};

template <typename Cursor>
void ReadBody(Cursor in, const PlyHeader &header, PlyMesh *mesh) {
    BodyReader<Cursor>(in, mesh).Read(header);
}

}  // namespace

PlyMesh ParsePly(std::string_view contents, const std::string &filename) {
    PlyHeader header = HeaderReader(contents, filename).Read();
    AssignRoles(header);
    std::string_view body = contents.substr(header.bodyOffset);
    CheckCountsFit(header, body.size());
    CheckMeshMemory(header);
    PlyMesh mesh;
    if (header.format == PlyFormat::Ascii)
        ReadBody(AsciiCursor(body, header.bodyLine, filename), header, &mesh);
    else
        ReadBody(BinaryCursor(body, header.bodyOffset,
                              (header.format == PlyFormat::BinaryBigEndian) !=
                                  (std::endian::native == std::endian::big),
                              filename),
                 header, &mesh);
    return mesh;
}

PlyMesh ReadPly(const std::string &filename) {
    // One read of the whole file: decoding then never waits on the disk.
    const FileLoc fileLoc{filename, 0, 0};
    std::string why;
    std::optional<uint64_t> size = RegularFileSize(filename, &why);
    if (!size) throw ParseError(fileLoc, "cannot open the PLY file: " + why);
    CheckMemory(fileLoc, fmt::format("reading the {}-byte PLY file", *size), *size);
    std::unique_ptr<char[]> contents(new char[*size]);  // not zero-filled: read overwrites it
    std::ifstream file(filename, std::ios::binary);
    if (!file.read(contents.get(), std::streamsize(*size)))
        throw ParseError(fileLoc, "cannot read the PLY file");
    return ParsePly(std::string_view(contents.get(), *size), filename);
}

}  // namespace pbrt
