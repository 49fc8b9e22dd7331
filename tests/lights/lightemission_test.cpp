// Emission sampling of every light (SampleLe, PDF_Le), which paths traced from the lights start
// with: the densities a sample reports are the ones PDF_Le gives for its ray, and the emitted
// power estimated from the samples, L |cos| / (pdfPos pdfDir), is the light's Phi (within 5
// standard errors of the same samples, fixed seeds). Spectra are constants, so one wavelength
// stands for all.
#include "pbrt_ext/lights/lights.h"
#include "pbrt_ext/shapes/shapes.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace pbrt;

namespace {

const SampledWavelengths kLambda = SampledWavelengths::SampleUniform(0.3f);
const Bounds3f kScene(Point3f(-2, -1, -3), Point3f(3, 2, 1));

// A square image with a bright spot, for the image-based lights.
Image Spotted(int n) {
    Image image(Point2i(n, n));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            for (int c = 0; c < 3; ++c)
                image.SetChannel(Point2i(x, y), c, (x == n / 3 && y == n / 2) ? 30 : 0.2f + 0.05f * (x + c));
    return image;
}

struct Case {
    std::string name;
    Light light;
    // How Phi relates to what SampleLe emits: its exact integral; a midpoint rule over the
    // texels (the projection light); or another quantity (the portal light's Phi is the power
    // through its window, pbrt-v4's, while its rays leave from the whole scene's disk).
    enum class Phi { Exact, MidpointRule, Unrelated } phi = Phi::Exact;
};

std::vector<Case> Cases() {
    static TriangleMesh mesh = MakeTriangleMesh(Transform(), false, {0, 1, 2},
                                                {Point3f(-1, -1, 1), Point3f(2, -0.5f, 1.5f), Point3f(0, 1.5f, 0.5f)});
    std::vector<Case> cases = {
        {"point", PointLight(Translate(Vector3f(1, 0.5f, -1)), Spectrum(3.f), 2)},
        {"spot", SpotLight(RotateX(30) * Translate(Vector3f(0, 1, 0)), Spectrum(3.f), 2, 35, 20)},
        {"goniometric", GoniometricLight(RotateY(20), Spectrum(1.f), 2, Spotted(16))},
        {"projection", ProjectionLight(RotateX(-10), Spotted(32), &RGBColorSpace::sRGB(), 1, 40), Case::Phi::MidpointRule},
        {"distant", DistantLight(RotateX(40), Spectrum(2.f), 1.5f)},
        {"one-sided triangle", DiffuseAreaLight(Triangle(&mesh, 0), Spectrum(2.f), 1, false)},
        {"two-sided sphere", DiffuseAreaLight(Sphere(Translate(Vector3f(0, 1, 0)), false, 0.5f, -0.5f, 0.5f, 360),
                                              Spectrum(2.f), 1, true)},
        {"disk", DiffuseAreaLight(Disk(RotateX(60), true, 0.2f, 1, 0, 360), Spectrum(1.f), 3, false)},
        {"uniform infinite", UniformInfiniteLight(Spectrum(0.5f), 2)},
        {"image infinite", ImageInfiniteLight(RotateZ(30), Spotted(16), 1.5f)},
        {"portal", PortalImageInfiniteLight(Transform(), Spotted(16), 1, &RGBColorSpace::sRGB(),
                                            {Point3f(-1, 2, -1), Point3f(1, 2, -1), Point3f(1, 2, 1), Point3f(-1, 2, 1)}),
         Case::Phi::Unrelated},
    };
    for (Case &c : cases)
        c.light.Preprocess(kScene);
    return cases;
}

TEST(LightEmission, SampledDensitiesAreThoseOfPDF_Le) {
    for (const Case &c : Cases()) {
        RNG rng(5);
        int sampled = 0, mismatched = 0;
        for (int i = 0; i < 4000; ++i) {
            Point2f u1(rng.Uniform<Float>(), rng.Uniform<Float>()), u2(rng.Uniform<Float>(), rng.Uniform<Float>());
            pstd::optional<LightLeSample> les = c.light.SampleLe(u1, u2, kLambda, 0);
            if (!les)
                continue;
            ++sampled;
            LightLePDF pdf = les->OnSurface()
                                 ? c.light.PDF_Le(les->ray.o, les->n, les->uv, les->ray.d)
                                 : c.light.PDF_Le(les->ray);
            // A point light's position is a delta: its PDF_Le reports no positional density;
            // a distant light's direction likewise.
            bool posAgrees = c.light.Type() == LightType::DeltaPosition ||
                             std::abs(pdf.pos - les->pdfPos) <= 1e-3f * les->pdfPos;
            bool dirAgrees = c.light.Type() == LightType::DeltaDirection ||
                             std::abs(pdf.dir - les->pdfDir) <= 1e-3f * les->pdfDir;
            mismatched += !posAgrees || !dirAgrees;
        }
        EXPECT_GT(sampled, 3000) << c.name;
        // A direction that maps back to an image's texel boundary in float may land in the
        // neighbouring texel, whose density differs: a few in a thousand.
        EXPECT_LE(mismatched, sampled / 200) << c.name;
    }
}

TEST(LightEmission, SampledRaysCarryThePower) {
    for (const Case &c : Cases()) {
        if (c.phi == Case::Phi::Unrelated)
            continue;
        RNG rng(9);
        const int n = 400000;
        double sum = 0, sum2 = 0;
        for (int i = 0; i < n; ++i) {
            Point2f u1(rng.Uniform<Float>(), rng.Uniform<Float>()), u2(rng.Uniform<Float>(), rng.Uniform<Float>());
            pstd::optional<LightLeSample> les = c.light.SampleLe(u1, u2, kLambda, 0);
            double v = les ? les->L[0] * les->AbsCosTheta(les->ray.d) / (les->pdfPos * les->pdfDir) : 0;
            sum += v;
            sum2 += v * v;
        }
        double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
        double phi = c.light.Phi(kLambda)[0];
        ASSERT_GT(phi, 0) << c.name;
        double tolerance = 5 * se + (c.phi == Case::Phi::Exact ? 1e-5 : 0.01) * phi;
        EXPECT_NEAR(mean, phi, tolerance) << c.name << ": standard error " << se;
    }
}

}  // namespace
