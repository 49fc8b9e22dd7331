// Images in the formats pbrt-v4 reads through stb_image (Debian's libstb): TGA, JPEG, BMP,
// GIF (its first frame), PSD (its composite), PIC and Radiance HDR, read into an
// ImageFileReader (host only). OpenImageIO could read them too, but loading it costs a
// render about a second and 100 MB (a scene with TGA textures, such as Bitterli's living
// room, paid that where pbrt-v4 does not).
#pragma once

#include "pbrt_ext/images/imagefile.h"

#include <memory>
#include <string>

namespace pbrt {

// Whether a file extension (lowercase, with its dot: ".tga") names a format read here.
bool IsSTBImageExtension(const std::string &extension);

// Reads the header. Radiance HDR files are linear floats, everything else 8 bits per channel,
// as pbrt-v4 reads them (a 16-bit PSD file keeps its high 8 bits). Throws std::runtime_error(<reason>), also
// when the header declares more pixels than a file of its size can encode.
std::unique_ptr<ImageFileReader> OpenSTBFile(const std::string &path);

}  // namespace pbrt
