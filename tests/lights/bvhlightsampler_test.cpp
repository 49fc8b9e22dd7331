// lightsamplers.h's BVHLightSampler and the bounds it is built from (lightbounds.h,
// util/directioncone.h):
//   - at every receiving point Sample's probability is PMF's (exactly), the PMF over all
//     lights sums to at most 1 (1e-4), and Sample's frequencies match PMF, the remainder being how
//     often it chooses nothing: a descent can reach a node whose children both have importance 0
//     though the node's own looser bounds did not (Pearson, 2e6 draws at each of 4 points,
//     alpha = 0.01 at each);
//   - the importance is conservative: wherever a light's own sampling finds radiance that reaches
//     the receiving side, its PMF is positive;
//   - lights without power are never chosen; lights without bounds are each chosen with
//     probability 1 / (nInfinite + 1) as pbrt-v4 chooses them, or in proportion to their
//     UnboundedLightImportance against the root's importance (InfiniteLightChoice), where a dim
//     distant light beside a bright area light is chosen in proportion;
//     under MIS (allowIncompletePDF) a uniform sky, whose light sampling then declines, is not;
//   - all of the above for both InfiniteLightChoices;
//   - cones: a union holds both cones, and the cone toward a box holds every point of it.
// Every random number comes from RNG with a fixed sequence.
#include "tests/support/chi2.h"

#include "pbrt_ext/lights/lights.h"
#include "pbrt_ext/lights/lightsamplers.h"
#include "pbrt_ext/shapes/shapes.h"
#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/directioncone.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/transform.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

using namespace pbrt;

