// Materials: bump and normal mapping perturb the shading frame exactly as pbrt-v4's formulas say;
// a mix chooses deterministically per hit.
#include "pbrt_ext/materials/materials.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

using namespace pbrt;

namespace {

// A hit on the plane z = 0 with uv = (x, y): dpdu = x, dpdv = y, n = z.
SurfaceInteraction PlaneHit(Point2f uv) {
    SurfaceInteraction si;
    si.p = Point3f(uv[0], uv[1], 0);
    si.n = si.shading.n = Normal3f(0, 0, 1);
    si.uv = uv;
    si.wo = Vector3f(0, 0, 1);
    si.dpdu = si.shading.dpdu = Vector3f(1, 0, 0);
    si.dpdv = si.shading.dpdv = Vector3f(0, 1, 0);
    return si;
}

// The world-space shading normal of a BSDF: the direction its local frame calls +z.
Vector3f ShadingNormal(const BSDF &bsdf) { return bsdf.LocalToRender(Vector3f(0, 0, 1)); }

// The material's BSDF at a hit, for some visible wavelengths (the frame does not depend on
// them). si is a copy: a bump or normal map perturbs its shading frame.
BSDF GetBSDF(const Material &m, SurfaceInteraction si) {
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    return m.GetBSDF(si, lambda);
}

// A diffuse material bumped by d(u) from a 2-texel image [0, k] with bilinear filtering and
// clamp: slope 2k in the middle, d = k/2 there.
Material RampBumpedMaterial(Float k) {
    Image image(Point2i(2, 1));
    for (int c = 0; c < 3; ++c) {
        image.SetChannel(Point2i(0, 0), c, 0);
        image.SetChannel(Point2i(1, 0), c, k);
    }
    FloatImageTexture ramp;
    ramp.mipmap = std::make_shared<MIPMap>(std::move(image), WrapMode::Clamp, MIPMapFilterOptions{});
    Material m = DiffuseMaterial{};
    m.SetDisplacement(ramp);
    return m;
}

}  // namespace

TEST(BumpMapping, RampDisplacementTiltsTheNormalByItsSlope) {
    // dp/du becomes (1, 0, 2k), so the normal is normalize(-2k, 0, 1).
    constexpr Float k = 0.25f;
    Material m = RampBumpedMaterial(k);
    Vector3f n = ShadingNormal(GetBSDF(m, PlaneHit(Point2f(0.5f, 0.5f))));
    Vector3f expected = Normalize(Vector3f(-2 * k, 0, 1));
    EXPECT_NEAR(n.x, expected.x, 1e-3f);
    EXPECT_NEAR(n.y, expected.y, 1e-3f);
    EXPECT_NEAR(n.z, expected.z, 1e-3f);
}

TEST(BumpMapping, TheHitTakesTheBSDFsShadingFrame) {
    // The integrators weigh every sample by |wi . si.shading.n|: after GetBSDF that must be the
    // BSDF's own normal, or a bumped surface's cosines (and so its brightness) are those of the
    // unperturbed one (the crown's bumped coated gold: gains of 24 in one bounce).
    constexpr Float k = 0.25f;
    Material m = RampBumpedMaterial(k);
    SurfaceInteraction si = PlaneHit(Point2f(0.5f, 0.5f));
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    BSDF bsdf = m.GetBSDF(si, lambda);
    Vector3f ns = ShadingNormal(bsdf);
    EXPECT_NEAR(Dot(Vector3f(si.shading.n), ns), 1, 1e-5f);
    EXPECT_NEAR(Dot(Normalize(si.shading.dpdu), bsdf.LocalToRender(Vector3f(1, 0, 0))), 1, 1e-5f);
    EXPECT_NEAR(Dot(si.shading.dpdu, ns), 0, 1e-5f);
    EXPECT_NEAR(Dot(si.shading.dpdv, ns), 0, 1e-5f);
    EXPECT_GT(Dot(Vector3f(si.shading.n), Vector3f(si.n)), 0);
}

TEST(NormalMapping, ANormalAlongDpduStillLeavesTheHitFiniteTangents) {
    // rgb (1, 0.5, 0.5) is dpdu's own direction: no part of dpdu is left to be a tangent.
    auto image = std::make_shared<Image>(Point2i(1, 1));
    image->SetChannel(Point2i(0, 0), 0, 1);
    image->SetChannel(Point2i(0, 0), 1, 0.5f);
    image->SetChannel(Point2i(0, 0), 2, 0.5f);
    Material m = DiffuseMaterial{};
    m.SetNormalMap(image);
    SurfaceInteraction si = PlaneHit(Point2f(0.4f, 0.6f));
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    m.GetBSDF(si, lambda);
    for (Vector3f t : {si.shading.dpdu, si.shading.dpdv}) {
        ASSERT_TRUE(IsFinite(t.x) && IsFinite(t.y) && IsFinite(t.z));
        EXPECT_NEAR(Length(t), 1, 1e-5f);
        EXPECT_NEAR(Dot(t, Vector3f(si.shading.n)), 0, 1e-5f);
    }
}

