// pbrt-v4's measured material (bxdfs/measured.h) on RGL .bsdf files that WriteConductorBSDF
// makes from the rough conductor (materials/measuredwriter.h): f equals that analytic BRDF, the
// sampling follows its density (chi-square), Sample_f agrees with f and PDF; and the pieces
// under it, the piecewise-linear warp and the tensor file, on their own.
#include "tests/support/bxdf_properties.h"
#include "tests/support/chi2.h"

#include "pbrt_ext/bxdfs/conductor.h"
#include "pbrt_ext/bxdfs/measured.h"
#include "pbrt_ext/materials/measuredwriter.h"
#include "pbrt_ext/render.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/util/piecewiselinear2d.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/tensorfile.h"

#include "tests/support/scenefolder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <utility>
#include <memory>
#include <string>
#include <vector>

namespace pbrt {
namespace {

std::filesystem::path Folder() {
    return TestFolder(std::string("pbrt_ext_measured_test_") +
                      testing::UnitTest::GetInstance()->current_test_info()->name());
}

// A file of gold at alpha, resolution^2 nodes per grid, `thetas` values of theta_i, and the
// wavelengths given: the analytic BRDF's parameters and the file's data.
struct GoldFile {
    ConductorTableSpec spec;
    std::shared_ptr<const MeasuredBxDFData> data;
};

GoldFile MakeGold(Float alpha, int resolution, int thetas, std::vector<float> wavelengths) {
    GoldFile g;
    g.spec.alpha = alpha;
    g.spec.eta = *GetNamedSpectrum("metal-Au-eta");
    g.spec.k = *GetNamedSpectrum("metal-Au-k");
    g.spec.wavelengths = std::move(wavelengths);
    g.spec.resolution = resolution;
    g.spec.thetaCount = thetas;
    std::string path = (Folder() / "gold.bsdf").string();
    WriteConductorBSDF(path, g.spec);
    g.data = MeasuredBxDFData::Read(path);
    return g;
}

// Four copies of one wavelength (the tables' own, so that only the angles are interpolated).
SampledWavelengths At(Float lambda) { return SampledWavelengths::SampleUniform(0, lambda, lambda); }

ConductorBxDF Analytic(const GoldFile &g, const SampledWavelengths &lambda) {
    return ConductorBxDF(TrowbridgeReitzDistribution(g.spec.alpha, g.spec.alpha),
                         g.spec.eta.Sample(lambda), g.spec.k.Sample(lambda));
}

// The relative differences |f_measured / f_analytic - 1| over random pairs of directions above
// 0.2 in cosine, where the analytic f is at least 5 % of its value at wo's mirror direction (the
// lobe, not its far tail), sorted.
std::vector<double> RelativeErrors(const GoldFile &g, int pairs) {
    RNG rng(7);
    std::vector<double> errors;
    for (int i = 0; i < pairs; ++i) {
        SampledWavelengths lambda = At(g.spec.wavelengths[size_t(i) % g.spec.wavelengths.size()]);
        Vector3f wo = SampleUniformHemisphere(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
        Vector3f wi = SampleUniformHemisphere(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
        if (wo.z < 0.2f || wi.z < 0.2f) continue;
        ConductorBxDF analytic = Analytic(g, lambda);
        Float a = analytic.f(wo, wi, TransportMode::Radiance)[0];
        Float peak = analytic.f(wo, Vector3f(-wo.x, -wo.y, wo.z), TransportMode::Radiance)[0];
        Float m = MeasuredBxDF(g.data.get(), lambda).f(wo, wi, TransportMode::Radiance)[0];
        if (a >= 0.05f * peak) errors.push_back(std::abs(m / a - 1));
    }
    std::sort(errors.begin(), errors.end());
    return errors;
}

// The tables are interpolated bilinearly in the warped coordinates and linearly in theta_i, so
// f differs from the analytic BRDF by an interpolation error that shrinks as the square of the
// node spacing (measured with theta_i uniform in u_theta: at 64^2 nodes and 32 theta_i the median
// is 2.6e-3 for alpha 0.2 and 5.1e-4 for alpha 0.5, at 128^2 and 64 theta_i 6.3e-4 and 1.5e-4).
// At 96^2 nodes and 48 theta_i, here, the median is within 0.2 % (measured 1.0e-3 and 2.0e-4) and
// 99 % of the values within 1 % (2.2e-3, 2.9e-3). The largest (up to 7.1 %, alpha 0.5) are for wo
// beyond 70 degrees and wm within a few degrees of the normal: the tail of wo's visible normals,
// where the tables' nodes are sparse; within 8 %.
TEST(MeasuredBxDF, FIsTheAnalyticBRDFItWasMadeFrom) {
    for (Float alpha : {0.2f, 0.5f}) {
        GoldFile g = MakeGold(alpha, 96, 48, {400, 450, 500, 550, 600, 650, 700, 750});
        std::vector<double> errors = RelativeErrors(g, 40000);
        ASSERT_GT(errors.size(), 5000u);
        double median = errors[errors.size() / 2], p99 = errors[errors.size() * 99 / 100];
        EXPECT_LE(median, 2e-3) << "alpha " << alpha;
        EXPECT_LE(p99, 1e-2) << "alpha " << alpha;
        EXPECT_LE(errors.back(), 8e-2) << "alpha " << alpha;
        std::printf("alpha %g: %zu values, median %.2e, 99%% %.2e, max %.2e\n", alpha,
                    errors.size(), median, p99, errors.back());
    }
}

// Sampling follows PDF (chi-square, Šidák-corrected alpha 0.01 over the 6 tests), and Sample_f
// agrees with f and PDF, for a smooth and a rough gold at normal, oblique and grazing wo.
TEST(MeasuredBxDF, SamplingFollowsItsDensity) {
    Chi2Options opts;
    opts.numTests = 6;
    opts.seed = 23;
    for (Float alpha : {0.15f, 0.5f}) {
        GoldFile g = MakeGold(alpha, 32, 16, {450, 550, 650});
        MeasuredBxDF bxdf(g.data.get(), At(550));
        for (Vector3f wo : {Vector3f(0, 0, 1), Normalize(Vector3f(0.5f, 0.2f, 0.8f)),
                            Normalize(Vector3f(-0.9f, 0.3f, 0.2f))}) {
            Chi2Result r = Chi2TestBxDF(bxdf, wo, opts);
            EXPECT_TRUE(r.passed) << "alpha " << alpha << "\n" << r.message;
        }
    }
}

TEST(MeasuredBxDF, SampleMatchesEvalAndIsFinite) {
    GoldFile g = MakeGold(0.3f, 32, 16, {450, 550, 650});
    MeasuredBxDF bxdf(g.data.get(), At(450));
    BxDFCheckOptions opts;
    for (Vector3f wo : PropertyTestDirections()) {
        PropertyResult sampled = CheckSampleMatchesEval(bxdf, wo, opts);
        EXPECT_TRUE(sampled.passed) << sampled.message;
        PropertyResult finite = CheckFiniteNonNegative(bxdf, wo, opts);
        EXPECT_TRUE(finite.passed) << finite.message;
    }
    EXPECT_EQ(bxdf.Flags(), BxDFFlags::GlossyReflection);
    EXPECT_FALSE(bxdf.Sample_f(Vector3f(0, 0, 1), 0.5f, Point2f(0.3f, 0.6f), TransportMode::Radiance,
                               BxDFReflTransFlags::Transmission));
}

// ---- The piecewise-linear warp -------------------------------------------------------------

// A 5 x 4 density with one parameter of two values (two slices of different shapes).
PiecewiseLinear2D<1> TwoSlices() {
    const float data[2][4][5] = {{{1, 2, 3, 4, 5}, {0, 1, 0, 1, 0}, {2, 2, 2, 2, 2}, {5, 1, 0, 0, 3}},
                                 {{0, 0, 1, 0, 0}, {0, 1, 4, 1, 0}, {1, 4, 9, 4, 1}, {0, 1, 4, 1, 0}}};
    return PiecewiseLinear2D<1>(&data[0][0][0], 5, 4, {std::vector<float>{0.f, 1.f}}, true);
}

TEST(PiecewiseLinear2D, InvertUndoesSampleAndPdfIsTheDensity) {
    PiecewiseLinear2D<1> table = TwoSlices();
    RNG rng(3);
    for (Float param : {0.f, 0.3f, 1.f}) {
        for (int i = 0; i < 2000; ++i) {
            Point2f u(rng.Uniform<Float>(), rng.Uniform<Float>());
            PLSample s = table.Sample(u, {param});
            PLSample back = table.Invert(s.p, {param});
            EXPECT_NEAR(back.p[0], u[0], 2e-4f) << param;
            EXPECT_NEAR(back.p[1], u[1], 2e-4f) << param;
            EXPECT_NEAR(s.pdf, table.Evaluate(s.p, {param}), 1e-4f * std::max<Float>(1, s.pdf));
            EXPECT_NEAR(back.pdf, s.pdf, 1e-4f * std::max<Float>(1, s.pdf));
        }
    }
}

// Each slice integrates to 1, and between parameter values the density is the mixture of the
// neighbouring slices' densities (so that sampling and evaluation stay one distribution).
TEST(PiecewiseLinear2D, DensityIntegratesToOneAndMixesSlices) {
    PiecewiseLinear2D<1> table = TwoSlices();
    for (Float param : {-1.f, 0.f, 0.25f, 1.f, 2.f}) {
        double sum = 0;
        constexpr int n = 400;
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                sum += table.Evaluate(Point2f((x + 0.5f) / n, (y + 0.5f) / n), {param});
        EXPECT_NEAR(sum / (n * n), 1, 1e-4) << param;
    }
    Point2f p(0.37f, 0.61f);
    EXPECT_NEAR(table.Evaluate(p, {0.25f}),
                0.75f * table.Evaluate(p, {0.f}) + 0.25f * table.Evaluate(p, {1.f}), 1e-5f);
}

// The warp's sample counts in an 8 x 8 grid of cells against the density's integrals over them
// (chi-square, alpha 0.01; 1e5 samples; the parameter halfway between the slices).
TEST(PiecewiseLinear2D, SamplesFollowTheDensity) {
    PiecewiseLinear2D<1> table = TwoSlices();
    constexpr int cells = 8, samples = 100000, quadrature = 32;
    std::vector<double> observed(cells * cells, 0), expected(cells * cells, 0);
    RNG rng(11);
    for (int i = 0; i < samples; ++i) {
        Point2f p = table.Sample(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()), {0.5f}).p;
        int cx = std::min(int(p[0] * cells), cells - 1), cy = std::min(int(p[1] * cells), cells - 1);
        observed[size_t(cy * cells + cx)] += 1;
    }
    for (int y = 0; y < cells * quadrature; ++y)
        for (int x = 0; x < cells * quadrature; ++x) {
            Point2f p((x + 0.5f) / (cells * quadrature), (y + 0.5f) / (cells * quadrature));
            expected[size_t((y / quadrature) * cells + x / quadrature)] +=
                table.Evaluate(p, {0.5f}) * samples / Sqr(double(cells * quadrature));
        }
    std::vector<std::pair<double, double>> pairs;
    for (size_t i = 0; i < observed.size(); ++i) pairs.emplace_back(expected[i], observed[i]);
    chi2detail::Pearson pearson = chi2detail::PooledPearson(pairs, 5);
    EXPECT_GT(Chi2SurvivalProbability(pearson.statistic, pearson.dof), 0.01)
        << "statistic " << pearson.statistic << " dof " << pearson.dof;
}

TEST(PiecewiseLinear2D, RejectsTablesThatAreNotDensities) {
    const float negative[4] = {1, -1, 1, 1}, nan[4] = {1, NAN, 1, 1}, line[2] = {1, 1};
    EXPECT_THROW(PiecewiseLinear2D<0>(negative, 2, 2, {}, true), std::invalid_argument);
    EXPECT_THROW(PiecewiseLinear2D<0>(nan, 2, 2, {}, true), std::invalid_argument);
    EXPECT_THROW(PiecewiseLinear2D<0>(line, 2, 1, {}, true), std::invalid_argument);
    EXPECT_THROW(PiecewiseLinear2D<1>(negative, 2, 2, {std::vector<float>{1.f, 0.f}}, true),
                 std::invalid_argument);
    // Raw values (not a density) may be negative.
    EXPECT_NEAR(PiecewiseLinear2D<0>(negative, 2, 2, {}, false).Evaluate(Point2f(1, 0), {}), -1, 1e-6f);
}

// ---- The tensor file -----------------------------------------------------------------------

TEST(TensorFile, RoundTrip) {
    std::string path = (Folder() / "t.bsdf").string();
    TensorFields fields;
    fields["values"] = TensorField::FromFloats({2, 3}, {1, 2, 3, 4, 5, 6});
    fields["flag"] = TensorField::FromBytes({1}, {7});
    WriteTensorFile(path, fields);
    TensorFields back = ReadTensorFile(path);
    ASSERT_EQ(back.size(), 2u);
    EXPECT_EQ(back["values"].shape, (std::vector<uint64_t>{2, 3}));
    std::span<const float> v = back["values"].Floats();
    EXPECT_EQ(std::vector<float>(v.begin(), v.end()), (std::vector<float>{1, 2, 3, 4, 5, 6}));
    EXPECT_EQ(back["flag"].UInt8s()[0], 7);
}

// Every corruption is an error naming the file, never a crash or a huge allocation.
TEST(TensorFile, CorruptFilesAreErrors) {
    std::string good = (Folder() / "good.bsdf").string();
    TensorFields fields;
    fields["values"] = TensorField::FromFloats({2, 3}, {1, 2, 3, 4, 5, 6});
    WriteTensorFile(good, fields);
    std::ifstream in(good, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto errorOf = [&](std::string contents) {
        std::string path = (Folder() / "bad.bsdf").string();
        std::ofstream(path, std::ios::binary) << contents;
        try {
            ReadTensorFile(path);
        } catch (const std::runtime_error &e) {
            return std::string(e.what()).substr(path.size());
        }
        return std::string("no error");
    };
    // The header: magic 12, version 2, count 4 (bytes 0-17); the field: name length 2, "values"
    // 6, rank 2, type 1 (byte 28), offset 8, shape 2 x 8 (bytes 37-52); then the data.
    EXPECT_EQ(errorOf("tensor_fil"), ": error: the file ends inside the header, in the magic (at byte 0 of 10); truncated?");
    EXPECT_EQ(errorOf(std::string("tensor_file\0\2\0", 14) + bytes.substr(14)),
              ": error: tensor file version 2.0; expected 1.0");
    std::string notTensor = bytes;
    notTensor[0] = 'T';
    EXPECT_THAT(errorOf(notTensor), testing::HasSubstr("not a tensor file"));
    EXPECT_THAT(errorOf(bytes.substr(0, 40)), testing::HasSubstr("ends inside the header"));
    EXPECT_THAT(errorOf(bytes.substr(0, bytes.size() - 4)),
                testing::HasSubstr("field \"values\" (2 x 3) lies outside the file"));
    std::string badType = bytes;
    badType[28] = 12;
    EXPECT_THAT(errorOf(badType), testing::HasSubstr("field \"values\" has the unknown type 12"));
    std::string hugeShape = bytes;
    hugeShape[44] = char(0x7f);  // the first size's top byte
    EXPECT_THAT(errorOf(hugeShape), testing::HasSubstr("lies outside the file"));
    std::string twice = bytes;
    twice[14] = 2;  // two fields: the second header is read from the data, or the file ends
    EXPECT_THAT(errorOf(twice), testing::AnyOf(testing::HasSubstr("ends inside the header"),
                                               testing::HasSubstr("field")));
}

// ---- The material in a scene ---------------------------------------------------------------

std::string WriteScene(const std::string &material) {
    std::filesystem::path scene = Folder() / "scene.pbrt";
    std::ofstream(scene) << "LookAt 0 0 -3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
                         << "Film \"rgb\" \"integer xresolution\" 16 \"integer yresolution\" 16\n"
                         << "Sampler \"independent\" \"integer pixelsamples\" 16\nWorldBegin\n"
                         << "LightSource \"infinite\" \"rgb L\" [1 1 1]\n" << material << "\n"
                         << "Shape \"sphere\"\n";
    return scene.string();
}

// A measured sphere under a uniform sky reflects like the conductor it was made from: both
// spheres' mean pixel values agree within 2 % (16 spp over the image, 4 wavelengths a sample).
TEST(MeasuredMaterial, RendersLikeTheConductorItWasMadeFrom) {
    ConductorTableSpec spec;
    spec.alpha = 0.3f;
    spec.eta = *GetNamedSpectrum("metal-Au-eta");
    spec.k = *GetNamedSpectrum("metal-Au-k");
    for (int lambda = 360; lambda <= 830; lambda += 10) spec.wavelengths.push_back(float(lambda));
    spec.resolution = 48;
    spec.thetaCount = 24;
    WriteConductorBSDF((Folder() / "gold.bsdf").string(), spec);
    auto meanOf = [](const std::string &scene) {
        std::unique_ptr<Scene> s = LoadScene(scene, RenderOverrides{});
        Render(*s, RenderOptions{0, true});
        double sum = 0;
        for (Point2i p : s->film.PixelBounds())
            for (int c = 0; c < 3; ++c) sum += s->film.GetPixelRGB(p)[c];
        return sum;
    };
    double measured = meanOf(WriteScene("Material \"measured\" \"string filename\" \"gold.bsdf\""));
    double conductor = meanOf(WriteScene("Material \"conductor\" \"spectrum eta\" \"metal-Au-eta\" "
                                         "\"spectrum k\" \"metal-Au-k\" \"float roughness\" 0.3 "
                                         "\"bool remaproughness\" false"));
    EXPECT_NEAR(measured / conductor, 1, 0.02);
}

TEST(MeasuredMaterial, BadFilesAreErrorsAtTheParameter) {
    std::string missing = WriteScene("Material \"measured\" \"string filename\" \"none.bsdf\"");
    EXPECT_THAT(LoadErrorAfterPath(missing), testing::StartsWith(":7:21: error: "));
    EXPECT_THAT(LoadErrorAfterPath(missing), testing::HasSubstr("none.bsdf: error: cannot be read"));
    std::ofstream(Folder() / "short.bsdf") << "tensor_file";
    std::string truncated = WriteScene("Material \"measured\" \"string filename\" \"short.bsdf\"");
    EXPECT_THAT(LoadErrorAfterPath(truncated), testing::HasSubstr("truncated?"));
    TensorFields notBRDF;
    notBRDF["values"] = TensorField::FromFloats({2}, {1, 2});
    WriteTensorFile((Folder() / "other.bsdf").string(), notBRDF);
    std::string other = WriteScene("Material \"measured\" \"string filename\" \"other.bsdf\"");
    EXPECT_THAT(LoadErrorAfterPath(other),
                testing::HasSubstr("not an RGL measured BRDF: has no field \"phi_i\""));
    EXPECT_THAT(LoadErrorAfterPath(WriteScene("Material \"measured\"")),
                testing::HasSubstr("the measured material needs \"string filename\""));
}

}  // namespace
}  // namespace pbrt
