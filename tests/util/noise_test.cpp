// Perlin noise (pbrt_ext/util/noise.h) is pbrt-v4's function: the cloud medium and procedural
// textures depend on matching its values, not just its character.
#include "pbrt_ext/util/noise.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pbrt {
namespace {

// Noise and DNoise at these points, printed by pbrt-v4's own util/noise.cpp (commit 5f7a6068,
// built from source).
struct Reference {
    Float x, y, z, noise, dx, dy, dz;
};
constexpr Reference kPbrtV4[] = {
    {0.300000012f, 1.70000005f, -2.20000005f, -0.473802835f, 0.467920303f, 1.15296543f, 0.197926164f},
    {10.25f, -3.5f, 7.75f, 0.334387302f, -0.514277816f, 0.539422035f, -0.356510282f},
    {123.400002f, 56.7000008f, -89.0999985f, -0.370473117f, -0.341421366f, -0.584965944f, 0.273108482f},
    {-0.00999999978f, 0.49000001f, 0.50999999f, 0.133935601f, 0.21301806f, -0.925780118f, 0.152783096f},
    {1000000.f, 2.5f, -3.25f, -0.0258789062f, 0.f, -0.787862778f, 0.163361803f},
};

TEST(Noise, MatchesPbrtV4) {
    for (const Reference &r : kPbrtV4) {
        EXPECT_NEAR(Noise(r.x, r.y, r.z), r.noise, 1e-5f) << r.x << " " << r.y << " " << r.z;
        // A forward difference over 0.01 scales rounding in Noise by 100.
        Vector3f d = DNoise(Point3f(r.x, r.y, r.z));
        EXPECT_NEAR(d.x, r.dx, 2e-4f);
        EXPECT_NEAR(d.y, r.dy, 2e-4f);
        EXPECT_NEAR(d.z, r.dz, 2e-4f);
    }
}

TEST(Noise, IsZeroOnTheLatticeBoundedAndPeriodic) {
    for (int i = -3; i <= 3; ++i)
        EXPECT_EQ(Noise(Float(i), Float(2 * i), Float(-i)), 0);
    Float largest = 0;
    for (int i = 0; i < 10000; ++i) {
        Point3f p(0.0137f * i, 0.029f * i + 0.3f, -0.011f * i);
        Float n = Noise(p);
        largest = std::max(largest, std::abs(n));
        EXPECT_NEAR(Noise(p + Vector3f(256, -512, 256)), n, 2e-4f) << i;
    }
    EXPECT_LE(largest, 1);
    EXPECT_GT(largest, 0.3f);  // not a constant
}

}  // namespace
}  // namespace pbrt
