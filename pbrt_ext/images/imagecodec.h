// The image formats other than PNG and EXR, which OpenImageIO reads and writes, behind an
// interface whose implementation (images/imagecodec_oiio.cpp) is a module loaded on first use.
//
// Why a module: linking OpenImageIO brings some 260 shared libraries whose loading and static
// initializers cost every process about 0.5 s and 120 MB before main() runs, although most
// renders read and write only PNG and EXR files, which libpng and OpenEXR handle directly
// (images/pngfile.h, images/exrfile.h). Loaded with dlopen, only a process that touches another
// format pays for it.
#pragma once

#include "pbrt_ext/images/imagefile.h"

#include <cstdint>
#include <memory>
#include <string>

namespace pbrt {

class ImageCodec {
  public:
    virtual ~ImageCodec() = default;
    // Throws std::runtime_error(<reason>) when no reader takes the file.
    virtual std::unique_ptr<ImageFileReader> Open(const std::string &path) const = 0;
    // Writes 8-bit sRGB RGB pixels to tmpPath in the format path's extension names. Throws
    // std::runtime_error(<reason>).
    virtual void Write8Bit(const std::string &path, const std::string &tmpPath, int width, int height,
                           const uint8_t *rgb) const = 0;
    // Whether a writer takes the format path's extension names.
    virtual bool HasWriter(const std::string &path) const = 0;
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
