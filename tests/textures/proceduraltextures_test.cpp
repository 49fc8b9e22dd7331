// Procedural textures and texture mappings against pbrt-v4's own values: the noise is pbrt-v4's,
// so FBm, turbulence, windy, marble, the polka dots and the checkerboards agree at fixed points to
// float rounding. The values were printed by pbrt-v4 (commit 5f7a6068, built from source) with a
// small program linked against its libpbrt_lib.a, calling the same functions at the same points.
#include "pbrt_ext/textures/textures.h"

#include "pbrt_ext/util/noise.h"

#include <gtest/gtest.h>

#include <string>

namespace pbrt {
namespace {

const SampledWavelengths kLambda = SampledWavelengths::SampleUniform(0, 400, 800);  // 400..700 nm

// At p with footprint (dpdx, dpdy): FBm(omega 0.5, 8 octaves), Turbulence(omega 0.6, 7 octaves),
// windy, marble (8 octaves, roughness 0.5, scale 2, variation 0.3) at 400, 500, 600, 700 nm, and
// the 3D checkerboard's weight of tex2; all with texture space = world space.
struct NoiseReference {
    Point3f p;
    Vector3f dpdx, dpdy;
    Float fbm, turbulence, windy;
    Float marble[4];
    Float checkerboard3D;
};
const NoiseReference kNoise[] = {
    {{0.300000012f, 1.70000005f, -2.20000005f}, {0.00999999978f, 0, 0}, {0, 0.0199999996f, 0.00499999989f},
     -0.577982545f, 0.839601219f, -0.056662593f, {0.832459807f, 0.825196207f, 0.82690382f, 0.837273657f}, 0},
    {{10.25f, -3.5f, 7.75f}, {0.200000003f, 0.100000001f, 0}, {0, 0.0500000007f, 0.300000012f},
     0.334387302f, 0.820390522f, 0.0680470243f, {0.918169737f, 0.880295098f, 0.86846137f, 0.894185543f}, 0.890089273f},
    {{-1.10000002f, 0.449999988f, 3.29999995f}, {0.00310000009f, 0.00200000009f, 0}, {0.00100000005f, 0, 0.00270000007f},
     0.404307902f, 0.523371041f, 0.223729983f, {0.801883578f, 0.679868698f, 0.643457353f, 0.723347068f}, 1},
    {{5.5f, 2.25f, -0.75f}, {0, 0, 0}, {0, 0, 0},
     0.0316926837f, 0.281517178f, 0.00156214845f, {0.918474078f, 0.880551696f, 0.868689477f, 0.894476771f}, 0},
};

TextureEvalContext At(Point3f p, Vector3f dpdx, Vector3f dpdy) {
    TextureEvalContext ctx;
    ctx.p = p;
    ctx.dpdx = dpdx;
    ctx.dpdy = dpdy;
    ctx.n = Normal3f(0, 0, 1);
    return ctx;
}

TEST(ProceduralTextures, NoiseTexturesMatchPbrtV4) {
    TextureMapping3D identity;
    for (const NoiseReference &r : kNoise) {
        TextureEvalContext ctx = At(r.p, r.dpdx, r.dpdy);
        EXPECT_NEAR(FBm(r.p, r.dpdx, r.dpdy, 0.5f, 8), r.fbm, 1e-5f);
        EXPECT_NEAR(Turbulence(r.p, r.dpdx, r.dpdy, 0.6f, 7), r.turbulence, 1e-5f);
        EXPECT_NEAR(FBmTexture({identity, 8, 0.5f}).Evaluate(ctx), r.fbm, 1e-5f);
        EXPECT_NEAR(WrinkledTexture({identity, 7, 0.6f}).Evaluate(ctx), r.turbulence, 1e-5f);
        EXPECT_NEAR(WindyTexture{identity}.Evaluate(ctx), r.windy, 1e-5f);
        SampledSpectrum marble = MarbleTexture{identity, 8, 0.5f, 2, 0.3f}.Evaluate(ctx, kLambda);
        // Marble's colour becomes a spectrum through the sRGB RGB-to-spectrum table, and ours is
        // made by our own optimizer (rgbtospectrum_test): the two tables' spectra differ by up to
        // 1.5e-4 here (measured), which is what this tolerance allows; the noise itself is
        // checked to 1e-5 above.
        for (int i = 0; i < 4; ++i) EXPECT_NEAR(marble[i], r.marble[i], 3e-4f) << "at " << kLambda[i] << " nm";
        EXPECT_NEAR(Checkerboard(identity, ctx), r.checkerboard3D, 1e-5f);
    }
}

// InsidePolkaDot on a 16x16 grid over [-2, 2)^2 (offset by (0.01, 0.02)), rows of t.
const char *const kDots[16] = {
    "1100000000011101", "1000000000001001", "0000000000000000", "0001110000011000",
    "0001110000011101", "0000100000001001", "0000000000000000", "0000000000000000",
    "0000000000000000", "0000000000000000", "0000000000000000", "0000000111000000",
    "0000000111000000", "0000000010000000", "0000000000000000", "0001100111001100"};

TEST(ProceduralTextures, PolkaDotsMatchPbrtV4) {
    FloatTexture dots = FloatDotsTexture(UVMapping{}, FloatTexture(0), FloatTexture(1));
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) {
            Point2f st(-2 + 0.25f * i + 0.01f, -2 + 0.25f * j + 0.02f);
            EXPECT_EQ(InsidePolkaDot(st), kDots[j][i] == '1') << st.x << " " << st.y;
            TextureEvalContext ctx;
            ctx.uv = st;
            EXPECT_EQ(dots.Evaluate(ctx), kDots[j][i] == '1' ? 1 : 0);
        }
}

// The 2D checkerboard through uv (2, 3, 0.1, -0.2) with a footprint: uv, dudx, dudy, dvdx and
// dvdy = dudx / 2, and pbrt-v4's weight of tex2.
TEST(ProceduralTextures, FilteredCheckerboardMatchesPbrtV4) {
    struct Case {
        Float u, v, dudx, dudy, dvdx, weight;
    } cases[] = {{0.300000012f, 0.699999988f, 0.0500000007f, 0.0199999996f, 0.00999999978f, 0.993829012f},
                 {1.21000004f, -0.400000006f, 0.300000012f, 0.100000001f, 0.200000003f, 0.324779779f},
                 {-2.5f, 3.29999995f, 0, 0, 0, 0},
                 {0.769999981f, 0.119999997f, 0.600000024f, 0.400000006f, 0.899999976f, 0.500000954f}};
    TextureMapping2D mapping = UVMapping{2, 3, 0.1f, -0.2f};
    for (const Case &c : cases) {
        TextureEvalContext ctx;
        ctx.uv = Point2f(c.u, c.v);
        ctx.dudx = c.dudx;
        ctx.dudy = c.dudy;
        ctx.dvdx = c.dvdx;
        ctx.dvdy = c.dudx * 0.5f;
        EXPECT_NEAR(Checkerboard(mapping, ctx), c.weight, 1e-5f) << c.u << " " << c.v;
    }
}

// Texture space = Translate(0.5, -1, 2) RotateY(30) Scale(2, 1, 1.5). At each point (the footprints
// of kNoise): the spherical (s, t), the cylindrical (s, t) and derivatives, the planar mapping's
// (v1 = (1, 0.5, 0), v2 = (0, 0.25, 1), udelta 0.1, vdelta -0.2) (s, t) and derivatives.
TEST(TextureMappings, MatchPbrtV4) {
    struct Expected {
        Float sph[2], cyl[6], planar[6];
    } expected[] = {
        {{0.727747977f, 0.195452482f},
         {0.695452511f, -2.49153781f, -0.000226418168f, 0.000438510324f, 0.00333333341f, 0.0028867512f},
         {2.41339731f, -2.0165379f, 0.00433012703f, 0.00875000004f, 0.00333333341f, 0.00788675062f}},
        {{0.164806023f, 0.883556485f},
         {0.383556545f, 6.56976414f, 0.00562552409f, -0.000548764772f, 0.0666666701f, 0.173205078f},
         {1.63437378f, 5.74476433f, 0.136602536f, -0.0500000045f, 0.0916666687f, 0.185705081f}},
        {{0.461164117f, 0.347407609f},
         {0.847407579f, 0.217221856f, -0.00020193361f, 1.77936199e-05f, 0.00103333336f, 0.00189217913f},
         {-0.19282034f, 0.37972188f, 0.00234233961f, -0.000241987291f, 0.00153333344f, 0.00189217913f}},
        {{0.494188905f, 0.135350525f},
         {0.635350525f, 0.0789533854f, 0, 0, 0, 0},
         {4.57756329f, 0.691453397f, 0, 0, 0, 0}},
    };
    Transform worldFromTexture = Translate(Vector3f(0.5f, -1, 2)) * RotateY(30) * Scale(2, 1, 1.5f);
    SphericalMapping spherical{worldFromTexture};
    CylindricalMapping cylindrical{worldFromTexture};
    PlanarMapping planar{worldFromTexture, Vector3f(1, 0.5f, 0), Vector3f(0, 0.25f, 1), 0.1f, -0.2f};
    auto expectCoords = [](TexCoord2D c, const Float *e, const std::string &what) {
        Float got[6] = {c.st[0], c.st[1], c.dsdx, c.dsdy, c.dtdx, c.dtdy};
        for (int i = 0; i < 6; ++i) EXPECT_NEAR(got[i], e[i], 2e-5f * std::max<Float>(1, std::abs(e[i]))) << what << " " << i;
    };
    for (size_t k = 0; k < std::size(expected); ++k) {
        TextureEvalContext ctx = At(kNoise[k].p, kNoise[k].dpdx, kNoise[k].dpdy);
        TexCoord2D s = spherical.Map(ctx);
        EXPECT_NEAR(s.st[0], expected[k].sph[0], 1e-5f);
        EXPECT_NEAR(s.st[1], expected[k].sph[1], 1e-5f);
        expectCoords(cylindrical.Map(ctx), expected[k].cyl, "cylindrical");
        expectCoords(planar.Map(ctx), expected[k].planar, "planar");
    }
}

// The spherical mapping's derivatives are each coordinate's own: against central differences of
// the mapping along the footprint (pbrt-v4 swaps s's and t's).
TEST(TextureMappings, SphericalDerivativesAreThoseOfItsCoordinates) {
    SphericalMapping spherical{Translate(Vector3f(0.5f, -1, 2))};
    for (const NoiseReference &r : kNoise) {
        if (LengthSquared(r.dpdx) == 0) continue;
        TexCoord2D c = spherical.Map(At(r.p, r.dpdx, r.dpdy));
        Float h = 1e-2f;
        TexCoord2D plus = spherical.Map(At(r.p + h * r.dpdx, {}, {}));
        TexCoord2D minus = spherical.Map(At(r.p - h * r.dpdx, {}, {}));
        EXPECT_NEAR(c.dsdx, (plus.st[0] - minus.st[0]) / (2 * h), 1e-3f * std::abs(c.dsdx) + 1e-5f);
        EXPECT_NEAR(c.dtdx, (plus.st[1] - minus.st[1]) / (2 * h), 1e-3f * std::abs(c.dtdx) + 1e-5f);
    }
}

// Bilerp and directionmix are pbrt-v4's formulas.
TEST(ProceduralTextures, BilerpAndDirectionMix) {
    FloatBilerpTexture bilerp{UVMapping{}, 1, 2, 3, 4};  // v00, v01, v10, v11
    TextureEvalContext ctx;
    ctx.uv = Point2f(0.25f, 0.5f);
    EXPECT_NEAR(bilerp.Evaluate(ctx), 0.75f * 0.5f * 1 + 0.25f * 0.5f * 3 + 0.75f * 0.5f * 2 + 0.25f * 0.5f * 4, 1e-6f);
    FloatTexture mix = FloatDirectionMixTexture(FloatTexture(10), FloatTexture(2), Normalize(Vector3f(0, 1, 1)));
    ctx.n = Normal3f(0, 0, -1);  // |n . dir| = 1/sqrt(2), whichever side faces it
    EXPECT_NEAR(mix.Evaluate(ctx), 10 / std::sqrt(2.f) + 2 * (1 - 1 / std::sqrt(2.f)), 1e-5f);
}

}  // namespace
}  // namespace pbrt
