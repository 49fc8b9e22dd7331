#include "pbrt_ext/util/tensorfile.h"

#include "pbrt_ext/util/atomicfile.h"
#include "pbrt_ext/util/error.h"
#include "pbrt_ext/util/resourcelimits.h"

#include <fmt/format.h>

#include <bit>
#include <cstring>
#include <fstream>

namespace pbrt {

// The format is little-endian and fields are read by copying their bytes.
static_assert(std::endian::native == std::endian::little, "tensor files need a little-endian host");

namespace {

constexpr char kMagic[12] = {'t', 'e', 'n', 's', 'o', 'r', '_', 'f', 'i', 'l', 'e', '\0'};
// Bounds no real file comes near (RGL's files have about 10 fields of rank 5 at most).
constexpr uint32_t kMaxFields = 1024;
constexpr uint16_t kMaxRank = 16;

// Reads the file's header fields in order, each checked to lie inside the file.
class Cursor {
  public:
    Cursor(const std::string &path, const std::vector<uint8_t> &file) : path(path), file(file) {}

    template <typename T>
    T Read(const char *what) {
        T v;
        Bytes(&v, sizeof(T), what);
        return v;
    }
    std::string ReadString(size_t n, const char *what) {
        std::string s(n, '\0');
        Bytes(s.data(), n, what);
        return s;
    }

  private:
    void Bytes(void *out, size_t n, const char *what) {
        if (n > file.size() - pos)
            ThrowFileError(path, fmt::format("the file ends inside the header, in {} (at byte {} "
                                             "of {}); truncated?",
                                             what, pos, file.size()));
        std::memcpy(out, file.data() + pos, n);
        pos += n;
    }

