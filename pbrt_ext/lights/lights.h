// Lights (pbrt-v4's src/pbrt/lights.h, reduced: no time, no alpha-masked area lights). The
// goniometric and projection lights are in imagepointlights.h, the portal light in portallight.h.
//
// Conventions, as in pbrt-v4:
//   - Render space = world space; worldFromLight is pbrt-v4's renderFromLight.
//   - SampleLi returns the radiance arriving at ctx.p along -wi and its density per unit solid
//     angle; delta lights (point, spot, distant) report pdf 1 and PDF_Li 0, since no other
//     strategy can find them.
//   - pLight is the point a shadow ray goes to: the sampled surface point, the light's position,
//     or a point beyond the scene (2 sceneRadius away) for distant and infinite lights.
//   - allowIncompletePDF: the caller combines light sampling with BSDF sampling by MIS, so the
//     light may leave directions BSDF sampling covers well to that strategy (pbrt-v4): the uniform
//     infinite light then samples nothing, and the image light samples a compensated density.
//   - Phi() is the emitted power; distant and infinite lights need Preprocess(sceneBounds) first.
//   - Bounds() bounds where a light is, what it emits and in which directions, for the BVH light
//     sampler; distant and infinite lights have none (they reach everywhere).
//   - Values are never negative, NaN or infinite: images are clamped at zero.
//   - Emission is spectral: each light samples its spectrum at the path's wavelengths. Spectra
//     other than constants are tabulated at 1 nm when the light is made (pbrt-v4's
//     DenselySampledSpectrum), so a lookup is one table read; an image light's texels are RGB
//     illuminant spectra of the image's colour space.
// Host code: area lights hold shapes that point into host meshes, the image light owns its image.
#pragma once

#include "pbrt_ext/images/image.h"
#include "pbrt_ext/interaction.h"
#include "pbrt_ext/lights/imagepointlights.h"
#include "pbrt_ext/lights/lightbounds.h"
#include "pbrt_ext/lights/lightsample.h"
#include "pbrt_ext/lights/portallight.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/shapes/shapes.h"
#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/transform.h"
#include "pbrt_ext/util/vecmath.h"

#include <memory>
#include <string>
#include <variant>

namespace pbrt {

// Isotropic point source of intensity scale * I at the light-space origin.
class PointLight {
  public:
    PointLight(const Transform &worldFromLight, Spectrum I, Float scale);

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

  private:
    Point3f pLight;
    Spectrum I;
    Float scale;
};

// A point source shining down light-space +z: full intensity within falloffStart degrees of
// the axis, zero beyond totalWidth, a smoothstep in cos theta between. pbrt-v4's parameters:
// a scene's "coneangle" is totalWidth and "coneangle - conedeltaangle" is falloffStart.
class SpotLight {
  public:
    SpotLight(const Transform &worldFromLight, Spectrum I, Float scale, Float totalWidth,
              Float falloffStart);

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

  private:
    Transform worldFromLight;
    Spectrum Iemit;
    Float scale, cosFalloffStart, cosFalloffEnd;
};

// Parallel light of radiance scale * Lemit arriving from light-space +z (pbrt-v4: the
// direction from "from" toward "to" is the one the light travels; the parser builds the
// transform that sends +z to from - to).
class DistantLight {
  public:
    DistantLight(const Transform &worldFromLight, Spectrum Lemit, Float scale);

    LightType Type() const { return LightType::DeltaDirection; }
    void Preprocess(const Bounds3f &sceneBounds);
    SampledSpectrum Phi(const SampledWavelengths &lambda) const;
    UnboundedLightImportance Importance(bool) const { return {scale * Lemit.MaxValue(), wLight}; }
    pstd::optional<LightLiSample> SampleLi(LightSampleContext ctx, Point2f u,
                                           const SampledWavelengths &lambda,
                                           bool allowIncompletePDF = false) const;
    Float PDF_Li(LightSampleContext, Vector3f, bool = false) const { return 0; }
    pstd::optional<LightLeSample> SampleLe(Point2f u1, Point2f u2, const SampledWavelengths &lambda,
                                           Float time) const;
    LightLePDF PDF_Le(const Ray &ray) const;
    std::string ToString() const;

  private:
    Vector3f wLight;  // unit, toward the light
    Spectrum Lemit;
    Float scale;
    Point3f sceneCenter;
    Float sceneRadius = 0;
};

// Constant radiance scale * Lemit leaving the front of a shape (both sides if twoSided); the
// front is the side the shape's geometric normal n points to.
// What modulates an image area light's emission over its uv (pbrt-v4's "filename" on a diffuse
// area light): the image's RGB as illuminant spectra of its colour space, bilinear, t flipped
// so that t = 0 is the file's bottom row, clamped at the edges. Shared by the lights of every
// primitive of the shape.
struct EmissionImage {
    EmissionImage(Image image, const RGBColorSpace *colorSpace);
    RGB Lookup(Point2f uv) const;

