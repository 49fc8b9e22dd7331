// The image formats OpenImageIO reads and writes, behind an interface whose implementation
// (util/imagecodec_oiio.cpp) is a module loaded on first use.
//
// Why a module: linking OpenImageIO brings some 260 shared libraries whose loading and static
// initializers cost every process about 0.5 s and 120 MB before main() runs, although most
// renders read no image and write EXR, which OpenEXR does directly (util/image.cpp). Loaded
// with dlopen, only a process that touches such a file pays for it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pbrt {

// What a file's header says, as OpenImageIO reports it: the pixels, and the numbers that size
// its decoder's own buffers (util/image.cpp checks them against the memory budget).
struct ImageFileSpec {
    int width = 0, height = 0, depth = 0, nChannels = 0;
    bool isFloat = false;  // float, half or double samples: linear, whatever the caller's encoding
    std::vector<std::string> channelNames;
    uint64_t scanlineBytes = 0, tileBytes = 0;
    int tileWidth = 0;     // 0 for a scanline file
    int readChunk = 256;   // OpenImageIO's "read_chunk" attribute
    int rowsPerStrip = 64; // a TIFF's, or OpenImageIO's default
};

class ImageFileReader {
  public:
    virtual ~ImageFileReader() = default;
    virtual const ImageFileSpec &Spec() const = 0;
    // Every channel of every pixel as float, row-major. Throws std::runtime_error(<reason>).
    virtual void ReadPixels(float *pixels) = 0;
};

class ImageCodec {
  public:
    virtual ~ImageCodec() = default;
    // Throws std::runtime_error(<reason>) when no reader takes the file.
    virtual std::unique_ptr<ImageFileReader> Open(const std::string &path) const = 0;
    // Writes 8-bit sRGB RGB pixels to tmpPath in the format path's extension names. Throws
    // std::runtime_error(<reason>).
    virtual void Write8Bit(const std::string &path, const std::string &tmpPath, int width, int height,
                           const uint8_t *rgb) const = 0;
    // The threads OpenImageIO (and OpenEXR through it) decode with.
    virtual void SetThreads(int n) const = 0;
};

// The codec, loaded once (thread-safely) on first call. Throws std::runtime_error naming the
// places it looked when the module cannot be loaded. Looked for, in order: $PBRT_EXT_IMAGE_CODEC;
// <executable's folder>/../<libdir>/pbrt_ext/ (an installed tree); the build tree's.
const ImageCodec &GetImageCodec();

}  // namespace pbrt

// The one symbol the module exports.
extern "C" const pbrt::ImageCodec *pbrt_ext_image_codec();
