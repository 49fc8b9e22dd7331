// An image file being read: what its header says, then its pixels. Implemented over libpng
// (images/pngfile.h), OpenEXR (images/exrfile.h) and OpenImageIO (images/imagecodec.h); images/image.cpp
// picks by the file's signature and decides what the header allows before any pixel is decoded.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace pbrt {

struct ImageFileSpec {
    int width = 0, height = 0, depth = 1, nChannels = 0;
    bool isFloat = false;  // float, half or double samples: linear, whatever the caller's encoding
    bool is8Bit = false;   // 8-bit samples, which ReadPixels() gives as byte / 255
    std::vector<std::string> channelNames;
    // The header's string attributes (EXR only: a film slice's description, filmslice.h).
    std::map<std::string, std::string> stringAttributes;
    // The colour space's primaries and white as xy: red, green, blue, white (EXR only, from its
    // standard "chromaticities" attribute; none when the file has none).
    std::optional<std::array<float, 8>> chromaticities;
    // What the decoder allocates besides the float pixels it returns, from the header alone.
    uint64_t decodeBufferBytes = 0;
};

class ImageFileReader {
  public:
    virtual ~ImageFileReader() = default;
    virtual const ImageFileSpec &Spec() const = 0;
    // Every channel of every pixel as float, row-major (integer formats scaled to [0, 1], still
    // in the file's encoding). Throws std::runtime_error(<reason>).
    virtual void ReadPixels(float *pixels) = 0;
};

}  // namespace pbrt