namespace {

Point3f RandomPoint(RNG &rng, Float extent) {
    return Point3f(extent * (2 * rng.Uniform<Float>() - 1), extent * (2 * rng.Uniform<Float>() - 1),
                   extent * (2 * rng.Uniform<Float>() - 1));
}

Vector3f RandomDirection(RNG &rng) {
    return SampleUniformSphere(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
}

// A scene's worth of lights: 40 small triangles (one- and two-sided, powers over four orders of
// magnitude), a sphere, a disk, point and spot lights, one light without power, and optionally
// a uniform infinite light and a distant light. The mesh must outlive the lights.
struct LightSet {
    std::unique_ptr<TriangleMesh> mesh;
    std::vector<Light> lights;
};

LightSet MakeLights(bool withInfinite) {
    RNG rng(7);
    std::vector<Point3f> p;
    std::vector<int> indices;
    for (int t = 0; t < 40; ++t) {
        Point3f c = RandomPoint(rng, 4);
        for (int v = 0; v < 3; ++v) {
            p.push_back(c + 0.4f * RandomDirection(rng));
            indices.push_back(3 * t + v);
        }
    }
    LightSet set;
    set.mesh = std::make_unique<TriangleMesh>(MakeTriangleMesh(Transform(), false, indices, p));
    for (int t = 0; t < 40; ++t) {
        Float scale = std::pow(10.f, 4 * rng.Uniform<Float>() - 2);
        set.lights.push_back(DiffuseAreaLight(Shape(Triangle(set.mesh.get(), t)), Spectrum(1.f),
                                              scale, t % 3 == 0));
    }
    set.lights.push_back(DiffuseAreaLight(
        Shape(Sphere(Translate(Vector3f(2, -1, 0)), false, 0.3f, -0.3f, 0.3f, 360)),
        Spectrum(2.f), 1, false));
    set.lights.push_back(DiffuseAreaLight(
        Shape(Disk(Translate(Vector3f(-2, 1, 3)) * Rotate(70, Vector3f(1, 0, 0)), false, 0, 0.5f,
                   0, 360)),
        Spectrum(3.f), 1, false));
    set.lights.push_back(PointLight(Translate(Vector3f(0, 3, 1)), Spectrum(5.f), 1));
    set.lights.push_back(SpotLight(Translate(Vector3f(1, 1, -3)), Spectrum(20.f), 1, 35, 25));
    set.lights.push_back(PointLight(Transform(), Spectrum(0.f), 1));  // no power
    if (withInfinite) {
        set.lights.push_back(UniformInfiniteLight(Spectrum(0.3f), 1));
        set.lights.push_back(DistantLight(Rotate(30, Vector3f(1, 1, 0)), Spectrum(2.f), 1));
        for (size_t i = set.lights.size() - 2; i < set.lights.size(); ++i)
            set.lights[i].Preprocess(Bounds3f(Point3f(-5, -5, -5), Point3f(5, 5, 5)));
    }
    return set;
}

// fmt rather than "(" + std::to_string(...): GCC 12 misreads the inlined std::string operator+
// (false -Wstringop-overflow and -Warray-bounds).
std::string Str(Point3f p) { return fmt::format("({}, {}, {})", p.x, p.y, p.z); }

// Receiving points: surfaces with random normals, and points in free space (n = 0).
std::vector<LightSampleContext> Receivers(int count) {
    RNG rng(11);
    std::vector<LightSampleContext> ctxs;
    for (int i = 0; i < count; ++i) {
        Normal3f n = i % 4 == 3 ? Normal3f(0, 0, 0) : Normal3f(RandomDirection(rng));
        ctxs.push_back(LightSampleContext(RandomPoint(rng, 5), n, n));
    }
    return ctxs;
}

constexpr InfiniteLightChoice kChoices[] = {InfiniteLightChoice::Importance,
                                            InfiniteLightChoice::PbrtV4};

}  // namespace

TEST(BVHLightSampler, SampleAgreesWithPMF) {
    for (bool withInfinite : {false, true})
      for (InfiniteLightChoice choice : kChoices) {
        LightSet set = MakeLights(withInfinite);
        BVHLightSampler sampler(set.lights, choice);
        RNG rng(3);
        for (const LightSampleContext &ctx : Receivers(64)) {
            double sum = 0;
            for (int i = 0; i < int(set.lights.size()); ++i)
                sum += sampler.PMF(ctx, i);
            EXPECT_LE(sum, 1 + 1e-4) << "p " << Str(ctx.p);
            for (int k = 0; k < 2000; ++k) {
                pstd::optional<SampledLight> s = sampler.Sample(ctx, rng.Uniform<Float>());
                if (s) {
                    EXPECT_EQ(s->p, sampler.PMF(ctx, s->lightIndex));
                }
            }
        }
    }
}

TEST(BVHLightSampler, FrequenciesMatchPMF) {
    LightSet set = MakeLights(true);
    RNG rng(5);
    constexpr int n = 2000000;
    for (InfiniteLightChoice choice : kChoices)
    for (const LightSampleContext &ctx : Receivers(4)) {
        BVHLightSampler sampler(set.lights, choice);
        std::vector<double> counts(set.lights.size(), 0);
        double none = 0;
        for (int k = 0; k < n; ++k) {
            pstd::optional<SampledLight> s = sampler.Sample(ctx, rng.Uniform<Float>());
            if (s)
                counts[s->lightIndex] += 1;
            else
                none += 1;
        }
        std::vector<std::pair<double, double>> cells;
        double sum = 0;
        for (size_t i = 0; i < set.lights.size(); ++i) {
            double expected = n * double(sampler.PMF(ctx, int(i)));
            sum += expected;
            if (expected == 0)
                EXPECT_EQ(counts[i], 0) << "light " << i << " has PMF 0 but was chosen";
            else
                cells.push_back({expected, counts[i]});
        }
        cells.push_back({std::max(n - sum, 0.0), none});
        chi2detail::Pearson p = chi2detail::PooledPearson(cells, 5);
        EXPECT_GE(Chi2SurvivalProbability(p.statistic, p.dof), 0.01)
            << "chi2 = " << p.statistic << " at p " << Str(ctx.p);
    }
}

TEST(BVHLightSampler, ImportanceIsConservative) {
    LightSet set = MakeLights(true);
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    RNG rng(9);
    int reached = 0;
    for (InfiniteLightChoice choice : kChoices)
    for (bool allowIncompletePDF : {false, true})
    for (const LightSampleContext &ctx : Receivers(200)) {
        BVHLightSampler sampler(set.lights, choice, allowIncompletePDF);
        for (int i = 0; i < int(set.lights.size()); ++i) {
            for (int k = 0; k < 16; ++k) {
                pstd::optional<LightLiSample> ls = set.lights[i].SampleLi(
                    ctx, Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()), lambda, allowIncompletePDF);
                if (!ls || !ls->L || !(ls->pdf > 0))
                    continue;
                if (ctx.n != Normal3f(0, 0, 0) && AbsDot(ls->wi, Vector3f(ctx.n)) == 0)
                    continue;
                ++reached;
                ASSERT_GT(sampler.PMF(ctx, i), 0)
                    << "light " << i << " reaches p " << Str(ctx.p) << " but is never chosen there";
                break;
            }
        }
    }
    EXPECT_GT(reached, 4000);  // the test saw many light-receiver pairs that do interact
}

