// pbrt-v4's debugging switches (--quick, --force-diffuse, --disable-*-jitter,
// --disable-texture-filtering, --disable-image-textures) and the scene's Option directives, which
// set them too and win over the command line, as in pbrt-v4.
#include "pbrt_ext/cameras/cameras.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/textures/mipmap.h"
#include "pbrt_ext/util/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace pbrt;

namespace {

constexpr const char *kScene = R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" 30
Film "rgb" "integer xresolution" 64 "integer yresolution" 40 "string filename" "out.exr"
Sampler "independent" "integer pixelsamples" 32
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Texture "checks" "spectrum" "checkerboard" "float uscale" 8 "float vscale" 8
Material "diffuse" "texture reflectance" "checks"
Shape "sphere"
)";

std::unique_ptr<Scene> Load(const std::string &text, RenderOverrides overrides = {}) {
    overrides.quiet = true;
    return LoadScene(std::vector<SceneFile>{{"<test>", text}}, overrides);
}

TEST(Quick, AQuarterOfTheResolutionAndOneSample) {
    RenderOverrides o;
    o.quick = true;
    std::unique_ptr<Scene> scene = Load(kScene, o);
    EXPECT_EQ(scene->film.FullResolution(), Point2i(16, 10));
    EXPECT_EQ(scene->sampler.SamplesPerPixel(), 1);
    o.spp = 64;  // --quick wins over --spp, as in pbrt-v4
    EXPECT_EQ(Load(kScene, o)->sampler.SamplesPerPixel(), 1);
}

TEST(Switches, DefaultsJitterAndFilter) {
    std::unique_ptr<Scene> scene = Load(kScene);
    EXPECT_FALSE(scene->switches.forceDiffuse);
    EXPECT_TRUE(scene->switches.pixelJitter);
    EXPECT_TRUE(scene->switches.wavelengthJitter);
    EXPECT_TRUE(scene->usesRayDifferentials);  // the checkerboard filters over the footprint
}

TEST(Switches, CommandLineSetsEach) {
    RenderOverrides o;
    o.forceDiffuse = o.disablePixelJitter = o.disableWavelengthJitter = o.disableTextureFiltering = true;
    std::unique_ptr<Scene> scene = Load(kScene, o);
    EXPECT_TRUE(scene->switches.forceDiffuse);
    EXPECT_FALSE(scene->switches.pixelJitter);
    EXPECT_FALSE(scene->switches.wavelengthJitter);
    EXPECT_FALSE(scene->usesRayDifferentials);
    // Every sample carries the same wavelengths.
    SampledWavelengths a = scene->SampleWavelengths(0.1f), b = scene->SampleWavelengths(0.9f);
    for (int i = 0; i < NSpectrumSamples; ++i) EXPECT_EQ(a[i], b[i]);
}

TEST(Switches, TheScenesOptionsWinOverTheCommandLine) {
    RenderOverrides o;
    o.disablePixelJitter = true;
    o.seed = 1;
    std::string text = "Option \"bool disablepixeljitter\" false\n"
                       "Option \"disablewavelengthjitter\" true\n"
                       "Option \"bool forcediffuse\" true\n"
                       "Option \"string rendercoordsys\" \"camera\"\n"
                       "Option \"bool wavefront\" true\n";
    text.append(kScene);
    std::unique_ptr<Scene> scene = Load(text, o);
    EXPECT_TRUE(scene->switches.pixelJitter);
    EXPECT_FALSE(scene->switches.wavelengthJitter);
    EXPECT_TRUE(scene->switches.forceDiffuse);
    EXPECT_EQ(scene->integratorOptions.type, IntegratorType::VolPath);
}

TEST(Switches, TheScenesSeedWinsOverTheCommandLine) {
    // The same sampler state as --seed 7 gives: the first sample of a pixel equal.
    RenderOverrides seven;
    seven.seed = 7;
    Sampler a = Load(kScene, seven)->sampler;
    Sampler b = Load(std::string("Option \"integer seed\" 7\n") + kScene)->sampler;
    Sampler c = Load(kScene)->sampler;
    a.StartPixelSample(Point2i(3, 4), 0);
    b.StartPixelSample(Point2i(3, 4), 0);
    c.StartPixelSample(Point2i(3, 4), 0);
    Float ua = a.Get1D(), ub = b.Get1D(), uc = c.Get1D();
    EXPECT_EQ(ua, ub);
    EXPECT_NE(ua, uc);
}

