#include "pbrt_ext/lights/imagepointlights.h"

#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/equalarea.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pbrt {

namespace {

std::string Format(Point3f p) { return fmt::format("[ {}, {}, {} ]", p.x, p.y, p.z); }

}  // namespace

// ---- GoniometricLight -----------------------------------------------------------------------

GoniometricLight::GoniometricLight(const Transform &worldFromLight, Spectrum I, Float scale, Image image)
    : worldFromLight(worldFromLight), Iemit(TabulatedForLookup(I)), scale(scale), image(std::move(image)) {
    Point2i res = this->image.Resolution();
    double sum = 0;
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x) sum += this->image.GetChannels(Point2i(x, y)).Average();
    meanIntensity = Float(sum / (double(res.x) * res.y));
}

SampledSpectrum GoniometricLight::I(Vector3f w, const SampledWavelengths &lambda) const {
    Point2f uv = EqualAreaSphereToSquare(w);
    return scale * Iemit.Sample(lambda) * image.LookupNearest(uv).Average();
}

SampledSpectrum GoniometricLight::Phi(const SampledWavelengths &lambda) const {
    return scale * Iemit.Sample(lambda) * 4 * Pi * meanIntensity;
}

pstd::optional<LightLiSample> GoniometricLight::SampleLi(LightSampleContext ctx, Point2f,
                                                         const SampledWavelengths &lambda, bool) const {
    return PointLightSample(worldFromLight, ctx, [&](Vector3f w) { return I(w, lambda); });
}

// Bounded as an isotropic point light of the same power, as pbrt-v4 does.
pstd::optional<LightBounds> GoniometricLight::Bounds() const {
    Point3f p = worldFromLight(Point3f(0, 0, 0));
    Float phi = scale * Iemit.MaxValue() * 4 * Pi * meanIntensity;
    return LightBounds(Bounds3f(p, p), Vector3f(0, 0, 1), phi, -1, 0, false);
}

std::string GoniometricLight::ToString() const {
    return fmt::format("[ GoniometricLight p: {} I: {} scale: {} image: {}x{} ]",
                       Format(worldFromLight(Point3f(0, 0, 0))), Iemit.ToString(), scale,
                       image.Resolution().x, image.Resolution().y);
}

// ---- ProjectionLight ------------------------------------------------------------------------

ProjectionLight::ProjectionLight(const Transform &worldFromLight, Image image,
                                 const RGBColorSpace *colorSpace, Float scale, Float fov)
    : worldFromLight(worldFromLight), image(std::move(image)), colorSpace(colorSpace), scale(scale),
      screenFromLight(Perspective(fov, hither, 1e30f)), tanHalfFov(std::tan(Radians(fov) / 2)) {
    // The image's shorter side spans [-1, 1] of the screen.
    Float aspect = Float(this->image.Resolution().x) / Float(this->image.Resolution().y);
    screenBounds = aspect > 1 ? Bounds2f(Point2f(-aspect, -1), Point2f(aspect, 1))
                              : Bounds2f(Point2f(-1, -1 / aspect), Point2f(1, 1 / aspect));
    A = 4 * Sqr(tanHalfFov) * (aspect > 1 ? aspect : 1 / aspect);
}

SampledSpectrum ProjectionLight::I(Vector3f w, const SampledWavelengths &lambda) const {
    if (w.z < hither) return SampledSpectrum(0.f);
    Point3f ps = screenFromLight(Point3f(w.x, w.y, w.z));
    if (!Inside(Point2f(ps.x, ps.y), screenBounds)) return SampledSpectrum(0.f);
    Vector2f uv = screenBounds.Offset(Point2f(ps.x, ps.y));
    RGB rgb = ClampZero(image.LookupNearest(Point2f(uv.x, uv.y)));
    return scale * RGBIlluminantSpectrum(*colorSpace, rgb).Sample(lambda);
}

SampledSpectrum ProjectionLight::Phi(const SampledWavelengths &lambda) const {
    return scale * IntegrateOverSolidAngle([&](RGB rgb) {
               return RGBIlluminantSpectrum(*colorSpace, rgb).Sample(lambda);
           });
}

pstd::optional<LightLiSample> ProjectionLight::SampleLi(LightSampleContext ctx, Point2f,
                                                        const SampledWavelengths &lambda, bool) const {
    return PointLightSample(worldFromLight, ctx, [&](Vector3f w) { return I(w, lambda); });
}

// pbrt-v4's bounds: the axis, the cone through the image's corner, and as power the texels'
// mean largest channel.
pstd::optional<LightBounds> ProjectionLight::Bounds() const {
    Point2i res = image.Resolution();
    double sum = 0;
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x) sum += ClampZero(image.GetChannels(Point2i(x, y))).MaxComponentValue();
    Float phi = scale * Float(sum / (double(res.x) * res.y));
    Float cosTotalWidth = Normalize(Vector3f(screenBounds.pMax.x * tanHalfFov, screenBounds.pMax.y * tanHalfFov, 1)).z;
    Point3f p = worldFromLight(Point3f(0, 0, 0));
    Vector3f w = Normalize(worldFromLight(Vector3f(0, 0, 1)));
    return LightBounds(Bounds3f(p, p), w, phi, 1, cosTotalWidth, false);
}

std::string ProjectionLight::ToString() const {
    return fmt::format("[ ProjectionLight p: {} scale: {} A: {} image: {}x{} ]",
                       Format(worldFromLight(Point3f(0, 0, 0))), scale, A, image.Resolution().x,
                       image.Resolution().y);
}

}  // namespace pbrt
