// The OpenImageIO module behind util/imagecodec.h: a thin adapter, so that what the project
// decides about a file (its channels, the memory it may take) stays in util/image.cpp.
#include "pbrt_ext/util/imagecodec.h"

#include <OpenImageIO/imageio.h>

#include <stdexcept>

namespace pbrt {
namespace {

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
        spec.channelNames = s.channelnames;
        spec.scanlineBytes = s.scanline_bytes(true);
        spec.tileWidth = s.tile_width;
        spec.tileBytes = s.tile_width > 0 ? s.tile_bytes(true) : 0;
        OIIO::getattribute("read_chunk", spec.readChunk);
        spec.rowsPerStrip = s.get_int_attribute("tiff:RowsPerStrip", 64);
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
