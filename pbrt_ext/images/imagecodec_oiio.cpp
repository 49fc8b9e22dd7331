// The OpenImageIO module behind images/imagecodec.h: a thin adapter, so that what the project
// decides about a file (its channels, the memory it may take) stays in images/image.cpp.
#include "pbrt_ext/images/imagecodec.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace pbrt {
namespace {

uint64_t SaturatingMultiply(uint64_t a, uint64_t b) {
    uint64_t product;
    return __builtin_mul_overflow(a, b, &product) ? UINT64_MAX : product;
}

// What OpenImageIO 2.4's read_image allocates besides the caller's buffer when it converts to
// float (imageinput.cpp): for a scanline file, whole native scanlines, about 64 MiB of them but at
// least its "read_chunk" (256) and a multiple of the rows per strip (64 unless a TIFF says),
// however few the image has; for a tiled file, a row of native tiles. The header decides both: a
// wide image of four rows made it allocate 3 GiB (found by the image fuzz target, docs/fuzzing.md).
uint64_t DecoderBufferBytes(const OIIO::ImageSpec &spec) {
    uint64_t scanline = std::max<uint64_t>(spec.scanline_bytes(true), 1);
    if (spec.tile_width > 0) {
        uint64_t tilesAcross = (uint64_t(spec.width) + uint64_t(spec.tile_width) - 1) / uint64_t(spec.tile_width);
        return SaturatingMultiply(tilesAcross, spec.tile_bytes(true));
    }
    int readChunk = 256;
    OIIO::getattribute("read_chunk", readChunk);
    uint64_t rows = std::max<uint64_t>((uint64_t(1) << 26) / scanline, uint64_t(std::max(readChunk, 1)));
    uint64_t rowsPerStrip = uint64_t(std::max(spec.get_int_attribute("tiff:RowsPerStrip", 64), 1));
    rows = (rows + rowsPerStrip - 1) / rowsPerStrip * rowsPerStrip;
    return SaturatingMultiply(rows, scanline);
}

class OIIOReader : public ImageFileReader {
  public:
    explicit OIIOReader(std::unique_ptr<OIIO::ImageInput> in) : in(std::move(in)) {
        const OIIO::ImageSpec &s = this->in->spec();
        spec.width = s.width;
        spec.height = s.height;
        spec.depth = s.depth;
        spec.nChannels = s.nchannels;
        spec.isFloat = s.format.basetype == OIIO::TypeDesc::FLOAT ||
                       s.format.basetype == OIIO::TypeDesc::HALF ||
                       s.format.basetype == OIIO::TypeDesc::DOUBLE;
        spec.is8Bit = s.format.basetype == OIIO::TypeDesc::UINT8;
        spec.channelNames = s.channelnames;
        spec.decodeBufferBytes = DecoderBufferBytes(s);
    }
    const ImageFileSpec &Spec() const override { return spec; }
    void ReadPixels(float *pixels) override {
        if (!in->read_image(0, 0, 0, spec.nChannels, OIIO::TypeDesc::FLOAT, pixels))
            throw std::runtime_error("cannot decode the pixels: " + in->geterror());
        in->close();
    }

  private:
    std::unique_ptr<OIIO::ImageInput> in;
    ImageFileSpec spec;
};

class OIIOCodec : public ImageCodec {
  public:
    std::unique_ptr<ImageFileReader> Open(const std::string &path) const override {
        std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
        if (!in) throw std::runtime_error("cannot read the image: " + OIIO::geterror());
        return std::make_unique<OIIOReader>(std::move(in));
    }
    void Write8Bit(const std::string &path, const std::string &tmpPath, int width, int height,
                   const uint8_t *rgb) const override {
        // The format follows the target's extension, not the temporary name's.
        std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
        if (!out) throw std::runtime_error("no image writer for this extension: " + OIIO::geterror());
        OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("oiio:ColorSpace", "sRGB");
        if (!out->open(tmpPath, spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgb) || !out->close())
            throw std::runtime_error("cannot write the image: " + out->geterror());
    }
    bool HasWriter(const std::string &path) const override {
        return OIIO::ImageOutput::create(path) != nullptr;
    }
    void SetThreads(int n) const override {
        OIIO::attribute("threads", n);
        OIIO::attribute("exr_threads", n);
    }
};

}  // namespace
}  // namespace pbrt

extern "C" const pbrt::ImageCodec *pbrt_ext_image_codec() {
    static const pbrt::OIIOCodec codec;
    return &codec;
}
