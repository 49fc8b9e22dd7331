// Film slices (issue 21): renders of disjoint sample ranges, written, read back and merged, equal
// one render of all the samples to float rounding, for every filter and sampler and for the
// integrators that splat; slices of different renders, overlapping slices and slices
// with a gap between them are refused.
#include "pbrt_ext/film/filmslice.h"
#include "pbrt_ext/render.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/scene/sceneloader.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace pbrt;

namespace {

namespace fs = std::filesystem;

// One per process: ctest runs the cases in parallel.
fs::path TempDir() {
    fs::path dir = fs::temp_directory_path() / ("pbrt_ext_filmslice_test." + std::to_string(getpid()));
    fs::create_directories(dir);
    return dir;
}

// A small room: a diffuse floor and back wall, a glossy sphere, a quad light above.
std::string SceneText(const std::string &filter, const std::string &sampler, int spp,
                      const std::string &integrator = "path") {
    std::ostringstream s;
    s << "LookAt 0 1 4  0 0.6 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\n"
      << "Film \"rgb\" \"integer xresolution\" 20 \"integer yresolution\" 14\n"
      << "PixelFilter \"" << filter << "\"\n"
      << "Sampler \"" << sampler << "\" \"integer pixelsamples\" " << spp << "\n"
      << "Integrator \"" << integrator << "\" \"integer maxdepth\" 4\nWorldBegin\n"
      << "AttributeBegin\n  AreaLightSource \"diffuse\" \"rgb L\" [8 8 8]\n"
      << "  Shape \"bilinearmesh\" \"point3 P\" [-0.5 2 -0.5  0.5 2 -0.5  -0.5 2 0.5  0.5 2 0.5]\n"
      << "AttributeEnd\n"
      << "Material \"diffuse\" \"rgb reflectance\" [0.6 0.5 0.4]\n"
      << "Shape \"bilinearmesh\" \"point3 P\" [-3 0 -3  3 0 -3  -3 0 3  3 0 3]\n"
      << "Shape \"bilinearmesh\" \"point3 P\" [-3 0 -1.5  3 0 -1.5  -3 3 -1.5  3 3 -1.5]\n"
      << "Material \"conductor\" \"float roughness\" 0.2\n"
      << "AttributeBegin\n  Translate 0 0.5 0\n  Shape \"sphere\" \"float radius\" 0.5\nAttributeEnd\n";
    return s.str();
}

struct Rendered {
    std::unique_ptr<Scene> scene;
    FilmSlice slice;
};

// Renders samples (all when unset) of the scene text, as pbrt_ext --samples does.
Rendered RenderSamples(const std::string &text, std::optional<SampleRange> samples,
                       RenderOverrides overrides = {}) {
    fs::path file = TempDir() / "scene.pbrt";
    std::ofstream(file) << text;
    overrides.quiet = true;
    Rendered r{LoadScene(file.string(), overrides), {}};
    RenderOptions options{2, true};
    options.samples = samples;
    RenderStatistics stats = Render(*r.scene, options);
    SampleRange rendered = SamplesToRender(*r.scene, options);
    SliceIdentity identity = MakeSliceIdentity(text, r.scene->sampler, r.scene->integratorOptions,
                                               r.scene->film, overrides);
    r.slice = FilmSlice::FromFilm(r.scene->film, rendered, stats.seconds, std::move(identity),
                                  file.string());
    return r;
}

// Writes each slice and reads it back, as a merge over files sees them.
FilmSlice ThroughFile(const FilmSlice &slice, const std::string &name) {
    std::string path = (TempDir() / name).string();
    slice.Write(path);
    return FilmSlice::Read(path);
}

// The largest difference relative to the full render's value, where that is not tiny (1e-3).
double MaxRelativeDifference(const Image &merged, const Image &full) {
    double worst = 0;
    for (int y = 0; y < full.Resolution().y; ++y)
        for (int x = 0; x < full.Resolution().x; ++x)
            for (int c = 0; c < 3; ++c) {
                double f = full.GetChannel({x, y}, c), m = merged.GetChannel({x, y}, c);
                worst = std::max(worst, std::abs(m - f) / std::max(std::abs(f), 1e-3));
            }
    return worst;
}

struct MergeCase {
    const char *filter, *sampler, *integrator;
};

class FilmSliceMerge : public testing::TestWithParam<MergeCase> {};

// Threshold 1e-5: the sums pass through 32-bit floats (relative rounding 6e-8 per slice).
TEST_P(FilmSliceMerge, ThreeSlicesEqualOneRender) {
    const MergeCase c = GetParam();
    const std::string text = SceneText(c.filter, c.sampler, 16, c.integrator);
    Rendered full = RenderSamples(text, std::nullopt);
    std::vector<FilmSlice> slices;
    std::vector<std::string> names;
    for (SampleRange range : {SampleRange{7, 16}, SampleRange{0, 3}, SampleRange{3, 7}}) {
        names.push_back("slice" + std::to_string(range.first) + ".exr");
        slices.push_back(ThroughFile(RenderSamples(text, range).slice, names.back()));
    }
    FilmSlice merged = MergeFilmSlices(slices, names);
    EXPECT_EQ(merged.samples, (SampleRange{0, 16}));
    // Only the integrators that trace paths from the lights splat.
    const std::string integrator = c.integrator;
    EXPECT_EQ(merged.splats.empty(), integrator != "bdpt" && integrator != "lightpath");
    const Image fullImage = full.scene->film.GetImage();
    EXPECT_LE(MaxRelativeDifference(merged.GetImage(), fullImage), 1e-5);
    // A full render's own slice gives the film's image (the same sums, the same ratio).
    EXPECT_LE(MaxRelativeDifference(full.slice.GetImage(), fullImage), 1e-6);
    // The merge is a slice too, read back unchanged.
    EXPECT_LE(MaxRelativeDifference(ThroughFile(merged, "merged.exr").GetImage(), fullImage), 1e-5);
}

INSTANTIATE_TEST_SUITE_P(
    FiltersSamplersIntegrators, FilmSliceMerge,
    testing::Values(MergeCase{"box", "independent", "path"}, MergeCase{"gaussian", "independent", "path"},
                    MergeCase{"box", "zsobol", "path"}, MergeCase{"gaussian", "zsobol", "path"},
                    MergeCase{"gaussian", "zsobol", "bdpt"},
                    // The other filters (Mitchell's and Lanczos's weights go negative) and samplers.
                    MergeCase{"mitchell", "stratified", "path"}, MergeCase{"lanczos", "halton", "path"},
                    MergeCase{"triangle", "sobol", "path"}, MergeCase{"box", "paddedsobol", "lightpath"},
                    MergeCase{"gaussian", "pmj02bn", "path"},
                    // pbrt-v4's estimators without MIS.
                    MergeCase{"gaussian", "zsobol", "simplepath"}, MergeCase{"box", "independent", "randomwalk"}),
    [](const testing::TestParamInfo<MergeCase> &param) {
        return std::string(param.param.filter) + "_" + param.param.sampler + "_" + param.param.integrator;
    });

// The message of the merge's refusal; empty when it merged.
std::string MergeError(const std::vector<FilmSlice> &slices) {
    std::vector<std::string> names;
    for (size_t i = 0; i < slices.size(); ++i) names.push_back(fmt::format("s{}.exr", i));
    try {
        MergeFilmSlices(slices, names);
    } catch (const std::runtime_error &e) {
        return e.what();
    }
    return "";
}

TEST(FilmSliceMerge, RefusesOverlapsGapsAndOtherRenders) {
    const std::string text = SceneText("box", "independent", 8);
    FilmSlice first = RenderSamples(text, SampleRange{0, 4}).slice;
    FilmSlice rest = RenderSamples(text, SampleRange{4, 8}).slice;
    ASSERT_EQ(MergeError({first, rest}), "");

    EXPECT_NE(MergeError({first, RenderSamples(text, SampleRange{3, 8}).slice}).find("overlap"), std::string::npos);
    EXPECT_NE(MergeError({first, first}).find("overlap"), std::string::npos);
    EXPECT_NE(MergeError({first, RenderSamples(text, SampleRange{5, 8}).slice}).find("samples 4:5 are missing"),
              std::string::npos);
    // The same scene file with another seed, sample count, film size or integrator.
    RenderOverrides seed, spp, film, integrator;
    seed.seed = 1;
    spp.spp = 9;
    film.resolution = Point2i(20, 15);
    integrator.integrator = "bdpt";
    for (auto [overrides, what] : {std::pair{seed, "sampler"}, std::pair{spp, "sampler"},
                                   std::pair{film, "film"}, std::pair{integrator, "integrator"}})
        EXPECT_NE(MergeError({first, RenderSamples(text, SampleRange{4, 8}, overrides).slice})
                      .find(std::string("their ") + what + " differs"),
                  std::string::npos)
            << what;
    // Another scene file (another filter).
    EXPECT_NE(MergeError({first, RenderSamples(SceneText("gaussian", "independent", 8), SampleRange{4, 8}).slice})
                  .find("their scene differs"),
              std::string::npos);
}

TEST(FilmSliceFile, AnImageWithoutSumsIsNoSlice) {
    Rendered full = RenderSamples(SceneText("box", "independent", 2), std::nullopt);
    std::string path = (TempDir() / "plain.exr").string();
    full.scene->film.GetImage().Write(path);
    try {
        FilmSlice::Read(path);
        FAIL() << "read a plain image as a slice";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find(path + ": error: not a film slice"), std::string::npos) << e.what();
    }
}

