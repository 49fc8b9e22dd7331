#include "pbrt_ext/textures/texturemappings.h"

#include <cmath>

namespace pbrt {

namespace {

// The footprint's two sides in texture space.
struct Footprint {
    Vector3f dpdx, dpdy;
};

Footprint InTextureSpace(const Transform &worldFromTexture, const TextureEvalContext &ctx) {
    return Footprint{worldFromTexture.ApplyInverse(ctx.dpdx), worldFromTexture.ApplyInverse(ctx.dpdy)};
}

// The coordinates and their derivatives along x and y, given each coordinate's gradient.
TexCoord2D WithDerivatives(Point2f st, Vector3f dsdp, Vector3f dtdp, const Footprint &f) {
    return TexCoord2D{st, Dot(dsdp, f.dpdx), Dot(dsdp, f.dpdy), Dot(dtdp, f.dpdx), Dot(dtdp, f.dpdy)};
}

// d(phi)/dp / 2pi: tangent to the circle about z, zero on the axis where phi has no gradient.
Vector3f AzimuthGradientOver2Pi(Point3f p) {
    Float x2y2 = Sqr(p.x) + Sqr(p.y);
    if (x2y2 == 0) return Vector3f(0, 0, 0);
    return Vector3f(-p.y, p.x, 0) / (2 * Pi * x2y2);
}

}  // namespace

TexCoord2D SphericalMapping::Map(const TextureEvalContext &ctx) const {
    Point3f p = worldFromTexture.ApplyInverse(ctx.p);
    Vector3f dir = Normalize(p - Point3f(0, 0, 0));
    Point2f st(SphericalTheta(dir) * InvPi, SphericalPhi(dir) * Inv2Pi);
    // d(theta)/dp / pi, theta = acos(z / |p|).
    Float x2y2 = Sqr(p.x) + Sqr(p.y), r = std::sqrt(x2y2), r2 = x2y2 + Sqr(p.z);
    Vector3f dthetadp = r > 0 ? Vector3f(p.x * p.z / r, p.y * p.z / r, -r) / (Pi * r2) : Vector3f(0, 0, 0);
    return WithDerivatives(st, dthetadp, AzimuthGradientOver2Pi(p), InTextureSpace(worldFromTexture, ctx));
}

TexCoord2D CylindricalMapping::Map(const TextureEvalContext &ctx) const {
    Point3f p = worldFromTexture.ApplyInverse(ctx.p);
    Point2f st((Pi + std::atan2(p.y, p.x)) * Inv2Pi, p.z);
    return WithDerivatives(st, AzimuthGradientOver2Pi(p), Vector3f(0, 0, 1),
                           InTextureSpace(worldFromTexture, ctx));
}

TexCoord2D PlanarMapping::Map(const TextureEvalContext &ctx) const {
    Vector3f v = worldFromTexture.ApplyInverse(ctx.p) - Point3f(0, 0, 0);
    Point2f st(ds + Dot(v, vs), dt + Dot(v, vt));
    return WithDerivatives(st, vs, vt, InTextureSpace(worldFromTexture, ctx));
}

}  // namespace pbrt
