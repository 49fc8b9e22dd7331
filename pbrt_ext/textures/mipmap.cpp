#include "pbrt_ext/textures/mipmap.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace pbrt {

std::optional<FilterFunction> ParseFilterFunction(const std::string &name) {
    if (name == "point") return FilterFunction::Point;
    if (name == "bilinear") return FilterFunction::Bilinear;
    if (name == "trilinear") return FilterFunction::Trilinear;
    if (name == "ewa" || name == "EWA") return FilterFunction::EWA;
    return {};
}

MIPMap::MIPMap(Image image, WrapMode wrapMode, MIPMapFilterOptions options)
    : pyramid(Image::GeneratePyramid(std::move(image), wrapMode)), wrapMode(wrapMode),
      options(options) {
    if (options.averageOnly) pyramid.erase(pyramid.begin(), pyramid.end() - 1);
}

namespace {

// The truncated Gaussian that weighs texels at squared ellipse radius r2 < 1.
Float EWAWeight(Float r2) {
    constexpr Float alpha = 2;
    return std::exp(-alpha * r2) - std::exp(-alpha);
}

}  // namespace

RGB MIPMap::Filter(Point2f st, Vector2f dst0, Vector2f dst1) const {
    if (options.filter != FilterFunction::EWA) {
        // The level at which the footprint's widest extent spans about one texel.
        Float width = 2 * std::max({std::abs(dst0[0]), std::abs(dst0[1]), std::abs(dst1[0]),
                                    std::abs(dst1[1])});
        Float level = Levels() - 1 + std::log2(std::max<Float>(width, 1e-8f));
        if (level >= Levels() - 1) return Texel(Levels() - 1, Point2i(0, 0));
        int iLevel = std::max(0, int(std::floor(level)));
        switch (options.filter) {
        case FilterFunction::Point: {
            Point2i res = LevelResolution(iLevel);
            return Texel(iLevel, Point2i(int(std::round(st[0] * res.x - 0.5f)),
                                         int(std::round(st[1] * res.y - 0.5f))));
        }
        case FilterFunction::Bilinear:
            return Bilerp(iLevel, st);
        default:  // trilinear; below level 0 the finest level alone
            if (level <= 0) return Bilerp(0, st);
            Float delta = level - Float(iLevel);
            return (1 - delta) * Bilerp(iLevel, st) + delta * Bilerp(iLevel + 1, st);
        }
    }
    // EWA: dst0 becomes the major axis, dst1 the minor one, lengthened to maxAnisotropy.
    if (LengthSquared(dst0) < LengthSquared(dst1)) std::swap(dst0, dst1);
    Float major = Length(dst0), minor = Length(dst1);
    if (minor * options.maxAnisotropy < major && minor > 0) {
        Float scale = major / (minor * options.maxAnisotropy);
        dst1 *= scale;
        minor *= scale;
    }
    if (minor == 0) return Bilerp(0, st);
    // The minor axis decides the level, so that the ellipse covers a few texels across.
    Float lod = std::max<Float>(0, Levels() - 1 + std::log2(minor));
    int ilod = int(std::floor(lod));
    Float delta = lod - Float(ilod);
    RGB fine = EWA(ilod, st, dst0, dst1);
    if (delta == 0) return fine;
    return (1 - delta) * fine + delta * EWA(ilod + 1, st, dst0, dst1);
}

RGB MIPMap::EWA(int level, Point2f st, Vector2f dst0, Vector2f dst1) const {
    if (level >= Levels()) return Texel(Levels() - 1, Point2i(0, 0));
    // To the level's texel coordinates, texel centers at integers.
    Point2i res = LevelResolution(level);
    st = Point2f(st[0] * res.x - 0.5f, st[1] * res.y - 0.5f);
    dst0 = Vector2f(dst0[0] * res.x, dst0[1] * res.y);
    dst1 = Vector2f(dst1[0] * res.x, dst1[1] * res.y);
    // The implicit ellipse A s^2 + B s t + C t^2 < 1 spanned by the axes, widened by a texel so
    // that it always holds one.
    Float A = Sqr(dst0[1]) + Sqr(dst1[1]) + 1;
    Float B = -2 * (dst0[0] * dst0[1] + dst1[0] * dst1[1]);
    Float C = Sqr(dst0[0]) + Sqr(dst1[0]) + 1;
    Float invF = 1 / (A * C - Sqr(B) * 0.25f);
    A *= invF;
    B *= invF;
    C *= invF;
    // Its bounding box.
    Float det = -Sqr(B) + 4 * A * C, invDet = 1 / det;
    Float uSqrt = SafeSqrt(det * C), vSqrt = SafeSqrt(A * det);
    int s0 = int(std::ceil(st[0] - 2 * invDet * uSqrt)), s1 = int(std::floor(st[0] + 2 * invDet * uSqrt));
    int t0 = int(std::ceil(st[1] - 2 * invDet * vSqrt)), t1 = int(std::floor(st[1] + 2 * invDet * vSqrt));
    RGB sum;
    Float sumWeights = 0;
    for (int it = t0; it <= t1; ++it) {
        Float tt = Float(it) - st[1];
        for (int is = s0; is <= s1; ++is) {
            Float ss = Float(is) - st[0];
            Float r2 = A * Sqr(ss) + B * ss * tt + C * Sqr(tt);
            if (r2 >= 1) continue;
            Float w = EWAWeight(r2);
            sum += w * Texel(level, Point2i(is, it));
            sumWeights += w;
        }
    }
    return sum / sumWeights;
}

}  // namespace pbrt