    Image image;
    const RGBColorSpace *colorSpace;
    Float meanChannel;    // over all texels and channels: the lights' bounds use it
    Float meanLuminance;  // of the texels' RGB: "power" divides by it
};

class DiffuseAreaLight {
  public:
    // Emits scale * Lemit, or scale times the image's spectrum at the point's uv where there is one.
    DiffuseAreaLight(Shape shape, Spectrum Lemit, Float scale, bool twoSided,
                     std::shared_ptr<const EmissionImage> image = nullptr);

    LightType Type() const { return LightType::Area; }
    SampledSpectrum Phi(const SampledWavelengths &lambda) const;
    pstd::optional<LightLiSample> SampleLi(LightSampleContext ctx, Point2f u,
                                           const SampledWavelengths &lambda,
                                           bool allowIncompletePDF = false) const;
    Float PDF_Li(LightSampleContext ctx, Vector3f wi, bool allowIncompletePDF = false) const;
    pstd::optional<LightLeSample> SampleLe(Point2f u1, Point2f u2, const SampledWavelengths &lambda,
                                           Float time) const;
    // For a ray leaving the light's surface point p (normal n, parameters uv) toward w.
    LightLePDF PDF_Le(Point3f p, Normal3f n, Point2f uv, Vector3f w) const;
    // Radiance leaving the surface point p with normal n toward w.
    SampledSpectrum L(Point3f p, Normal3f n, Point2f uv, Vector3f w,
                      const SampledWavelengths &lambda) const;
    pstd::optional<LightBounds> Bounds() const;
    std::string ToString() const;

  private:
    Shape shape;
    Float area;
    Spectrum Lemit;
    Float scale;
    bool twoSided;
    std::shared_ptr<const EmissionImage> image;
};

// Constant radiance scale * Lemit from every direction at infinity.
class UniformInfiniteLight {
  public:
    UniformInfiniteLight(Spectrum Lemit, Float scale);

    LightType Type() const { return LightType::Infinite; }
    void Preprocess(const Bounds3f &sceneBounds);
    SampledSpectrum Phi(const SampledWavelengths &lambda) const;
    // Under MIS (allowIncompletePDF) its light sampling gives nothing: BSDF sampling covers it.
    UnboundedLightImportance Importance(bool allowIncompletePDF) const {
        return {allowIncompletePDF ? 0 : Pi * scale * Lemit.MaxValue(), {}};
    }
    pstd::optional<LightLiSample> SampleLi(LightSampleContext ctx, Point2f u,
                                           const SampledWavelengths &lambda,
                                           bool allowIncompletePDF = false) const;
    Float PDF_Li(LightSampleContext ctx, Vector3f wi, bool allowIncompletePDF = false) const;
    pstd::optional<LightLeSample> SampleLe(Point2f u1, Point2f u2, const SampledWavelengths &lambda,
                                           Float time) const;
    LightLePDF PDF_Le(const Ray &ray) const;
    SampledSpectrum Le(const Ray &ray, const SampledWavelengths &lambda) const;
    std::string ToString() const;

  private:
    Spectrum Lemit;
    Float scale;
    Point3f sceneCenter;
    Float sceneRadius = 0;
};

// Environment light from a square RGB image in the equal-area octahedral parameterization
// (util/equalarea.h): the light-space direction w has radiance scale * image(EqualAreaSphereToSquare(w)),
// nearest-pixel lookup as pbrt-v4. Directions are importance sampled by a PiecewiseConstant2D
// over the pixels' average RGB; since the map is equal-area, its density per unit square is
// the density per solid angle times 4 pi. Throws std::runtime_error for an image that is not
// square.
class ImageInfiniteLight {
  public:
    // colorSpace: the image's (nullptr: sRGB).
    ImageInfiniteLight(const Transform &worldFromLight, Image image, Float scale,
                       const RGBColorSpace *colorSpace = nullptr);

    LightType Type() const { return LightType::Infinite; }
    void Preprocess(const Bounds3f &sceneBounds);
    SampledSpectrum Phi(const SampledWavelengths &lambda) const;
    // Whole, also under MIS: weighing only what stands out of the average (what the compensated
    // density samples) starved light sampling of sky.exr behind fabric, whose BSDF sampling
    // finds the sky poorly (error 1.6x pbrt-v4's choice's on scenes/fabric-cylinder.pbrt).
    UnboundedLightImportance Importance(bool) const { return {Pi * scale * meanChannel, {}}; }
    pstd::optional<LightLiSample> SampleLi(LightSampleContext ctx, Point2f u,
                                           const SampledWavelengths &lambda,
                                           bool allowIncompletePDF = false) const;
    Float PDF_Li(LightSampleContext ctx, Vector3f wi, bool allowIncompletePDF = false) const;
    pstd::optional<LightLeSample> SampleLe(Point2f u1, Point2f u2, const SampledWavelengths &lambda,
                                           Float time) const;
    LightLePDF PDF_Le(const Ray &ray) const;
    SampledSpectrum Le(const Ray &ray, const SampledWavelengths &lambda) const;
    std::string ToString() const;

