// Fuzz harnesses: one function per input surface of the renderer, fed arbitrary bytes.
//
// Each harness turns the bytes into one call of the code under test and accepts the outcomes that
// code promises for bad input (a ParseError or std::runtime_error with a message). Anything else is
// a finding: a crash, a sanitizer report, another exception type (it escapes and terminates), a
// hang, or a violated invariant, which a harness reports on stderr before std::abort(). The
// libFuzzer entry points (fuzzer_main.cpp, once per target) and the regression test
// (tests/fuzz_regression_test.cpp) call the same functions, so a committed input replays exactly
// what the fuzzer ran. Harnesses are deterministic and keep no state between inputs beyond their
// scratch directory (fuzz/scratch.h).
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace pbrt::fuzz {

// Scene text through the tokenizer, the parser and BasicSceneBuilder (DescribeSceneString).
void FuzzParser(std::span<const uint8_t> data);
// A PLY file in memory (ParsePly).
void FuzzPly(std::span<const uint8_t> data);
// An image file through Image::Read: the first byte picks the file extension, the rest is the file.
void FuzzImage(std::span<const uint8_t> data);
// PNG and EXR through Image::Read (first byte even: EXR, odd: PNG; the rest is the file, its
// signature restored), the formats the project decodes itself (images/pngfile.cpp,
// images/exrfile.cpp): without OpenImageIO's plugins, many times the inputs per second of the image
// target.
void FuzzPngExr(std::span<const uint8_t> data);
// The image target's inputs that stb_image decodes (images/stbfile.cpp: TGA, JPEG, BMP, PNM and
// HDR among its extensions), and only those: also without OpenImageIO's plugins.
void FuzzStb(std::span<const uint8_t> data);
// FabricBxDF built from fabric-material parameters, evaluated and sampled at one pair of
// directions, with its invariants asserted (layout in fabric_target.cpp).
void FuzzFabric(std::span<const uint8_t> data);
// A scene file through LoadScene: the parser and everything the scene loader creates.
void FuzzScene(std::span<const uint8_t> data);
// A NanoVDB file that a scene's "nanovdb" medium reads (through LoadScene).
void FuzzNanoVDB(std::span<const uint8_t> data);
// A film slice's EXR (FilmSlice::Read), merged with itself moved past its own samples.
void FuzzSlice(std::span<const uint8_t> data);
// A lens description made into a RealisticCamera, and rays through it (lens_target.cpp).
void FuzzLens(std::span<const uint8_t> data);
// An RGL .bsdf file read as a measured BRDF, evaluated and sampled (measured_target.cpp).
void FuzzMeasured(std::span<const uint8_t> data);
// A guiding tree file (--guiding-load) after its header, read, sampled and evaluated
// (guidingtree_target.cpp).
void FuzzGuidingTree(std::span<const uint8_t> data);

struct FuzzTarget {
    std::string_view name;  // as scripts/fuzz and tests/data/fuzz/<name>/ call it
    void (*run)(std::span<const uint8_t>);
};

// Every target, in the order scripts/fuzz --list prints them.
inline constexpr FuzzTarget kFuzzTargets[] = {
    {"parser", FuzzParser}, {"ply", FuzzPly},     {"image", FuzzImage}, {"pngexr", FuzzPngExr},
    {"stb", FuzzStb},       {"fabric", FuzzFabric}, {"scene", FuzzScene},
    {"nanovdb", FuzzNanoVDB}, {"slice", FuzzSlice}, {"lens", FuzzLens},
    {"measured", FuzzMeasured}, {"guidingtree", FuzzGuidingTree}};

}  // namespace pbrt::fuzz