TEST(NormalMapping, TheHitTakesTheBSDFsShadingFrame) {
    auto image = std::make_shared<Image>(Point2i(1, 1));
    for (int c = 0; c < 3; ++c)
        image->SetChannel(Point2i(0, 0), c, c == 2 ? 0.8f : 0.7f);
    Material m = DiffuseMaterial{};
    m.SetNormalMap(image);
    SurfaceInteraction si = PlaneHit(Point2f(0.4f, 0.6f));
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    BSDF bsdf = m.GetBSDF(si, lambda);
    Vector3f ns = ShadingNormal(bsdf);
    EXPECT_LT(ns.z, 0.95f);  // the map turns it
    EXPECT_NEAR(Dot(Vector3f(si.shading.n), ns), 1, 1e-5f);
    EXPECT_NEAR(Dot(si.shading.dpdu, ns), 0, 1e-5f);
    EXPECT_NEAR(Dot(si.shading.dpdv, ns), 0, 1e-5f);
}

TEST(BumpMapping, ConstantDisplacementLeavesTheFrame) {
    Material m = DiffuseMaterial{};
    m.SetDisplacement(FloatTexture(0.3f));
    Vector3f n = ShadingNormal(GetBSDF(m, PlaneHit(Point2f(0.2f, 0.7f))));
    EXPECT_NEAR(n.z, 1, 1e-6f);
}

TEST(NormalMapping, TangentSpaceColorSetsTheNormal) {
    // rgb (0.5, 0.5, 1) is the unperturbed normal; (1, 0.5, 0.5) points along dpdu.
    auto map = [](Float r, Float g, Float b) {
        auto image = std::make_shared<Image>(Point2i(1, 1));
        image->SetChannel(Point2i(0, 0), 0, r);
        image->SetChannel(Point2i(0, 0), 1, g);
        image->SetChannel(Point2i(0, 0), 2, b);
        Material m = DiffuseMaterial{};
        m.SetNormalMap(image);
        return ShadingNormal(GetBSDF(m, PlaneHit(Point2f(0.4f, 0.6f))));
    };
    Vector3f flat = map(0.5f, 0.5f, 1), along = map(1, 0.5f, 0.5f);
    EXPECT_NEAR(flat.z, 1, 1e-5f);
    EXPECT_NEAR(along.x, 1, 1e-5f);
    EXPECT_NEAR(along.z, 0, 1e-5f);
}

TEST(MixMaterial, ChoiceIsDeterministicPerHitAndFollowsAmount) {
    MixMaterial mix{{3, 7}, FloatTexture(0.3f)};
    SurfaceInteraction si = PlaneHit(Point2f(0.1f, 0.2f));
    EXPECT_EQ(mix.Choose(si), mix.Choose(si));
    int second = 0, n = 20000;
    for (int i = 0; i < n; ++i) {
        si.p = Point3f(i * 0.001f, 0.5f, 0);
        second += mix.Choose(si) == 7;
    }
    // Binomial(20000, 0.3): standard deviation 0.0032 in the fraction; 5 of them.
    EXPECT_NEAR(second / double(n), 0.3, 0.016);
    EXPECT_EQ((MixMaterial{{3, 7}, FloatTexture(0.f)}.Choose(si)), 3);
    EXPECT_EQ((MixMaterial{{3, 7}, FloatTexture(1.f)}.Choose(si)), 7);
}

TEST(BumpMapping, TheNormalsTurningScalesTheDisplacedTangent) {
    // pbrt-v4's dp/du gains d * dn/du. On a cylinder of radius r around y (dn/du = dp/du / r),
    // RampBumpedMaterial's ramp, d = k/2 at its middle, makes dp/du
    // (1 + d/r, 0, 2k): the normal tilts less than on the plane.
    constexpr Float k = 0.25f, r = 0.5f;
    Material m = RampBumpedMaterial(k);
    SurfaceInteraction si = PlaneHit(Point2f(0.5f, 0.5f));
    si.shading.dndu = Normal3f(1 / r, 0, 0);
    Vector3f n = ShadingNormal(GetBSDF(m, si));
    Vector3f expected = Normalize(Vector3f(-2 * k, 0, 1 + k / 2 / r));
    EXPECT_NEAR(n.x, expected.x, 1e-3f);
    EXPECT_NEAR(n.z, expected.z, 1e-3f);
}