    const std::string &path;
    const std::vector<uint8_t> &file;
    size_t pos = 0;
};

std::vector<uint8_t> ReadWholeFile(const std::string &path) {
    std::string why;
    std::optional<uint64_t> size = RegularFileSize(path, &why);
    if (!size) ThrowFileError(path, "cannot be read: " + why);
    // The file, and then its fields copied out of it.
    CheckMemory(FileLoc{path, 0, 0}, "reading the tensor file", SaturatingProduct({*size, 2}));
    std::vector<uint8_t> bytes(*size);
    std::ifstream in(path, std::ios::binary);
    if (!in.read(reinterpret_cast<char *>(bytes.data()), std::streamsize(bytes.size())))
        ThrowFileError(path, "cannot be read");
    return bytes;
}

std::string ShapeString(const std::vector<uint64_t> &shape) {
    std::string s;
    for (uint64_t n : shape) s += (s.empty() ? "" : " x ") + std::to_string(n);
    return s.empty() ? "a scalar" : s;
}

}  // namespace

size_t TensorElementSize(uint8_t type) {
    static constexpr size_t kSizes[] = {0, 1, 1, 2, 2, 4, 4, 8, 8, 2, 4, 8};
    return type < std::size(kSizes) ? kSizes[type] : 0;
}

uint64_t TensorField::Count() const {
    uint64_t n = 1;
    for (uint64_t s : shape) n *= s;
    return n;
}

std::span<const float> TensorField::Floats() const {
    if (type != Type::Float32) throw std::logic_error("TensorField::Floats of a non-float32 field");
    return {reinterpret_cast<const float *>(bytes.data()), bytes.size() / sizeof(float)};
}

std::span<const uint8_t> TensorField::UInt8s() const {
    if (type != Type::UInt8) throw std::logic_error("TensorField::UInt8s of a non-uint8 field");
    return bytes;
}

TensorField TensorField::FromFloats(std::vector<uint64_t> shape, const std::vector<float> &values) {
    TensorField f{Type::Float32, std::move(shape),
                  std::vector<uint8_t>(values.size() * sizeof(float))};
    std::memcpy(f.bytes.data(), values.data(), f.bytes.size());
    return f;
}

TensorField TensorField::FromBytes(std::vector<uint64_t> shape,
                                   const std::vector<uint8_t> &values) {
    return TensorField{Type::UInt8, std::move(shape), values};
}

TensorFields ReadTensorFile(const std::string &path) {
    const std::vector<uint8_t> file = ReadWholeFile(path);
    Cursor in(path, file);
    if (in.ReadString(sizeof(kMagic), "the magic") != std::string(kMagic, sizeof(kMagic)))
        ThrowFileError(path, "not a tensor file (it does not start with \"tensor_file\")");
    uint8_t major = in.Read<uint8_t>("the version"), minor = in.Read<uint8_t>("the version");
    if (major != 1 || minor != 0)
        ThrowFileError(path, fmt::format("tensor file version {}.{}; expected 1.0", major, minor));
    uint32_t nFields = in.Read<uint32_t>("the field count");
    if (nFields > kMaxFields)
        ThrowFileError(path, fmt::format("{} fields; expected at most {}", nFields, kMaxFields));

    TensorFields fields;
    for (uint32_t i = 0; i < nFields; ++i) {
        std::string name =
            in.ReadString(in.Read<uint16_t>("a field's name length"), "a field's name");
        uint16_t rank = in.Read<uint16_t>("a field's rank");
        uint8_t type = in.Read<uint8_t>("a field's type");
        uint64_t offset = in.Read<uint64_t>("a field's offset");
        if (rank > kMaxRank)
            ThrowFileError(path, fmt::format("field \"{}\" has rank {}; expected at most {}", name,
                                             rank, kMaxRank));
        if (TensorElementSize(type) == 0)
            ThrowFileError(path, fmt::format("field \"{}\" has the unknown type {}", name, type));
        TensorField field;
        field.type = TensorField::Type(type);
        uint64_t bytes = TensorElementSize(type);
        for (uint16_t d = 0; d < rank; ++d) {
            field.shape.push_back(in.Read<uint64_t>("a field's shape"));
            bytes = SaturatingProduct({bytes, field.shape.back()});
        }
        if (offset > file.size() || bytes > file.size() - offset)
            ThrowFileError(path, fmt::format("field \"{}\" ({}) lies outside the file of {} bytes; "
                                             "truncated?",
                                             name, ShapeString(field.shape), file.size()));
        field.bytes.assign(file.begin() + std::ptrdiff_t(offset),
                           file.begin() + std::ptrdiff_t(offset + bytes));
        if (!fields.emplace(name, std::move(field)).second)
            ThrowFileError(path, fmt::format("field \"{}\" appears twice", name));
    }
    return fields;
}

void WriteTensorFile(const std::string &path, const TensorFields &fields) {
    // The header first, then each field's data in the same order.
    std::vector<uint8_t> header(std::begin(kMagic), std::end(kMagic));
    auto put = [&header](const auto &v) {
        const auto *p = reinterpret_cast<const uint8_t *>(&v);
        header.insert(header.end(), p, p + sizeof(v));
    };
    header.push_back(1);
    header.push_back(0);
    put(uint32_t(fields.size()));
    size_t headerSize = header.size();
    for (const auto &[name, field] : fields)
        headerSize += 2 + name.size() + 2 + 1 + 8 + 8 * field.shape.size();
    uint64_t offset = headerSize;
    for (const auto &[name, field] : fields) {
        put(uint16_t(name.size()));
        header.insert(header.end(), name.begin(), name.end());
        put(uint16_t(field.shape.size()));
        put(uint8_t(field.type));
        put(offset);
        for (uint64_t n : field.shape) put(n);
        offset += field.bytes.size();
    }
    WriteFileAtomically(path, [&](const std::string &tmp) {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char *>(header.data()), std::streamsize(header.size()));
        for (const auto &entry : fields)
            out.write(reinterpret_cast<const char *>(entry.second.bytes.data()),
                      std::streamsize(entry.second.bytes.size()));
        if (!out) ThrowFileError(path, "cannot be written");
    });
}

}  // namespace pbrt