TEST(BVHLightSampler, LightsWithoutPowerOrBounds) {
    LightSet set = MakeLights(true);
    BVHLightSampler pbrtV4(set.lights, InfiniteLightChoice::PbrtV4);
    BVHLightSampler byImportance(set.lights, InfiniteLightChoice::Importance);
    BVHLightSampler underMIS(set.lights, InfiniteLightChoice::Importance, true);
    BVHLightSampler pbrtV4UnderMIS(set.lights, InfiniteLightChoice::PbrtV4, true);
    int noPower = int(set.lights.size()) - 3, infinite = noPower + 1, distant = noPower + 2;
    for (const LightSampleContext &ctx : Receivers(16)) {
        for (const BVHLightSampler *sampler : {&pbrtV4, &byImportance}) {
            EXPECT_EQ(sampler->PMF(ctx, noPower), 0);
            EXPECT_EQ(sampler->PMF(ctx, -1), 0);
        }
        // Two lights without bounds and the tree, equally likely.
        EXPECT_FLOAT_EQ(pbrtV4.PMF(ctx, infinite), 1.f / 3);
        EXPECT_FLOAT_EQ(pbrtV4.PMF(ctx, distant), 1.f / 3);
        // By importance, in the ratio of the irradiance they give: pi 0.3 from the sky, 2 |cos|
        // from the sun (it shines along light-space -z, turned by the rotation).
        Vector3f toSun = Normalize(Rotate(30, Vector3f(1, 1, 0))(Vector3f(0, 0, 1)));
        Float cosSun = ctx.n == Normal3f(0, 0, 0) ? 1 : AbsDot(toSun, Vector3f(ctx.n));
        EXPECT_NEAR(byImportance.PMF(ctx, infinite) * 2 * cosSun,
                    byImportance.PMF(ctx, distant) * Pi * 0.3f, 1e-5f)
            << "p " << Str(ctx.p);
        // Under MIS the uniform sky's light sampling declines (BSDF sampling covers it), so it
        // is never chosen; pbrt-v4's choice still spends a third of the samples on it.
        EXPECT_EQ(underMIS.PMF(ctx, infinite), 0);
        EXPECT_GT(underMIS.PMF(ctx, distant), 0);
        EXPECT_FLOAT_EQ(pbrtV4UnderMIS.PMF(ctx, infinite), 1.f / 3);
    }
    std::vector<Light> onlyInfinite = {UniformInfiniteLight(Spectrum(1.f), 1)};
    LightSampleContext ctx(Point3f(0, 0, 0), Normal3f(0, 0, 1), Normal3f(0, 0, 1));
    for (InfiniteLightChoice choice : kChoices) {
        BVHLightSampler infiniteOnly(onlyInfinite, choice);
        EXPECT_EQ(infiniteOnly.Sample(ctx, 0.7f)->lightIndex, 0);
        EXPECT_EQ(infiniteOnly.PMF(ctx, 0), 1);
        std::vector<Light> none;
        EXPECT_FALSE(BVHLightSampler(none, choice).Sample(ctx, 0.3f).has_value());
    }
}

// pbrt-v4's killeroo scenes: a disk light of radiance 50 and radius 150 at height 800 over a
// floor, and a distant light of radiance 0.2. pbrt-v4 gives the distant light half the samples
// though it gives the floor under 5 % of its irradiance; by importance it gets about that share.
TEST(BVHLightSampler, ADimDistantLightBesideABrightDiskGetsItsShare) {
    std::vector<Light> lights;
    lights.push_back(DiffuseAreaLight(
        Shape(Disk(Translate(Vector3f(0, 0, 800)), true, 0, 150, 0, 360)), Spectrum(50.f), 1, false));
    lights.push_back(DistantLight(Transform(), Spectrum(0.2f), 1));
    lights.back().Preprocess(Bounds3f(Point3f(-400, -400, 0), Point3f(400, 400, 800)));
    LightSampleContext floor(Point3f(100, -50, 0), Normal3f(0, 0, 1), Normal3f(0, 0, 1));
    // The disk's irradiance at the floor, as a small light: L area / d^2.
    Float diskIrradiance = 50 * Pi * Sqr(150.f) / Sqr(800.f), distantIrradiance = 0.2f;
    Float share = distantIrradiance / (distantIrradiance + diskIrradiance);
    EXPECT_EQ(BVHLightSampler(lights, InfiniteLightChoice::PbrtV4).PMF(floor, 1), 0.5f);
    Float pmf = BVHLightSampler(lights, InfiniteLightChoice::Importance).PMF(floor, 1);
    EXPECT_GT(pmf, share / 2);
    EXPECT_LT(pmf, 2 * share);
}

TEST(DirectionCone, UnionHoldsBothCones) {
    RNG rng(13);
    for (int trial = 0; trial < 2000; ++trial) {
        DirectionCone a(RandomDirection(rng), 2 * rng.Uniform<Float>() - 1);
        DirectionCone b(RandomDirection(rng), 2 * rng.Uniform<Float>() - 1);
        DirectionCone u = Union(a, b);
        for (const DirectionCone &c : {a, b}) {
            // The cone's rim: the axis turned by its full angle.
            Vector3f x, y;
            CoordinateSystem(c.w, &x, &y);
            Float sinTheta = SafeSqrt(1 - Sqr(c.cosTheta));
            Float phi = 2 * Pi * rng.Uniform<Float>();
            Vector3f rim = c.cosTheta * c.w + sinTheta * (std::cos(phi) * x + std::sin(phi) * y);
            EXPECT_GE(Dot(rim, u.w), u.cosTheta - 1e-4f) << "trial " << trial;
        }
    }
}

TEST(DirectionCone, BoundSubtendedDirectionsHoldsTheBox) {
    RNG rng(17);
    for (int trial = 0; trial < 500; ++trial) {
        Bounds3f box(RandomPoint(rng, 2), RandomPoint(rng, 2));
        Point3f p = RandomPoint(rng, 6);
        DirectionCone cone = BoundSubtendedDirections(box, p);
        for (int k = 0; k < 20; ++k) {
            Point3f q = box.Lerp(Point3f(rng.Uniform<Float>(), rng.Uniform<Float>(),
                                         rng.Uniform<Float>()));
            if (q == p)
                continue;
            EXPECT_GE(Dot(Normalize(q - p), cone.w), cone.cosTheta - 1e-4f);
        }
    }
}
