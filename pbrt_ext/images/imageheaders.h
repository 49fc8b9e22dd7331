// A check of an image file's declared sizes before a decoder believes them, and its format by
// signature (host only).
//
// Some decoders allocate a header field at the size the file declares before reading it: a 28-byte
// OpenEXR file declaring a 2 GiB string attribute makes OpenEXR 3.1 allocate and zero 2 GiB, for
// seconds, before it finds the file too short; a 500-byte PNG declaring a 1.9 GiB text chunk makes
// libpng allocate that much (both found by the image fuzz target, docs/fuzzing.md). Walking the
// file's structure first, seeking over the values and allocating nothing, turns that into an error.
#pragma once

#include <string>

namespace pbrt {

// Throws std::runtime_error("<path>: error: ...") when the file is an OpenEXR or PNG file (by its
// signature, whatever its extension: OpenImageIO tries every reader) one of whose header
// attributes or chunks declares more bytes than the file has left. Anything else, malformed or
// not, is left to the decoders.
void CheckDeclaredSizes(const std::string &path);

// The format a file's signature names (its first 8 bytes), whatever its extension; Other for
// anything else, including an unreadable file.
enum class ImageFileFormat { PNG, EXR, Other };
ImageFileFormat ImageFileFormatOf(const std::string &path);

}  // namespace pbrt
