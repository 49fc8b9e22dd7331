#include "pbrt_ext/lights/lightbounds.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pbrt {

namespace {

// cos and sin of max(0, a - b) from the sines and cosines of two angles in [0, pi].
Float CosSubClamped(Float sinA, Float cosA, Float sinB, Float cosB) {
    return cosA > cosB ? 1 : cosA * cosB + sinA * sinB;
}
Float SinSubClamped(Float sinA, Float cosA, Float sinB, Float cosB) {
    return cosA > cosB ? 0 : sinA * cosB - cosA * sinB;
}

}  // namespace

LightBounds::Constants::Constants(const LightBounds &lb)
    : centroid(lb.Centroid()), halfDiagonal(Length(lb.bounds.Diagonal()) / 2),
      sinTheta_o(SafeSqrt(1 - Sqr(lb.cosTheta_o))) {
    lb.bounds.BoundingSphere(&sphereCenter, &sphereRadius);
}

Float LightBounds::Importance(Point3f p, Normal3f n, const Constants &k) const {
    Point3f pc = k.centroid;
    // Clamped below by half the diagonal, so that points inside or near the bounds are not
    // given unbounded importance.
    Float d2 = std::max(DistanceSquared(p, pc), k.halfDiagonal);

    // The angle between the cone's axis and the direction from the bounds to p, less the
    // normals' spread and the angle the bounds subtend from p: the smallest emission angle.
    Vector3f wi = Normalize(p - pc);
    Float cosTheta_w = Dot(w, wi);
    if (twoSided)
        cosTheta_w = std::abs(cosTheta_w);
    Float sinTheta_w = SafeSqrt(1 - Sqr(cosTheta_w));
    // BoundSubtendedDirections(bounds, p).cosTheta, without the cone's axis.
    Float cosTheta_b = SubtendedCosTheta(k.sphereCenter, k.sphereRadius, p);
    Float sinTheta_b = SafeSqrt(1 - Sqr(cosTheta_b));
    Float cosTheta_x = CosSubClamped(sinTheta_w, cosTheta_w, k.sinTheta_o, cosTheta_o);
    Float sinTheta_x = SinSubClamped(sinTheta_w, cosTheta_w, k.sinTheta_o, cosTheta_o);
    Float cosThetap = CosSubClamped(sinTheta_x, cosTheta_x, sinTheta_b, cosTheta_b);
    if (cosThetap <= cosTheta_e)
        return 0;
    Float importance = phi * cosThetap / d2;

    // The smallest incident cosine at a surface point, either side (transmission counts).
    if (n != Normal3f(0, 0, 0)) {
        Float cosTheta_i = AbsDot(wi, Vector3f(n));
        Float sinTheta_i = SafeSqrt(1 - Sqr(cosTheta_i));
        importance *= CosSubClamped(sinTheta_i, cosTheta_i, sinTheta_b, cosTheta_b);
    }
    return std::max<Float>(importance, 0);
}

std::string LightBounds::ToString() const {
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "[ LightBounds phi: %g w: [ %g %g %g ] cosTheta_o: %g cosTheta_e: %g "
                  "twoSided: %d ]",
                  phi, w.x, w.y, w.z, cosTheta_o, cosTheta_e, int(twoSided));
    return buf;
}

LightBounds Union(const LightBounds &a, const LightBounds &b) {
    if (a.phi == 0)
        return b;
    if (b.phi == 0)
        return a;
    DirectionCone cone = Union(DirectionCone(a.w, a.cosTheta_o), DirectionCone(b.w, b.cosTheta_o));
    return LightBounds(Union(a.bounds, b.bounds), cone.w, a.phi + b.phi, cone.cosTheta,
                       std::min(a.cosTheta_e, b.cosTheta_e), a.twoSided || b.twoSided);
}

}  // namespace pbrt
