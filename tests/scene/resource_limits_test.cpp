// Resource guards: a scene that asks for an absurd film, sample count, mesh, image or file gets a
// located error that names the numbers, before anything is allocated for it. The requests here
// are terabytes where that is cheap to ask (sparse files, a 65-byte PNG): were a check to come
// after the allocation, the release build would throw std::bad_alloc (not ParseError) and an
// AddressSanitizer build would abort, so these tests also prove that each check comes first.
//
// Every test runs with a memory budget of 1 GiB (or less), so that messages do not depend on the
// machine. Include depth is covered by parser_test (RecursiveIncludeStopsAtTheDepthLimit).
#include "pbrt_ext/images/image.h"
#include "pbrt_ext/samplers/samplers.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/util/error.h"
#include "pbrt_ext/util/ply.h"
#include "pbrt_ext/util/resourcelimits.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <string>

using namespace pbrt;

namespace {

namespace fs = std::filesystem;

constexpr uint64_t kGiB = uint64_t(1) << 30, kTiB = uint64_t(1) << 40;
const std::string kBad = std::string(PBRT_EXT_TEST_DATA_DIR) + "/bad/";
const std::string kOverBudget =
    "expected at most the memory budget of 1073741824 bytes (1.0 GiB, set by the application)";

class ResourceLimits : public testing::Test {
  protected:
    void SetUp() override {
        SetMemoryBudget(kGiB);
        Log().quiet = true;
    }
    void TearDown() override {
        SetMemoryBudget(0);
        if (!scratch.empty()) fs::remove_all(scratch);
    }

    // A fresh folder for this test's files, removed after it.
    fs::path Scratch() {
        if (scratch.empty()) {
            const testing::TestInfo *test = testing::UnitTest::GetInstance()->current_test_info();
            scratch = fs::temp_directory_path() /
                      ("pbrt_ext_resource_limits_" + std::to_string(::getpid()) + "_" + test->name());
            fs::remove_all(scratch);
            fs::create_directories(scratch);
        }
        return scratch;
    }
    std::string WriteFile(const std::string &name, const std::string &text) {
        fs::path path = Scratch() / name;
        std::ofstream(path, std::ios::binary) << text;
        return path.string();
    }
    // size bytes of zeros that take no disk space; reading the file whole would need all of them.
    std::string SparseFile(const std::string &name, uint64_t size) {
        std::string path = WriteFile(name, "");
        fs::resize_file(path, size);
        return path;
    }

