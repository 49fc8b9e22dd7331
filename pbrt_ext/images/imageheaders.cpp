#include "pbrt_ext/images/imageheaders.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <optional>
#include <stdexcept>

namespace pbrt {

namespace {

// OpenEXR (openexr.com, "OpenEXR File Layout"): magic number, version field with flags, then the
// header(s): attributes "name\0type\0" + little-endian int32 size + value, each header ending with
// an empty name; a multi-part file has several headers and ends the list with an empty one.
constexpr uint32_t kExrMagic = 20000630;
constexpr uint32_t kExrMultipartFlag = 0x1000;
constexpr size_t kExrMaxNameLength = 255;  // with the long-names flag; 31 without

// PNG (ISO/IEC 15948): the signature, then chunks: big-endian uint32 length, 4-byte type, data,
// 4-byte CRC, up to IEND.
constexpr std::array<uint8_t, 8> kPngSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

uint32_t LittleEndian(std::array<uint8_t, 4> b) {
    return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
}

class FileReader {
  public:
    explicit FileReader(const std::string &path) : in(path, std::ios::binary | std::ios::ate) {
        size = in ? uint64_t(in.tellg()) : 0;
        in.seekg(0);
    }
    bool Ok() const { return bool(in); }
    uint64_t Left() { return size - uint64_t(in.tellg()); }
    void Skip(uint64_t bytes) { in.seekg(std::streamoff(bytes), std::ios::cur); }

    template <size_t N>
    std::array<uint8_t, N> Bytes() {
        std::array<uint8_t, N> b{};
        in.read(reinterpret_cast<char *>(b.data()), N);
        return b;
    }
    uint32_t LittleEndian32() { return LittleEndian(Bytes<4>()); }
    uint32_t BigEndian32() {
        auto b = Bytes<4>();
        return uint32_t(b[3]) | uint32_t(b[2]) << 8 | uint32_t(b[1]) << 16 | uint32_t(b[0]) << 24;
    }
    // A null-terminated name: empty at the end of an OpenEXR header, nullopt when malformed.
    std::optional<std::string> Name() {
        std::string name;
        for (char c; in.get(c) && c != '\0';) {
            if (name.size() == kExrMaxNameLength)
                return {};
            name += c;
        }
        return in ? std::optional(name) : std::nullopt;
    }

  private:
    std::ifstream in;
    uint64_t size = 0;
};

[[noreturn]] void ThrowTooLarge(const std::string &path, const std::string &what, uint64_t declared,
                                uint64_t left) {
    throw std::runtime_error(fmt::format("{}: error: corrupt file: {} declares {} bytes, but the "
                                         "file has {} left",
                                         path, what, declared, left));
}

void CheckExr(FileReader &file, const std::string &path) {
    bool multipart = file.LittleEndian32() & kExrMultipartFlag;
    for (bool emptyHeader = false; !emptyHeader;) {
        emptyHeader = true;
        for (;;) {
            std::optional<std::string> name = file.Name();
            if (!name || name->empty())
                break;
            emptyHeader = false;
            std::optional<std::string> type = file.Name();
            uint32_t size = file.LittleEndian32();
            if (!type || !file.Ok())
                return;
            if (size > file.Left())  // a negative int32 size reads as huge: rejected too
                ThrowTooLarge(path, fmt::format("OpenEXR attribute \"{}\" of type \"{}\"", *name, *type),
                              size, file.Left());
            file.Skip(size);
        }
        if (!file.Ok() || !multipart)
            return;
    }
}

void CheckPng(FileReader &file, const std::string &path) {
    for (;;) {
        uint32_t length = file.BigEndian32();
        auto type = file.Bytes<4>();
        if (!file.Ok())
            return;
        std::string name(type.begin(), type.end());
        if (uint64_t(length) + 4 > file.Left())  // the data and its CRC
            ThrowTooLarge(path, fmt::format("PNG chunk \"{}\"", name), length, file.Left());
        if (name == "IEND")
            return;
        file.Skip(uint64_t(length) + 4);
    }
}

}  // namespace

ImageFileFormat ImageFileFormatOf(const std::string &path) {
    FileReader file(path);
    auto magic = file.Bytes<4>();
    if (!file.Ok())
        return ImageFileFormat::Other;
    if (LittleEndian(magic) == kExrMagic)
        return ImageFileFormat::EXR;
    auto rest = file.Bytes<4>();
    if (file.Ok() && std::equal(magic.begin(), magic.end(), kPngSignature.begin()) &&
        std::equal(rest.begin(), rest.end(), kPngSignature.begin() + 4))
        return ImageFileFormat::PNG;
    return ImageFileFormat::Other;
}

void CheckDeclaredSizes(const std::string &path) {
    ImageFileFormat format = ImageFileFormatOf(path);
    if (format == ImageFileFormat::Other)
        return;
    FileReader file(path);
    file.Skip(format == ImageFileFormat::EXR ? 4 : 8);
    if (format == ImageFileFormat::EXR)
        CheckExr(file, path);
    else
        CheckPng(file, path);
}

}  // namespace pbrt
