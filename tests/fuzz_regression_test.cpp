// Replays, through the fuzz harnesses (fuzz/fuzz_targets.h), every input that once made a fuzz
// target fail (tests/data/fuzz/<target>/, kept after the fix) and a handful of its seeds, so that
// the test exercises each harness even where nothing was ever found. A harness that meets a
// problem aborts with its finding on stderr (or lets an unexpected exception escape), which fails
// this test the way it failed the fuzzer. docs/fuzzing.md tells how inputs get here.
#include "fuzz/finding.h"
#include "fuzz/fuzz_targets.h"
#include "fuzz/scratch.h"

#include "pbrt_ext/images/image.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>
#include <vector>

using namespace pbrt::fuzz;
namespace fs = std::filesystem;

namespace pbrt::fuzz {
// GoogleTest names the parameter of a failing case with this.
void PrintTo(const FuzzTarget &target, std::ostream *os) { *os << target.name; }
}  // namespace pbrt::fuzz

namespace {

const fs::path kDataDir = PBRT_EXT_TEST_DATA_DIR;
const fs::path kSeedsDir = PBRT_EXT_FUZZ_SEEDS_DIR;

// Where each target's inputs come from besides tests/data/fuzz/<target>/: the files it was seeded
// with (scripts/fuzz), by folder and extension.
struct SeedSource {
    fs::path folder;
    std::string extension;
};

std::vector<SeedSource> Seeds(std::string_view target) {
    if (target == "parser")
        return {{kDataDir / "parser", ".pbrt"}, {kDataDir / "bad", ".pbrt"}};
    if (target == "ply")
        return {{kDataDir / "ply", ".ply"}, {kDataDir / "bad", ".ply"}};
    if (target == "scene")  // the loader's error cases; valid scenes render in other tests
        return {{kDataDir / "bad", ".pbrt"}};
    if (target == "pngexr" || target == "stb")  // the image target's seeds, read their own way
        return {{kSeedsDir / "image", ".seed"}, {kDataDir / "fuzz" / "image", ".seed"}};
    return {{kSeedsDir / target, ".seed"}};
}

// Regular files of folder (recursively) with the extension, or all when it is empty; sorted, so
// that a failure names the same file on every machine.
std::vector<fs::path> Files(const fs::path &folder, const std::string &extension) {
    std::vector<fs::path> files;
    if (!fs::is_directory(folder))
        return files;
    for (const fs::directory_entry &entry : fs::recursive_directory_iterator(folder))
        if (entry.is_regular_file() && (extension.empty() || entry.path().extension() == extension))
            files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

// The file's bytes; a file that cannot be opened fails the test (an empty one is a valid input).
std::vector<uint8_t> ReadBytes(const fs::path &path) {
    std::ifstream in(path, std::ios::binary);
    EXPECT_TRUE(in) << "cannot read " << path;
    return {std::istreambuf_iterator<char>(in), {}};
}

class FuzzRegression : public testing::TestWithParam<FuzzTarget> {};

}  // namespace

TEST_P(FuzzRegression, ReplaysFoundInputsAndSeeds) {
    const FuzzTarget &target = GetParam();
    std::vector<fs::path> inputs = Files(kDataDir / "fuzz" / target.name, "");
    size_t found = inputs.size();
    for (const SeedSource &source : Seeds(target.name)) {
        std::vector<fs::path> seeds = Files(source.folder, source.extension);
        inputs.insert(inputs.end(), seeds.begin(), seeds.end());
    }
    // Without seeds the test would pass without running the harness at all.
    ASSERT_GT(inputs.size(), found) << "no seeds found for " << target.name;
    for (const fs::path &input : inputs) {
        SCOPED_TRACE(input.string());
        target.run(ReadBytes(input));
    }
    RecordProperty("inputs", int(inputs.size()));
}

// The image target's findings: decoders allocated what a corrupt header declared before they
// failed: OpenEXR the 2 GiB of a 28-byte file's string attribute (zeroing it, for seconds), libpng
// the 1.9 GiB of a 502-byte file's text chunk, OpenImageIO 3 GiB of scanline buffer for an image
// 2097157 pixels wide and 4 high (OpenEXR, which now reads it, would take 768 MiB: two blocks of
// its compression's scanlines, whatever the image's height), and OpenEXR 1.8 GB for 7 s on a 2 KB
// multipart file whose channel "G" declares a sampling of a billion rows (now refused by OpenEXR's
// core library before its C++ reader sees the file). The replays above would pass without the
// fixes too, only slowly and with gigabytes of memory, so this checks that our checks answer first.
TEST(FuzzRegressionImage, DeclaredSizesBeyondTheFileOrTheBudgetAreRejectedBeforeDecoding) {
    struct Case {
        const char *input, *extension, *message;
    };
    const Case cases[] = {
        {"exr_string_attribute_2gib.seed", "exr",
         "error: corrupt file: OpenEXR attribute \"E|,i\" of type \"string\" declares 1979711651 "
         "bytes, but the file has 3 left"},
        {"png_text_chunk_2gib.seed", "png",
         "error: corrupt file: PNG chunk \"tEXt\" declares 1949043392 bytes, but the file has "
         "249 left"},
        {"exr_wide_four_rows.seed", "exr",
         "error: decoding the 2097157 x 4 image would take 805308288 bytes (768.0 MiB) of memory"},
        {"exr_multipart_channel_sampling.seed", "exr",
         "OpenEXR: Invalid pixel sampling (x -1375731711 y 1397975078) adding channel 'G' to list"}};
    pbrt::SetMemoryBudget(kFuzzMemoryBudget);
    for (const Case &c : cases) {
        std::vector<uint8_t> bytes = ReadBytes(kDataDir / "fuzz" / "image" / c.input);
        ASSERT_FALSE(bytes.empty());
        // The fuzz input's first byte picks the extension; the file is the rest.
        std::string path = WriteScratchFile("regression", std::string("input.") + c.extension,
                                            std::span(bytes).subspan(1));
        EXPECT_THAT([&] { pbrt::Image::Read(path); },
                    testing::ThrowsMessage<std::runtime_error>(testing::HasSubstr(c.message)))
            << c.input;
    }
    pbrt::SetMemoryBudget(0);
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzRegression, testing::ValuesIn(kFuzzTargets),
                         [](const testing::TestParamInfo<FuzzTarget> &target) {
                             return std::string(target.param.name);
                         });
