// The image target: Image::Read, which decodes PNG through libpng (util/pngfile.cpp), EXR through
// OpenEXR (util/exrfile.cpp) and the other formats through the OpenImageIO module
// (util/imagecodec.h). Only the project's code is instrumented for coverage; libpng, OpenEXR,
// OpenImageIO and the codec libraries are Debian's builds, so the fuzzer steers by our code alone
// and reports their crashes without guidance into them.
#include "fuzz/finding.h"
#include "fuzz/fuzz_targets.h"
#include "fuzz/scratch.h"

#include "pbrt_ext/util/image.h"
#include "pbrt_ext/util/imagecodec.h"

#include <string>

namespace pbrt::fuzz {

namespace {

// The formats a scene's textures and environment maps come in (the extension picks the reader);
// fuzz/seeds/make_seeds.py writes the seeds with the same indices.
constexpr const char *kExtensions[] = {"exr", "png", "hdr", "pfm", "tga", "jpg", "ppm", "bmp", "tif"};

}  // namespace

void FuzzImage(std::span<const uint8_t> data) {
    if (data.empty())
        return;
    // One thread in OpenImageIO and OpenEXR: a fuzzer is a single-core job, and a deterministic one.
    // Set once: setting "threads" again resizes OpenImageIO's thread pool, which costs milliseconds.
    static const bool oneThread = (GetImageCodec().SetThreads(1), true);
    (void)oneThread;
    std::string extension = kExtensions[data[0] % std::size(kExtensions)];
    std::string path = WriteScratchFile("image", "input." + extension, data.subspan(1));
    ExpectReadOrRejection("image", [&] { Image::Read(path); });
}

}  // namespace pbrt::fuzz
