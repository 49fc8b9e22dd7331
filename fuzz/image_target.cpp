// The image target: Image::Read, which decodes PNG through libpng (images/pngfile.cpp), EXR through
// OpenEXR (images/exrfile.cpp), TGA, JPEG, BMP, PNM and HDR through stb_image (images/stbfile.cpp)
// and the other formats through the OpenImageIO module (images/imagecodec.h). Only the project's code is instrumented for coverage; libpng, OpenEXR,
// OpenImageIO and the codec libraries are Debian's builds, so the fuzzer steers by our code alone
// and reports their crashes without guidance into them.
#include "fuzz/finding.h"
#include "fuzz/fuzz_targets.h"
#include "fuzz/scratch.h"

#include "pbrt_ext/images/image.h"
#include "pbrt_ext/images/imagecodec.h"
#include "pbrt_ext/images/stbfile.h"

#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

namespace pbrt::fuzz {

namespace {

// The formats a scene's textures and environment maps come in (the extension picks the reader);
// fuzz/seeds/make_seeds.py writes the seeds with the same indices, which the pngexr target reads
// too: an even first byte is EXR there, an odd one PNG.
constexpr const char *kExtensions[] = {"exr", "png", "hdr", "pfm", "tga", "jpg", "ppm", "bmp", "tif"};

}  // namespace

void FuzzImage(std::span<const uint8_t> data) {
    // One thread in OpenImageIO and OpenEXR: a fuzzer is a single-core job, and a deterministic one.
    // Set once: setting "threads" again resizes OpenImageIO's thread pool, which costs milliseconds.
    static const bool oneThread = (GetImageCodec().SetThreads(1), true);
    (void)oneThread;
    if (data.empty())
        return;
    std::string extension = kExtensions[data[0] % std::size(kExtensions)];
    std::string path = WriteScratchFile("image", "input." + extension, data.subspan(1));
    ExpectReadOrRejection("image", [&] { Image::Read(path); });
}

void FuzzStb(std::span<const uint8_t> data) {
    if (data.empty())
        return;
    std::string extension = kExtensions[data[0] % std::size(kExtensions)];
    if (!IsSTBImageExtension("." + extension))
        return;
    std::string path = WriteScratchFile("stb", "input." + extension, data.subspan(1));
    ExpectReadOrRejection("stb", [&] { Image::Read(path); });
}

void FuzzPngExr(std::span<const uint8_t> data) {
    // Image::Read picks the decoder by signature: a mutated one would send the file to
    // OpenImageIO, so it is restored (the seeds carry it already).
    constexpr uint8_t kExrSignature[] = {0x76, 0x2f, 0x31, 0x01};
    constexpr uint8_t kPngSignature[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (data.size() < 1 + std::size(kPngSignature))
        return;
    bool exr = data[0] % 2 == 0;
    std::vector<uint8_t> file(data.begin() + 1, data.end());
    if (exr)
        std::copy(std::begin(kExrSignature), std::end(kExrSignature), file.begin());
    else
        std::copy(std::begin(kPngSignature), std::end(kPngSignature), file.begin());
    std::string path = WriteScratchFile("pngexr", exr ? "input.exr" : "input.png", file);
    ExpectReadOrRejection("pngexr", [&] { Image::Read(path); });
}

}  // namespace pbrt::fuzz
