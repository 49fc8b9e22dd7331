// Point lights whose intensity an image modulates (pbrt-v4's GoniometricLight and
// ProjectionLight): delta lights at the light-space origin, found only by light sampling.
#pragma once

#include "pbrt_ext/images/image.h"
#include "pbrt_ext/interaction.h"
#include "pbrt_ext/lights/lightbounds.h"
#include "pbrt_ext/lights/lightsample.h"
#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/transform.h"

#include <string>

namespace pbrt {

class RGBColorSpace;

// Intensity scale * I * image(w): the image is a goniometric diagram over the sphere of
// directions, in the equal-area octahedral parameterization (square), read at the nearest texel;
// its channels' average is the relative intensity. worldFromLight includes pbrt-v4's exchange of
// y and z, so the diagram's pole is light-space +y.
class GoniometricLight {
  public:
    GoniometricLight(const Transform &worldFromLight, Spectrum I, Float scale, Image image);

    LightType Type() const { return LightType::DeltaPosition; }
    SampledSpectrum Phi(const SampledWavelengths &lambda) const;
    pstd::optional<LightLiSample> SampleLi(LightSampleContext ctx, Point2f u,
                                           const SampledWavelengths &lambda,
                                           bool allowIncompletePDF = false) const;
    Float PDF_Li(LightSampleContext, Vector3f, bool = false) const { return 0; }
    pstd::optional<LightLeSample> SampleLe(Point2f u1, Point2f u2, const SampledWavelengths &lambda,
                                           Float time) const;
    LightLePDF PDF_Le(const Ray &ray) const;
    pstd::optional<LightBounds> Bounds() const;
    std::string ToString() const;

    // Intensity toward the light-space direction w (unit).
    SampledSpectrum I(Vector3f w, const SampledWavelengths &lambda) const;
    // The image's mean relative intensity: Phi is 4 pi times it.
    Float MeanIntensity() const { return meanIntensity; }
    // For "power", which pbrt-v4 derives from the light's own integrals.
    void MultiplyScale(Float factor) { scale *= factor; }

  private:
    Transform worldFromLight;
    Spectrum Iemit;
    Float scale;
    Image image;
    Float meanIntensity;
};

// A slide projector: the image (RGB illuminant spectra of its colour space) on the plane z = 1
// of light space, spanning fov degrees across its shorter side, scale times its texels'
// radiant intensity. Nothing behind the projector's near plane or outside the image.
// worldFromLight includes pbrt-v4's flip of y, so the image's top row is light-space +y.
class ProjectionLight {
  public:
    ProjectionLight(const Transform &worldFromLight, Image image, const RGBColorSpace *colorSpace,
                    Float scale, Float fov);

    LightType Type() const { return LightType::DeltaPosition; }
    SampledSpectrum Phi(const SampledWavelengths &lambda) const;
    pstd::optional<LightLiSample> SampleLi(LightSampleContext ctx, Point2f u,
                                           const SampledWavelengths &lambda,
                                           bool allowIncompletePDF = false) const;
    Float PDF_Li(LightSampleContext, Vector3f, bool = false) const { return 0; }
    pstd::optional<LightLeSample> SampleLe(Point2f u1, Point2f u2, const SampledWavelengths &lambda,
                                           Float time) const;
    LightLePDF PDF_Le(const Ray &ray) const;
    pstd::optional<LightBounds> Bounds() const;
    std::string ToString() const;

    SampledSpectrum I(Vector3f w, const SampledWavelengths &lambda) const;
    void MultiplyScale(Float factor) { scale *= factor; }
    // The solid-angle weighted mean of f over the image's texels: sum f(texel) dw/dA, times the
    // image plane's area over the texel count (pbrt-v4's Phi and "power" integrals).
    template <typename F>
    auto IntegrateOverSolidAngle(F f) const;

  private:
    static constexpr Float hither = 1e-3f;
    Transform worldFromLight;
    Image image;
    const RGBColorSpace *colorSpace;
    Float scale;
    Bounds2f screenBounds;
    Transform screenFromLight;
    Float tanHalfFov;
    Float A;  // the image's area on the plane z = 1
};

template <typename F>
auto ProjectionLight::IntegrateOverSolidAngle(F f) const {
    Point2i res = image.Resolution();
    decltype(f(RGB())) sum(0.f);
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x) {
            Point2f ps = screenBounds.Lerp(Point2f((x + 0.5f) / res.x, (y + 0.5f) / res.y));
            Vector3f w = Normalize(Vector3f(ps.x * tanHalfFov, ps.y * tanHalfFov, 1));
            sum += f(ClampZero(image.GetChannels(Point2i(x, y)))) * Pow<3>(w.z);
        }
    return sum * (A / Float(res.x * res.y));
}

}  // namespace pbrt
