#include "pbrt_ext/images/stbfile.h"

#include "pbrt_ext/util/resourcelimits.h"

#include <stb_image.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace pbrt {

namespace {

// No format read here encodes more pixels per byte than this: GIF's 12-bit LZW codes reach
// about 2,700, the run lengths of TGA, BMP, PSD, PIC and HDR 64 to 128, progressive JPEG's
// one-bit DC codes about 340. A header that declares more is lying about a file too short
// to hold its pixels, and stb_image would allocate and fill them all before it found out.
constexpr uint64_t kMaxPixelsPerByte = 4096;

std::string FailureReason() {
    const char *reason = stbi_failure_reason();
    return reason ? reason : "unknown error";
}

class STBReader : public ImageFileReader {
  public:
    STBReader() = default;
    // Separate from the constructor, so that the destructor closes what a failure leaves.
    void Open(const std::string &path) {
        file = std::fopen(path.c_str(), "rb");
        if (!file) throw std::runtime_error("cannot open the image");
        int width = 0, height = 0, channels = 0;
        if (!stbi_info_from_file(file, &width, &height, &channels))
            throw std::runtime_error("cannot read the image header: " + FailureReason());
        std::error_code ec;
        uint64_t fileBytes = std::filesystem::file_size(path, ec);
        if (ec || uint64_t(width) * uint64_t(height) > kMaxPixelsPerByte * fileBytes)
            throw std::runtime_error("the header declares " + std::to_string(width) + " x " +
                                     std::to_string(height) + " pixels, more than a file of " +
                                     std::to_string(fileBytes) + " bytes can hold");
        hdr = stbi_is_hdr_from_file(file);
        spec.width = width;
        spec.height = height;
        spec.nChannels = channels;
        spec.isFloat = hdr;
        spec.is8Bit = !hdr;
        spec.channelNames = channels >= 3 ? std::vector<std::string>{"R", "G", "B", "A"}
                                          : std::vector<std::string>{"Y", "A"};
        spec.channelNames.resize(size_t(channels));
        spec.decodeBufferBytes =
            SaturatingProduct({uint64_t(width), uint64_t(height), uint64_t(channels), hdr ? 4u : 1u});
    }
    ~STBReader() override {
        if (file) std::fclose(file);
    }
    STBReader(const STBReader &) = delete;
    STBReader &operator=(const STBReader &) = delete;

    const ImageFileSpec &Spec() const override { return spec; }

    void ReadPixels(float *pixels) override {
        int width = 0, height = 0, channels = 0;
        size_t n = size_t(spec.width) * size_t(spec.height) * size_t(spec.nChannels);
        if (hdr) {
            float *data = stbi_loadf_from_file(file, &width, &height, &channels, 0);
            Check(data, width, height, channels);
            std::copy(data, data + n, pixels);
            stbi_image_free(data);
        } else {
            stbi_uc *data = stbi_load_from_file(file, &width, &height, &channels, 0);
            Check(data, width, height, channels);
            std::transform(data, data + n, pixels, [](stbi_uc v) { return float(v) / 255; });
            stbi_image_free(data);
        }
    }

  private:
    // The decoded image must be the one the header described.
    void Check(void *data, int width, int height, int channels) const {
        if (!data) throw std::runtime_error("cannot decode the pixels: " + FailureReason());
        if (width != spec.width || height != spec.height || channels != spec.nChannels) {
            stbi_image_free(data);
            throw std::runtime_error("the decoded image differs from its header");
        }
    }

    FILE *file = nullptr;
    bool hdr = false;
    ImageFileSpec spec;
};

}  // namespace

bool IsSTBImageExtension(const std::string &extension) {
    // Not PNM: Debian's stb_image (2.27) reads 16-bit PNM samples in the wrong byte order, and
    // OpenImageIO reads PNM files right.
    static constexpr std::array<const char *, 8> kExtensions = {".tga", ".jpg", ".jpeg", ".bmp",
                                                                ".gif", ".psd", ".pic", ".hdr"};
    return std::find(kExtensions.begin(), kExtensions.end(), extension) != kExtensions.end();
}

std::unique_ptr<ImageFileReader> OpenSTBFile(const std::string &path) {
    auto reader = std::make_unique<STBReader>();
    reader->Open(path);
    return reader;
}

}  // namespace pbrt
