#include "pbrt_ext/images/exrfile.h"

#include "pbrt_ext/util/resourcelimits.h"

#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <ImfTileDescription.h>
#include <openexr.h>

#include <cstdint>
#include <stdexcept>

namespace pbrt {

namespace {

// The scanlines a chunk holds, per compression (the OpenEXR file layout's table).
int ScanlinesPerBlock(Imf::Compression compression) {
    switch (compression) {
    case Imf::NO_COMPRESSION:
    case Imf::RLE_COMPRESSION:
    case Imf::ZIPS_COMPRESSION: return 1;
    case Imf::ZIP_COMPRESSION:
    case Imf::PXR24_COMPRESSION: return 16;
    case Imf::PIZ_COMPRESSION:
    case Imf::B44_COMPRESSION:
    case Imf::B44A_COMPRESSION:
    case Imf::DWAA_COMPRESSION: return 32;
    default: return 256;  // DWAB, and any later one
    }
}

class EXRReader : public ImageFileReader {
  public:
    explicit EXRReader(const std::string &path) try : file(path.c_str()) {
        const Imf::Header &header = file.header();
        dataWindow = header.dataWindow();
        int64_t width = int64_t(dataWindow.max.x) - dataWindow.min.x + 1;
        int64_t height = int64_t(dataWindow.max.y) - dataWindow.min.y + 1;
        if (width <= 0 || height <= 0 || width > INT32_MAX || height > INT32_MAX)
            throw std::runtime_error("the data window is empty or too large");
        spec.width = int(width);
        spec.height = int(height);
        spec.isFloat = true;
        for (Imf::ChannelList::ConstIterator c = header.channels().begin(); c != header.channels().end(); ++c) {
            spec.channelNames.push_back(c.name());
            spec.isFloat = spec.isFloat && c.channel().type != Imf::UINT;
        }
        spec.nChannels = int(spec.channelNames.size());
        for (Imf::Header::ConstIterator a = header.begin(); a != header.end(); ++a)
            if (const auto *text = dynamic_cast<const Imf::StringAttribute *>(&a.attribute()))
                spec.stringAttributes[a.name()] = text->value();
        if (Imf::hasChromaticities(header)) {
            const Imf::Chromaticities &c = Imf::chromaticities(header);
            spec.chromaticities = {c.red.x,  c.red.y,  c.green.x, c.green.y,
                                   c.blue.x, c.blue.y, c.white.x, c.white.y};
        }
        // OpenEXR decodes a block of scanlines at a time, compressed and uncompressed (a row of
        // tiles for a tiled file), however few rows the image has: a header 2 million pixels
        // wide declares gigabytes of it (found by the image fuzz target, docs/fuzzing.md).
        uint64_t rowsAtOnce = header.hasTileDescription() ? uint64_t(header.tileDescription().ySize)
                                                          : uint64_t(ScanlinesPerBlock(header.compression()));
        spec.decodeBufferBytes =
            SaturatingProduct({2 * rowsAtOnce, uint64_t(width), uint64_t(spec.nChannels), sizeof(float)});
    } catch (const std::exception &e) {
        throw std::runtime_error(std::string("cannot read the image: OpenEXR: ") + e.what());
    }

    const ImageFileSpec &Spec() const override { return spec; }

    void ReadPixels(float *pixels) override {
        // OpenEXR addresses the buffer by absolute data-window coordinates.
        size_t xStride = size_t(spec.nChannels) * sizeof(float), yStride = xStride * size_t(spec.width);
        char *base = reinterpret_cast<char *>(pixels) - ptrdiff_t(dataWindow.min.x) * ptrdiff_t(xStride) -
                     ptrdiff_t(dataWindow.min.y) * ptrdiff_t(yStride);
        Imf::FrameBuffer frameBuffer;
        for (int c = 0; c < spec.nChannels; ++c)
            frameBuffer.insert(spec.channelNames[size_t(c)],
                               Imf::Slice(Imf::FLOAT, base + size_t(c) * sizeof(float), xStride, yStride));
        try {
            file.setFrameBuffer(frameBuffer);
            file.readPixels(dataWindow.min.y, dataWindow.max.y);
        } catch (const std::exception &e) {
            throw std::runtime_error(std::string("cannot decode the pixels: OpenEXR: ") + e.what());
        }
    }

  private:
    Imf::InputFile file;
    Imath::Box2i dataWindow;
    ImageFileSpec spec;
};

// OpenEXR 3.1's C++ reader trusts a header's channel list: a fuzzed 2 KB multipart file whose
// channel declares a sampling of a billion rows made Imf::InputFile allocate 1.8 GB for 7 s
// before failing (found by the image fuzz target, docs/fuzzing.md). OpenEXR's core library
// validates the headers (sampling, attribute sizes, required attributes) at once and says what
// is wrong; the C++ reader only gets the files it accepts. Throws std::runtime_error(<reason>).
void ValidateHeaders(const std::string &path) {
    std::string firstError;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.user_data = &firstError;
    init.error_handler_fn = [](exr_const_context_t context, exr_result_t, const char *message) {
        void *data = nullptr;
        if (exr_get_user_data(context, &data) == EXR_ERR_SUCCESS && data)
            if (auto *error = static_cast<std::string *>(data); error->empty()) *error = message;
    };
    exr_context_t context = nullptr;
    exr_result_t result = exr_start_read(&context, path.c_str(), &init);
    if (context) exr_finish(&context);
    if (result != EXR_ERR_SUCCESS)
        throw std::runtime_error(std::string("cannot read the image: OpenEXR: ") +
                                 (firstError.empty() ? exr_get_default_error_message(result) : firstError));
}

}  // namespace

std::unique_ptr<ImageFileReader> OpenEXRFile(const std::string &path) {
    ValidateHeaders(path);
    return std::make_unique<EXRReader>(path);
}

}  // namespace pbrt