// The message of reading the slice back after Write; empty when it reads.
std::string ReadError(const FilmSlice &slice) {
    std::string path = (TempDir() / "tampered.exr").string();
    slice.Write(path);
    try {
        FilmSlice::Read(path);
    } catch (const std::runtime_error &e) {
        return e.what();
    }
    return "";
}

TEST(FilmSliceFile, AttributesOutOfRangeAreRefused) {
    FilmSlice slice = RenderSamples(SceneText("box", "independent", 4), SampleRange{0, 2}).slice;
    ASSERT_EQ(ReadError(slice), "");
    FilmSlice huge = slice;
    huge.samples = {0, std::numeric_limits<int>::max()};
    EXPECT_NE(ReadError(huge).find("expected integers from 0 to 1073741824"), std::string::npos);
    FilmSlice outside = slice;
    outside.fullResolution = Point2i(10, 10);
    EXPECT_NE(ReadError(outside).find("not inside the fullResolution"), std::string::npos);
}

TEST(FilmSliceRender, RefusesRangesOutsideTheSamplerAndSPPM) {
    fs::path file = TempDir() / "range.pbrt";
    std::ofstream(file) << SceneText("box", "independent", 8);
    RenderOverrides overrides;
    overrides.quiet = true;
    std::unique_ptr<Scene> scene = LoadScene(file.string(), overrides);
    for (SampleRange bad : {SampleRange{0, 9}, SampleRange{4, 4}, SampleRange{-1, 2}}) {
        RenderOptions options{1, true};
        options.samples = bad;
        EXPECT_THROW(Render(*scene, options), std::invalid_argument);
    }
    // sppm's iterations and mlt's chains are no samples of their own.
    for (const char *integrator : {"sppm", "mlt"}) {
        overrides.integrator = integrator;
        std::unique_ptr<Scene> whole = LoadScene(file.string(), overrides);
        RenderOptions options{1, true};
        options.samples = SampleRange{0, 4};
        EXPECT_THROW(Render(*whole, options), std::invalid_argument) << integrator;
    }
}

}  // namespace