  private:
    // Radiance at the point uv of the equal-area square.
    SampledSpectrum ImageLe(Point2f uv, const SampledWavelengths &lambda) const;

    Transform worldFromLight;
    Image image;
    const RGBColorSpace *colorSpace;
    Float scale;
    Point3f sceneCenter;
    Float sceneRadius = 0;
    // The second density is for MIS with BSDF sampling: the image minus its average, clamped at
    // zero, so that light sampling concentrates on what stands out and leaves the smooth
    // remainder to BSDF sampling (Karlík et al. 2019, "MIS compensation", as pbrt-v4).
    PiecewiseConstant2D distribution, compensatedDistribution;
    Float meanChannel;  // over all pixels and channels
};

// Closed dispatch over the light kinds. L is zero for lights without a surface, Le zero for
// lights that escaping rays cannot see, and Preprocess does nothing for lights that do not
// depend on the scene's extent.
class Light {
  public:
    template <typename T>
    Light(T light) : light(std::move(light)) {}

    LightType Type() const {
        return std::visit([](const auto &l) { return l.Type(); }, light);
    }
    SampledSpectrum Phi(const SampledWavelengths &lambda) const {
        return std::visit([&](const auto &l) { return l.Phi(lambda); }, light);
    }
    pstd::optional<LightBounds> Bounds() const {
        return std::visit([](const auto &l) -> pstd::optional<LightBounds> {
            if constexpr (requires { l.Bounds(); })
                return l.Bounds();
            else
                return {};
        }, light);
    }
    // What the BVH light sampler weighs a light without Bounds() (distant, infinite) by, for
    // SampleLi with allowIncompletePDF as given; every such kind must say.
    UnboundedLightImportance Importance(bool allowIncompletePDF) const {
        return std::visit([&](const auto &l) -> UnboundedLightImportance {
            if constexpr (requires { l.Bounds(); })
                return {};
            else
                return l.Importance(allowIncompletePDF);
        }, light);
    }
    void Preprocess(const Bounds3f &sceneBounds) {
        std::visit([&](auto &l) {
            if constexpr (requires { l.Preprocess(sceneBounds); })
                l.Preprocess(sceneBounds);
        }, light);
    }
    pstd::optional<LightLiSample> SampleLi(LightSampleContext ctx, Point2f u,
                                           const SampledWavelengths &lambda,
                                           bool allowIncompletePDF = false) const {
        return std::visit(
            [&](const auto &l) { return l.SampleLi(ctx, u, lambda, allowIncompletePDF); }, light);
    }
    Float PDF_Li(LightSampleContext ctx, Vector3f wi, bool allowIncompletePDF = false) const {
        return std::visit([&](const auto &l) { return l.PDF_Li(ctx, wi, allowIncompletePDF); },
                          light);
    }
    // Emission sampling, for paths traced from the lights (bdpt, lightpath): a ray leaving the
    // light, and the densities of a given one. PDF_Le(p, n, uv, w) is for area lights, whose rays
    // leave their surface; PDF_Le(ray) for the others.
    pstd::optional<LightLeSample> SampleLe(Point2f u1, Point2f u2, const SampledWavelengths &lambda,
                                           Float time) const {
        return std::visit([&](const auto &l) { return l.SampleLe(u1, u2, lambda, time); }, light);
    }
    LightLePDF PDF_Le(const Ray &ray) const {
        return std::visit([&](const auto &l) {
            if constexpr (requires { l.PDF_Le(ray); })
                return l.PDF_Le(ray);
            else
                return LightLePDF{};
        }, light);
    }
    LightLePDF PDF_Le(Point3f p, Normal3f n, Point2f uv, Vector3f w) const {
        return std::visit([&](const auto &l) {
            if constexpr (requires { l.PDF_Le(p, n, uv, w); })
                return l.PDF_Le(p, n, uv, w);
            else
                return LightLePDF{};
        }, light);
    }
    SampledSpectrum L(Point3f p, Normal3f n, Point2f uv, Vector3f w,
                      const SampledWavelengths &lambda) const {
        return std::visit([&](const auto &l) {
            if constexpr (requires { l.L(p, n, uv, w, lambda); })
                return l.L(p, n, uv, w, lambda);
            else
                return SampledSpectrum(0.f);
        }, light);
    }
    SampledSpectrum Le(const Ray &ray, const SampledWavelengths &lambda) const {
        return std::visit([&](const auto &l) {
            if constexpr (requires { l.Le(ray, lambda); })
                return l.Le(ray, lambda);
            else
                return SampledSpectrum(0.f);
        }, light);
    }
    std::string ToString() const {
        return std::visit([](const auto &l) { return l.ToString(); }, light);
    }

    template <typename T>
    const T *CastOrNullptr() const {
        return std::get_if<T>(&light);
    }

  private:
    std::variant<PointLight, SpotLight, GoniometricLight, ProjectionLight, DistantLight,
                 DiffuseAreaLight, UniformInfiniteLight, ImageInfiniteLight, PortalImageInfiniteLight>
        light;
};

}  // namespace pbrt
