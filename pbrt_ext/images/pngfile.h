// PNG files through libpng: reading into an ImageFileReader, and writing 8-bit RGB (host only).
#pragma once

#include "pbrt_ext/images/imagefile.h"

#include <cstdint>
#include <memory>
#include <string>

namespace pbrt {

// Reads the header; palette, gray and low-bit-depth files are expanded to 8 or 16 bits per
// channel, with tRNS as alpha. Throws std::runtime_error(<reason>).
std::unique_ptr<ImageFileReader> OpenPNGFile(const std::string &path);

// Writes rows of 8-bit sRGB RGB pixels to path. Throws std::runtime_error(<reason>).
void WritePNG(const std::string &path, int width, int height, const uint8_t *rgb);

}  // namespace pbrt
