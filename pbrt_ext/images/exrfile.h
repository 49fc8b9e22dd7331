// Reading OpenEXR files through OpenEXR itself into an ImageFileReader (host only). Writing is
// Image::Write's, which adds the render's metadata.
#pragma once

#include "pbrt_ext/images/imagefile.h"

#include <memory>
#include <string>

namespace pbrt {

// Reads the header of the file's first part. Throws std::runtime_error(<reason>).
std::unique_ptr<ImageFileReader> OpenEXRFile(const std::string &path);

}  // namespace pbrt