  private:
    fs::path scratch;
};

std::string LoadError(const std::string &file, const RenderOverrides &overrides = {}) {
    try {
        LoadScene(file, overrides);
    } catch (const ParseError &e) {
        return e.what();
    }
    return "no error";
}

template <typename F>
std::string ErrorOf(F f) {
    try {
        f();
    } catch (const ParseError &e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

// ---- The budget ---------------------------------------------------------------------------------

// The physical memory, or the cgroup's limit where a container sets a lower one.
TEST_F(ResourceLimits, DefaultBudgetIsThePhysicalMemoryOrTheCgroupLimit) {
    SetMemoryBudget(0);
    uint64_t physical = uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
    std::optional<uint64_t> cgroup = CgroupMemoryLimit();
    bool limited = cgroup && *cgroup < physical;
    uint64_t expected = limited ? *cgroup : physical;
    EXPECT_EQ(MemoryBudget(), expected);
    EXPECT_NO_THROW(CheckMemory(FileLoc{"f", 1, 2}, "a request", expected));
    std::string error = ErrorOf([&] { CheckMemory(FileLoc{"f", 1, 2}, "a request", expected + 1); });
    EXPECT_TRUE(error.starts_with(fmt::format("f:1:2: error: a request would take {} bytes (",
                                              expected + 1))) << error;
    EXPECT_NE(error.find(fmt::format("; expected at most the memory budget of {} bytes (", expected)),
              std::string::npos) << error;
    EXPECT_TRUE(error.ends_with(limited ? ", the memory limit of this process's cgroup)"
                                        : ", the physical memory)")) << error;
}

// cgroup v2 writes "max" for no limit; v1 writes a byte count (a huge one for no limit).
TEST_F(ResourceLimits, CgroupMemoryLimitFilesParse) {
    EXPECT_EQ(ParseCgroupMemoryLimit("1073741824\n"), std::optional<uint64_t>(1073741824));
    EXPECT_EQ(ParseCgroupMemoryLimit("9223372036854771712"),
              std::optional<uint64_t>(9223372036854771712ull));
    EXPECT_EQ(ParseCgroupMemoryLimit("max\n"), std::nullopt);
    EXPECT_EQ(ParseCgroupMemoryLimit(""), std::nullopt);
    EXPECT_EQ(ParseCgroupMemoryLimit("12 GiB"), std::nullopt);
    EXPECT_EQ(ParseCgroupMemoryLimit("-1"), std::nullopt);
}

TEST_F(ResourceLimits, OverflowingProductsExceedEveryBudget) {
    EXPECT_EQ(SaturatingProduct({3, 5, 7}), 105u);
    EXPECT_EQ(SaturatingProduct({uint64_t(1) << 32, uint64_t(1) << 32}),
              std::numeric_limits<uint64_t>::max());
    EXPECT_EQ(ErrorOf([] {
                  CheckMemory(FileLoc{"f", 0, 0}, "it",
                              SaturatingProduct({uint64_t(1) << 40, uint64_t(1) << 40}));
              }),
              "f: error: it would take more than 2^64 bytes of memory; " + kOverBudget);
    EXPECT_NO_THROW(CheckMemory(FileLoc{"f", 0, 0}, "it", kGiB));
}

// ---- Film ---------------------------------------------------------------------------------------

TEST_F(ResourceLimits, FilmMemoryIsCheckedBeforeTheFilmAllocates) {
    // 1.6 * 10^9 pixels x (4 doubles + 3 floats + 3 bytes) = 75 GB.
    std::string file = kBad + "limit_film_resolution.pbrt";
    EXPECT_EQ(LoadError(file), file + ":2:12: error: the film's 40000 x 40000 pixels would take "
                                      "75200000000 bytes (70.0 GiB) of memory; " + kOverBudget);
}

TEST_F(ResourceLimits, FilmPixelCountMustFitAnInt) {
    std::string file = kBad + "limit_film_pixel_count.pbrt";
    EXPECT_EQ(LoadError(file), file + ":2:12: error: the film's 50000 x 50000 pixels are "
                                      "2500000000 in all; expected at most 2147483647");
}

TEST_F(ResourceLimits, FilmAxisMustFitFloatPixelCoordinates) {
    std::string file = kBad + "limit_film_axis.pbrt";
    EXPECT_EQ(LoadError(file), file + ":2:12: error: xresolution 20000000 is too large; expected "
                                      "at most 16777216 (2^24: pixel coordinates are 32-bit floats)");
}

TEST_F(ResourceLimits, CroppedHugeFilmAllocatesOnlyTheCrop) {
    // The same film, cropped on the command line to what fits.
    RenderOverrides overrides;
    overrides.pixelBounds = Bounds2i(Point2i(20000, 20000), Point2i(20016, 20008));
    std::unique_ptr<Scene> scene = LoadScene(kBad + "limit_film_resolution.pbrt", overrides);
    EXPECT_EQ(scene->film.PixelBounds().Area(), 16 * 8);
    EXPECT_EQ(scene->film.FullResolution(), Point2i(40000, 40000));
}

// ---- Samples per pixel --------------------------------------------------------------------------

TEST_F(ResourceLimits, StratifiedSampleCountMustFitAnInt) {
    std::string file = kBad + "limit_spp_stratified.pbrt";
    EXPECT_EQ(LoadError(file), file + ":2:22: error: stratified sampler: 100000 x 100000 = "
                                      "10000000000 samples per pixel; expected at most 2147483647");
}

TEST_F(ResourceLimits, ZSobolRoundedSampleCountMustFitAnInt) {
    std::string file = kBad + "limit_spp_zsobol.pbrt";
    const std::string message = "zsobol sampler: 2000000000 samples per pixel round up to "
                                "2147483648; expected at most 1073741824";
    EXPECT_EQ(LoadError(file), file + ":2:18: error: " + message);
    // The same count from the command line is reported there.
    RenderOverrides overrides;
    overrides.spp = 2000000000;
    std::string small = WriteFile("small.pbrt", "Film \"rgb\" \"integer xresolution\" 8 "
                                                "\"integer yresolution\" 8\nWorldBegin\n");
    EXPECT_EQ(LoadError(small, overrides), "--spp: error: " + message);
}

TEST_F(ResourceLimits, ZSobolSampleIndexMustFit63Bits) {
    std::string file = kBad + "limit_spp_zsobol_bits.pbrt";
    EXPECT_EQ(LoadError(file),
              file + ":3:18: error: zsobol sampler: 65536 samples per pixel at resolution "
                     "16777216 x 1 need 64-bit sample indices (16 bits for the samples, 2 x 24 for "
                     "the pixels); expected at most 63 bits");
}

TEST_F(ResourceLimits, ZSobolAtTheBitLimitStillSamples) {
    // 15 + 2 x 24 = 63 bits: the last sample of the last pixel shifts by 63, not 64 (UBSan
    // checks the shifts in the asan preset).
    ZSobolSampler sampler(1 << 15, Point2i(1 << 24, 1));
    sampler.StartPixelSample(Point2i((1 << 24) - 1, 0), (1 << 15) - 1);
    for (int i = 0; i < 4; ++i) {
        Point2f u = sampler.Get2D();
        EXPECT_TRUE(u.x >= 0 && u.x < 1 && u.y >= 0 && u.y < 1) << u.x << " " << u.y;
    }
    EXPECT_THROW(ZSobolSampler(1 << 16, Point2i(1 << 24, 1)), std::runtime_error);
}

// ---- Meshes -------------------------------------------------------------------------------------

TEST_F(ResourceLimits, LoopSubdivisionLevelsAreBoundedBeforeRefining) {
    // Each level quadruples the triangles: 4^40 of them overflow any count.
    std::string file = kBad + "limit_loopsubdiv_levels.pbrt";
    EXPECT_EQ(LoadError(file), file + ":3:1: error: loopsubdiv to level 40 would take more than "
                                      "2^64 bytes of memory; " + kOverBudget);
    std::string thirteen = WriteFile(
        "levels13.pbrt", "WorldBegin\nShape \"loopsubdiv\" \"integer levels\" 13 "
                         "\"integer indices\" [0 1 2] \"point3 P\" [0 0 0 1 0 0 0 1 0]\n");
    EXPECT_EQ(LoadError(thirteen), thirteen + ":2:1: error: loopsubdiv to level 13 would take "
                                              "3489660928 bytes (3.2 GiB) of memory; " +
                                              kOverBudget);
}

TEST_F(ResourceLimits, PlyFaceCountIsBoundedByTheFile) {
    // The header declares 2^31 faces; the 13 bytes after the vertices hold one.
    std::string file = kBad + "limit_ply_faces.pbrt";
    EXPECT_EQ(LoadError(file), kBad + "limit_ply_faces.ply:8:1: error: element \"face\" declares "
                                      "2147483648 instances; expected at most what the remaining "
                                      "13 bytes can hold");
}

TEST_F(ResourceLimits, PlyAsciiValuesTakeTwoBytesEach) {
    // The tightest ascii body: one-character values and single separators, no final newline.
    const std::string header = "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\n"
                               "property float y\nproperty float z\nelement face 1\n"
                               "property list uchar int vertex_indices\nend_header\n";
    std::string tight = fmt::format(fmt::runtime(header), 3) + "0 0 0 1 0 0 0 1 0 3 0 1 2";
    EXPECT_EQ(ParsePly(tight, "m.ply").triIndices.size(), 3u);
    // Six vertices need at least 36 bytes; the body has 25.
    std::string claims = fmt::format(fmt::runtime(header), 6) + "0 0 0 1 0 0 0 1 0 3 0 1 2";
    EXPECT_EQ(ErrorOf([&] { ParsePly(claims, "m.ply"); }),
              "m.ply:3:1: error: element \"vertex\" declares 6 instances; expected at most what "
              "the remaining 25 bytes can hold");
}

TEST_F(ResourceLimits, PlyMeshMemoryIsCheckedFromTheHeader) {
    // 90 vertices of eight one-byte properties become 90 x 32 bytes of points, normals and uvs.
    SetMemoryBudget(1024);
    std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 90\n";
    for (const char *name : {"x", "y", "z", "nx", "ny", "nz", "u", "v"})
        ply += fmt::format("property uchar {}\n", name);
    ply += "element face 1\nproperty list uchar uchar vertex_indices\nend_header\n";
    ply += std::string(90 * 8, '\0') + std::string("\3\0\1\2", 4);
    EXPECT_EQ(ErrorOf([&] { ParsePly(ply, "m.ply"); }),
              "m.ply:3:1: error: element \"vertex\" of 90 instances would take 2880 bytes (2.8 KiB) "
              "of memory; expected at most the memory budget of 1024 bytes (1.0 KiB, set by the "
              "application)");
}

TEST_F(ResourceLimits, PlyFileSizeIsCheckedBeforeReading) {
    std::string path = SparseFile("huge.ply", kTiB);
    EXPECT_EQ(ErrorOf([&] { ReadPly(path); }),
              path + ": error: reading the 1099511627776-byte PLY file would take 1099511627776 "
                     "bytes (1.0 TiB) of memory; " + kOverBudget);
}

TEST_F(ResourceLimits, EmittingMeshAreaLightsAreChecked) {
    // One area light per triangle: enough triangles to exceed a 1 MiB budget in lights, in a
    // scene file small enough to parse within it.
    SetMemoryBudget(1 << 20);
    size_t triangles = (1 << 20) / sizeof(Light) + 1;
    std::string indices;
    for (size_t i = 0; i < triangles; ++i) indices += "0 1 2 ";
    std::string file = WriteFile("lights.pbrt",
                                 "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\n"
                                 "WorldBegin\nAreaLightSource \"diffuse\"\n"
                                 "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] "
                                 "\"integer indices\" [" + indices + "]\n");
    std::string error = LoadError(file);
    std::string prefix = fmt::format("{}:4:1: error: the {} area lights of an emitting trianglemesh "
                                     "would take {} bytes (", file, triangles,
                                     triangles * sizeof(Light));
    EXPECT_TRUE(error.starts_with(prefix)) << error;
    EXPECT_TRUE(error.ends_with(" of memory; expected at most the memory budget of 1048576 bytes "
                                "(1.0 MiB, set by the application)")) << error;
}

// ---- Images -------------------------------------------------------------------------------------

TEST_F(ResourceLimits, ImageSizeIsCheckedFromTheHeader) {
    // A valid PNG header for 60000 x 60000 gray pixels: 57.6 GB as floats.
    std::string png = kBad + "limit_image_huge.png";
    const std::string expected = png + ": error: the 60000 x 60000 image of 1 channel would take "
                                       "57600000000 bytes (53.6 GiB) of memory; " + kOverBudget;
    EXPECT_EQ(ErrorOf([&] { Image::Read(png); }), expected);
    // Image textures and environment maps read through Image::Read.
    EXPECT_EQ(LoadError(kBad + "limit_image_texture.pbrt"), expected);
    EXPECT_EQ(LoadError(kBad + "limit_image_environment.pbrt"), expected);
}

TEST_F(ResourceLimits, VolumeImagesAreRefused) {
    // A 2 x 2 x 2 DDS volume texture: read_image would write both slices into a buffer sized
    // for one.
    std::string dds = kBad + "limit_image_volume.dds";
    try {
        Image::Read(dds);
        FAIL() << "no error";
    } catch (const std::runtime_error &e) {
        EXPECT_EQ(std::string(e.what()),
                  dds + ": error: the image is a volume of 2 slices; expected a 2D image");
    }
}

// ---- Files read whole ---------------------------------------------------------------------------

TEST_F(ResourceLimits, IncludedDeviceIsRefused) {
    std::string file = kBad + "limit_include_device.pbrt";
    EXPECT_EQ(LoadError(file), file + ":2:1: error: cannot open included file \"/dev/zero\": not a "
                                      "regular file (a device or pipe may never end); expected a file");
    EXPECT_EQ(LoadError("/dev/zero"), "/dev/zero: error: cannot open file: not a regular file (a "
                                      "device or pipe may never end); expected a file");
}

TEST_F(ResourceLimits, SceneFileSizeIsCheckedBeforeReading) {
    std::string huge = SparseFile("huge.pbrt", kTiB);
    std::string main = WriteFile("main.pbrt", "WorldBegin\nInclude \"huge.pbrt\"\n");
    const std::string what = "parsing the 1099511627776-byte file \"" + huge +
                             "\" would take 8796093022208 bytes (8.0 TiB) of memory; " + kOverBudget;
    EXPECT_EQ(LoadError(main), main + ":2:1: error: " + what);
    EXPECT_EQ(LoadError(huge), huge + ": error: " + what);
}

TEST_F(ResourceLimits, IncludedFilesMustFitTogether) {
    // 1000-byte files: one fits the budget of 12000 bytes (8 per byte), two do not, whether one
    // includes the other or both are included side by side.
    std::string text = "Include \"self.pbrt\"\n#";
    text += std::string(1000 - text.size() - 1, '.') + "\n";
    std::string self = WriteFile("self.pbrt", text);
    std::string leaf = WriteFile("leaf.pbrt", std::string(999, '#') + "\n");
    std::string twice = WriteFile("twice.pbrt", "Include \"leaf.pbrt\"\nInclude \"leaf.pbrt\"\n");
    SetMemoryBudget(12000);
    const std::string budget = " of memory; expected at most the memory budget of 12000 bytes "
                               "(11.7 KiB, set by the application)";
    EXPECT_EQ(LoadError(self), self + ":1:1: error: parsing 2 files of 2000 bytes in all would "
                                      "take 16000 bytes (15.6 KiB)" + budget);
    EXPECT_EQ(LoadError(twice), twice + ":2:1: error: parsing 3 files of 2040 bytes in all would "
                                        "take 16320 bytes (15.9 KiB)" + budget);
}

TEST_F(ResourceLimits, SpectrumFileThatIsADeviceIsRefused) {
    std::string file = kBad + "limit_spectrum_device.pbrt";
    EXPECT_EQ(LoadError(file), file + ":4:20: error: spectrum file \"/dev/zero\" cannot be read, "
                                      "expected a file of (wavelength, value) pairs");
}
