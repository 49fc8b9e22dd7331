#include "pbrt_ext/images/pngfile.h"

#include "pbrt_ext/util/resourcelimits.h"

#include <png.h>

#include <algorithm>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace pbrt {

namespace {

// libpng reports an error by calling its error function, which must not return: it longjmps
// back to the setjmp of the libpng call in progress. Each function below that calls libpng
// holds nothing with a destructor between its setjmp and its return, so the jump skips no
// cleanup; the message waits in Errors until a C++ exception can carry it.
struct Errors {
    std::string message;
};

void OnError(png_structp png, png_const_charp message) {
    static_cast<Errors *>(png_get_error_ptr(png))->message = message;
    png_longjmp(png, 1);
}
void OnWarning(png_structp, png_const_charp) {}

struct PNGHeader {
    png_uint_32 width = 0, height = 0;
    int channels = 0, bitDepth = 0;
    size_t rowBytes = 0;
};

// png_read_info and the transforms to 8 or 16 bits per channel, then the header as transformed.
bool ReadHeader(png_structp png, png_infop info, FILE *file, PNGHeader *header) {
    if (setjmp(png_jmpbuf(png)))
        return false;
    png_init_io(png, file);
    png_read_info(png, info);
    png_set_expand(png);  // palette to RGB, gray below 8 bits to 8, tRNS to alpha
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    header->width = png_get_image_width(png, info);
    header->height = png_get_image_height(png, info);
    header->channels = png_get_channels(png, info);
    header->bitDepth = png_get_bit_depth(png, info);
    header->rowBytes = png_get_rowbytes(png, info);
    return true;
}

bool ReadRows(png_structp png, png_bytepp rows) {
    if (setjmp(png_jmpbuf(png)))
        return false;
    png_read_image(png, rows);
    return true;
}

class PNGReader : public ImageFileReader {
  public:
    PNGReader() = default;
    // Separate from the constructor, so that the destructor releases what a failure leaves.
    void Open(const std::string &path) {
        file = std::fopen(path.c_str(), "rb");
        if (!file) throw std::runtime_error("cannot open the image");
        png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &errors, OnError, OnWarning);
        info = png ? png_create_info_struct(png) : nullptr;
        if (!info) throw std::runtime_error("libpng: out of memory");
        if (!ReadHeader(png, info, file, &header))
            throw std::runtime_error("cannot read the PNG header: " + errors.message);
        spec.width = int(std::min<png_uint_32>(header.width, INT32_MAX));
        spec.height = int(std::min<png_uint_32>(header.height, INT32_MAX));
        spec.nChannels = header.channels;
        spec.is8Bit = header.bitDepth == 8;
        spec.channelNames = header.channels >= 3 ? std::vector<std::string>{"R", "G", "B", "A"}
                                                 : std::vector<std::string>{"Y", "A"};
        spec.channelNames.resize(size_t(header.channels));
        spec.decodeBufferBytes = SaturatingProduct({header.rowBytes, header.height});  // the rows, below
    }
    ~PNGReader() override {
        png_destroy_read_struct(png ? &png : nullptr, info ? &info : nullptr, nullptr);
        if (file) std::fclose(file);
    }
    PNGReader(const PNGReader &) = delete;
    PNGReader &operator=(const PNGReader &) = delete;

    const ImageFileSpec &Spec() const override { return spec; }

    void ReadPixels(float *pixels) override {
        std::vector<png_byte> bytes(header.rowBytes * header.height);
        std::vector<png_bytep> rows(header.height);
        for (png_uint_32 y = 0; y < header.height; ++y) rows[y] = bytes.data() + y * header.rowBytes;
        if (!ReadRows(png, rows.data()))
            throw std::runtime_error("cannot decode the pixels: " + errors.message);
        size_t n = size_t(header.width) * header.height * size_t(header.channels);
        if (header.bitDepth == 16)
            for (size_t i = 0; i < n; ++i) pixels[i] = float(bytes[2 * i] << 8 | bytes[2 * i + 1]) / 65535;
        else
            for (size_t i = 0; i < n; ++i) pixels[i] = float(bytes[i]) / 255;
    }

  private:
    FILE *file = nullptr;
    png_structp png = nullptr;
    png_infop info = nullptr;
    Errors errors;
    PNGHeader header;
    ImageFileSpec spec;
};

bool WriteRows(png_structp png, png_infop info, FILE *file, int width, int height, png_bytepp rows) {
    if (setjmp(png_jmpbuf(png)))
        return false;
    png_init_io(png, file);
    png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, info);
    return true;
}

}  // namespace

std::unique_ptr<ImageFileReader> OpenPNGFile(const std::string &path) {
    auto reader = std::make_unique<PNGReader>();
    reader->Open(path);
    return reader;
}

void WritePNG(const std::string &path, int width, int height, const uint8_t *rgb) {
    Errors errors;
    FILE *file = std::fopen(path.c_str(), "wb");
    if (!file) throw std::runtime_error("cannot write the image: cannot open the file");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &errors, OnError, OnWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    std::vector<png_bytep> rows(static_cast<size_t>(height));
    for (int y = 0; y < height; ++y) rows[size_t(y)] = const_cast<png_bytep>(rgb) + size_t(y) * 3 * size_t(width);
    bool written = info && WriteRows(png, info, file, width, height, rows.data());
    png_destroy_write_struct(png ? &png : nullptr, info ? &info : nullptr);
    bool closed = std::fclose(file) == 0;
    if (!written || !closed)
        throw std::runtime_error("cannot write the image: " + (info ? errors.message : "libpng: out of memory"));
}

}  // namespace pbrt