TEST(Switches, ABadOptionValueIsAnErrorAtItsLine) {
    try {
        Load(std::string("Option \"string rendercoordsys\" \"screen\"\n") + kScene);
        FAIL() << "no error";
    } catch (const ParseError &e) {
        EXPECT_NE(std::string(e.what()).find("<test>:1:"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("camera, cameraworld or world"), std::string::npos) << e.what();
    }
}

TEST(PixelJitter, DisabledTakesThePixelCentreAndWeightOne) {
    Sampler sampler = IndependentSampler(4, 0);
    Filter filter;  // pbrt-v4's default Gaussian
    sampler.StartPixelSample(Point2i(5, 9), 0);
    CameraSample cs = GetCameraSample(sampler, Point2i(5, 9), filter, true, false);
    EXPECT_EQ(cs.pFilm, Point2f(5.5f, 9.5f));
    EXPECT_EQ(cs.pLens, Point2f(0.5f, 0.5f));
    EXPECT_EQ(cs.time, 0.5f);
    EXPECT_EQ(cs.filterWeight, 1);
}

TEST(ForceDiffuse, ADiffuseBSDFKeepsItsReflectance) {
    SurfaceInteraction si;
    si.wo = Normalize(Vector3f(0.3f, -0.2f, 1));
    si.shading.n = Normal3f(0, 0, 1);
    si.shading.dpdu = Vector3f(1, 0, 0);
    SampledSpectrum R(0.3f);
    BSDF diffuse = DiffuseEquivalent(BSDF(si.shading.n, si.shading.dpdu, DiffuseBxDF(R)), si);
    Vector3f wi = Normalize(Vector3f(-0.5f, 0.1f, 0.7f));
    // Cosine sampling weighs every sample of a Lambertian BSDF by exactly R: the quadrature is
    // exact.
    SampledSpectrum f = diffuse.f(si.wo, wi);
    for (int i = 0; i < NSpectrumSamples; ++i) EXPECT_NEAR(f[i], 0.3f * InvPi, 1e-6f);
}

TEST(ForceDiffuse, AConductorBecomesDiffuseWithItsAlbedo) {
    SurfaceInteraction si;
    si.wo = Normalize(Vector3f(0.1f, 0.2f, 1));
    si.shading.n = Normal3f(0, 0, 1);
    si.shading.dpdu = Vector3f(1, 0, 0);
    // A smooth conductor: its albedo is the Fresnel reflectance at wo, whatever the samples.
    SampledSpectrum eta(0.2f), k(3.0f);
    BSDF mirror(si.shading.n, si.shading.dpdu,
                ConductorBxDF(TrowbridgeReitzDistribution(0, 0), eta, k));
    BSDF diffuse = DiffuseEquivalent(mirror, si);
    EXPECT_TRUE(IsDiffuse(diffuse.Flags()));
    EXPECT_FALSE(IsSpecular(diffuse.Flags()));
    SampledSpectrum expected = FrComplex(AbsCosTheta(si.wo), eta, k);
    SampledSpectrum f = diffuse.f(si.wo, Vector3f(0, 0, 1));
    for (int i = 0; i < NSpectrumSamples; ++i) EXPECT_NEAR(f[i] * Pi, expected[i], 1e-5f);
}

TEST(ImageTextures, DisabledKeepOnlyTheAverage) {
    Image image(Point2i(4, 2));
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) {
            image.SetChannel(Point2i(x, y), 0, Float(x));
            image.SetChannel(Point2i(x, y), 1, Float(y));
            image.SetChannel(Point2i(x, y), 2, 1);
        }
    MIPMap average(image, WrapMode::Repeat, MIPMapFilterOptions{FilterFunction::Bilinear, 8, true});
    ASSERT_EQ(average.Levels(), 1);
    EXPECT_EQ(average.LevelResolution(0), Point2i(1, 1));
    RGB v = average.Filter(Point2f(0.1f, 0.7f), Vector2f(0, 0), Vector2f(0, 0));
    EXPECT_NEAR(v.r, 1.5f, 1e-5f);  // the mean of 0, 1, 2, 3
    EXPECT_NEAR(v.g, 0.5f, 1e-5f);
    EXPECT_NEAR(v.b, 1.0f, 1e-5f);
    MIPMap full(image, WrapMode::Repeat, MIPMapFilterOptions{});
    EXPECT_GT(full.Levels(), 1);
}

}  // namespace
