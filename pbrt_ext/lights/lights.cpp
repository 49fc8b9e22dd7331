#include "pbrt_ext/lights/lights.h"

#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/equalarea.h"
#include "pbrt_ext/util/math.h"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <utility>
#include <vector>

namespace pbrt {

namespace {

std::string Format(Vector3f v) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "[ %g, %g, %g ]", v.x, v.y, v.z);
    return buf;
}
std::string Format(Point3f p) { return Format(Vector3f(p)); }
std::string Format(Float v) { return std::to_string(v); }

// Beyond every point of the scene in direction wi, for the shadow ray toward a light at
// infinity (pbrt-v4 uses the same 2 sceneRadius).
Point3f PointOutsideScene(Point3f p, Vector3f wi, Float sceneRadius) {
    return p + wi * (2 * sceneRadius);
}

// Power of constant radiance L arriving from all directions (or from one, for distant
// lights) onto the scene's bounding disk, as pbrt-v4 approximates it.
Float DiskArea(Float sceneRadius) { return Pi * Sqr(sceneRadius); }

}  // namespace

// ---------------------------------------------------------------------------------------
// PointLight

PointLight::PointLight(const Transform &worldFromLight, Spectrum I, Float scale)
    : pLight(worldFromLight(Point3f(0, 0, 0))), I(TabulatedForLookup(I)), scale(scale) {}

SampledSpectrum PointLight::Phi(const SampledWavelengths &lambda) const {
    return 4 * Pi * scale * I.Sample(lambda);
}

pstd::optional<LightLiSample> PointLight::SampleLi(LightSampleContext ctx, Point2f,
                                                   const SampledWavelengths &lambda, bool) const {
    Float r2 = DistanceSquared(pLight, ctx.p);
    if (r2 == 0)
        return {};
    Vector3f wi = Normalize(pLight - ctx.p);
    return LightLiSample{scale * I.Sample(lambda) / r2, wi, 1, pLight, Normal3f(0, 0, 0)};
}

// Isotropic: every direction from one point (pbrt-v4's bounds: cos(pi) and cos(pi/2)).
pstd::optional<LightBounds> PointLight::Bounds() const {
    Float phi = 4 * Pi * scale * I.MaxValue();
    return LightBounds(Bounds3f(pLight, pLight), Vector3f(0, 0, 1), phi, -1, 0, false);
}

std::string PointLight::ToString() const {
    return "[ PointLight p: " + Format(pLight) + " I: " + I.ToString() +
           " scale: " + Format(scale) + " ]";
}

// ---------------------------------------------------------------------------------------
// SpotLight

SpotLight::SpotLight(const Transform &worldFromLight, Spectrum I, Float scale,
                     Float totalWidth, Float falloffStart)
    : worldFromLight(worldFromLight), Iemit(TabulatedForLookup(I)), scale(scale),
      cosFalloffStart(std::cos(Radians(falloffStart))),
      cosFalloffEnd(std::cos(Radians(totalWidth))) {}

SampledSpectrum SpotLight::I(Vector3f w, const SampledWavelengths &lambda) const {
    return SmoothStep(CosTheta(w), cosFalloffEnd, cosFalloffStart) * scale * Iemit.Sample(lambda);
}

// The full cone up to the falloff start, plus the falloff band at the average of the
// smoothstep over cos theta (1/2).
SampledSpectrum SpotLight::Phi(const SampledWavelengths &lambda) const {
    return scale * Iemit.Sample(lambda) * 2 * Pi *
           ((1 - cosFalloffStart) + (cosFalloffStart - cosFalloffEnd) / 2);
}

pstd::optional<LightLiSample> SpotLight::SampleLi(LightSampleContext ctx, Point2f,
                                                  const SampledWavelengths &lambda, bool) const {
    return PointLightSample(worldFromLight, ctx, [&](Vector3f w) { return I(w, lambda); });
}

// The axis with the full cone as the normals' spread, and the falloff band as emission spread.
pstd::optional<LightBounds> SpotLight::Bounds() const {
    Point3f p = worldFromLight(Point3f(0, 0, 0));
    Vector3f w = Normalize(worldFromLight(Vector3f(0, 0, 1)));
    Float phi = scale * Iemit.MaxValue() * 4 * Pi;
    Float cosTheta_e = std::cos(std::acos(cosFalloffEnd) - std::acos(cosFalloffStart));
    // Slack for the rounding of the importance's cosines where the band is thin (pbrt-v4).
    if (cosTheta_e == 1 && cosFalloffEnd != cosFalloffStart)
        cosTheta_e = 0.999f;
    return LightBounds(Bounds3f(p, p), w, phi, cosFalloffStart, cosTheta_e, false);
}

std::string SpotLight::ToString() const {
    return "[ SpotLight p: " + Format(worldFromLight(Point3f(0, 0, 0))) +
           " axis: " + Format(Normalize(worldFromLight(Vector3f(0, 0, 1)))) +
           " I: " + Iemit.ToString() + " scale: " + Format(scale) +
           " cosFalloffStart: " + Format(cosFalloffStart) +
           " cosFalloffEnd: " + Format(cosFalloffEnd) + " ]";
}

// ---------------------------------------------------------------------------------------
// DistantLight

DistantLight::DistantLight(const Transform &worldFromLight, Spectrum Lemit, Float scale)
    : wLight(Normalize(worldFromLight(Vector3f(0, 0, 1)))), Lemit(TabulatedForLookup(Lemit)), scale(scale) {}

void DistantLight::Preprocess(const Bounds3f &sceneBounds) {
    sceneBounds.BoundingSphere(&sceneCenter, &sceneRadius);
}

SampledSpectrum DistantLight::Phi(const SampledWavelengths &lambda) const {
    return scale * Lemit.Sample(lambda) * DiskArea(sceneRadius);
}

pstd::optional<LightLiSample> DistantLight::SampleLi(LightSampleContext ctx, Point2f,
                                                     const SampledWavelengths &lambda, bool) const {
    return LightLiSample{scale * Lemit.Sample(lambda), wLight, 1, PointOutsideScene(ctx.p, wLight, sceneRadius),
                         Normal3f(0, 0, 0)};
}

std::string DistantLight::ToString() const {
    return "[ DistantLight w: " + Format(wLight) + " Lemit: " + Lemit.ToString() +
           " scale: " + Format(scale) + " ]";
}

// ---------------------------------------------------------------------------------------
// DiffuseAreaLight

EmissionImage::EmissionImage(Image image, const RGBColorSpace *colorSpace)
    : image(std::move(image)), colorSpace(colorSpace) {
    Point2i res = this->image.Resolution();
    RGB lum = colorSpace->LuminanceVector();
    double sumLuminance = 0;
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x) {
            RGB rgb = this->image.GetChannels(Point2i(x, y));
            sumLuminance += lum.r * rgb.r + lum.g * rgb.g + lum.b * rgb.b;
        }
    meanChannel = this->image.MeanChannel();
    meanLuminance = Float(sumLuminance / (double(res.x) * res.y));
}

RGB EmissionImage::Lookup(Point2f uv) const {
    return ClampZero(image.Bilerp(Point2f(uv[0], 1 - uv[1]), WrapMode::Clamp));
}

DiffuseAreaLight::DiffuseAreaLight(Shape shape, Spectrum Lemit, Float scale, bool twoSided,
                                   std::shared_ptr<const EmissionImage> image)
    : shape(std::move(shape)), area(this->shape.Area()), Lemit(TabulatedForLookup(Lemit)), scale(scale),
      twoSided(twoSided), image(std::move(image)) {}

// Lambertian emission: pi L per unit area and side, L the image's mean spectrum if there is one.
SampledSpectrum DiffuseAreaLight::Phi(const SampledWavelengths &lambda) const {
    SampledSpectrum L = Lemit.Sample(lambda);
    if (image) {
        Point2i res = image->image.Resolution();
        L = SampledSpectrum(0.f);
        for (int y = 0; y < res.y; ++y)
            for (int x = 0; x < res.x; ++x)
                L += RGBIlluminantSpectrum(*image->colorSpace, ClampZero(image->image.GetChannels(Point2i(x, y))))
                         .Sample(lambda);
        L /= Float(res.x * res.y);
    }
    return Pi * (twoSided ? 2 : 1) * area * scale * L;
}

SampledSpectrum DiffuseAreaLight::L(Point3f, Normal3f n, Point2f uv, Vector3f w,
                                    const SampledWavelengths &lambda) const {
    if (!twoSided && Dot(n, w) < 0)
        return SampledSpectrum(0.f);
    if (image) return scale * RGBIlluminantSpectrum(*image->colorSpace, image->Lookup(uv)).Sample(lambda);
    return scale * Lemit.Sample(lambda);
}

pstd::optional<LightLiSample> DiffuseAreaLight::SampleLi(LightSampleContext ctx, Point2f u,
                                                         const SampledWavelengths &lambda,
                                                         bool) const {
    pstd::optional<ShapeSample> ss = shape.Sample(ctx, u);
    if (!ss || !(ss->pdf > 0) || LengthSquared(ss->intr.p - ctx.p) == 0)
        return {};
    Vector3f wi = Normalize(ss->intr.p - ctx.p);
    SampledSpectrum Le = L(ss->intr.p, ss->intr.n, ss->intr.uv, -wi, lambda);
    if (!Le)
        return {};
    return LightLiSample{Le, wi, ss->pdf, ss->intr.p, ss->intr.n, ss->intr.uv};
}

Float DiffuseAreaLight::PDF_Li(LightSampleContext ctx, Vector3f wi, bool) const {
    return shape.PDF(ctx, wi);
}

namespace {

// The directions the shape's emitting normals take, read from the shape's own samples so that
// they are oriented exactly as its intersections are (the side L() emits toward). Triangles and
// disks are flat, a bilinear patch's normal stays within the cone of its corner normals (the
// cross product of its tangents is bilinear in u and v), and spheres and cylinders face every
// way (a partial cylinder's cone is left whole, as pbrt-v4 leaves it).
DirectionCone NormalBounds(const Shape &shape) {
    if (shape.CastOrNullptr<Sphere>() || shape.CastOrNullptr<Cylinder>())
        return DirectionCone::EntireSphere();
    static constexpr Point2f center[] = {Point2f(0.5f, 0.5f)};
    static constexpr Point2f corners[] = {Point2f(0, 0), Point2f(OneMinusEpsilon, 0),
                                          Point2f(0, OneMinusEpsilon),
                                          Point2f(OneMinusEpsilon, OneMinusEpsilon)};
    pstd::span<const Point2f> at = center;
    if (shape.CastOrNullptr<BilinearPatch>())
        at = corners;
    DirectionCone cone;
    for (Point2f u : at) {
        pstd::optional<ShapeSample> ss = shape.Sample(u);
        if (!ss || LengthSquared(ss->intr.n) == 0)
            return DirectionCone::EntireSphere();
        cone = Union(cone, DirectionCone(Vector3f(ss->intr.n)));
    }
    return cone;
}

}  // namespace

// pbrt-v4's: power pi L area (one side), the shape's normal cone, emission over a hemisphere.
pstd::optional<LightBounds> DiffuseAreaLight::Bounds() const {
    Float phi = (image ? image->meanChannel : Lemit.MaxValue()) * scale * area * Pi;
    DirectionCone normals = NormalBounds(shape);
    return LightBounds(shape.Bounds(), normals.w, phi, normals.cosTheta, 0, twoSided);
}

std::string DiffuseAreaLight::ToString() const {
    return "[ DiffuseAreaLight shape: " + shape.ToString() + " Lemit: " + Lemit.ToString() +
           " scale: " + Format(scale) + " twoSided: " + (twoSided ? "true" : "false") +
           " ]";
}

// ---------------------------------------------------------------------------------------
// UniformInfiniteLight

UniformInfiniteLight::UniformInfiniteLight(Spectrum Lemit, Float scale)
    : Lemit(TabulatedForLookup(Lemit)), scale(scale) {}

void UniformInfiniteLight::Preprocess(const Bounds3f &sceneBounds) {
    sceneBounds.BoundingSphere(&sceneCenter, &sceneRadius);
}

SampledSpectrum UniformInfiniteLight::Phi(const SampledWavelengths &lambda) const {
    return 4 * Pi * DiskArea(sceneRadius) * scale * Lemit.Sample(lambda);
}

// Under MIS, BSDF sampling alone covers a constant environment better than uniform sphere
// sampling would: the light declines, and PDF_Li says so.
pstd::optional<LightLiSample> UniformInfiniteLight::SampleLi(LightSampleContext ctx, Point2f u,
                                                             const SampledWavelengths &lambda,
                                                             bool allowIncompletePDF) const {
    if (allowIncompletePDF)
        return {};
    Vector3f wi = SampleUniformSphere(u);
    return LightLiSample{scale * Lemit.Sample(lambda), wi, UniformSpherePDF(),
                         PointOutsideScene(ctx.p, wi, sceneRadius), Normal3f(0, 0, 0)};
}

Float UniformInfiniteLight::PDF_Li(LightSampleContext, Vector3f, bool allowIncompletePDF) const {
    return allowIncompletePDF ? 0 : UniformSpherePDF();
}

SampledSpectrum UniformInfiniteLight::Le(const Ray &, const SampledWavelengths &lambda) const {
    return scale * Lemit.Sample(lambda);
}

std::string UniformInfiniteLight::ToString() const {
    return "[ UniformInfiniteLight Lemit: " + Lemit.ToString() +
           " scale: " + Format(scale) + " ]";
}

// ---------------------------------------------------------------------------------------
// ImageInfiniteLight

namespace {

// Radiance is the pixel clamped at zero (EXR filtering can ring below it).
RGB PixelRGB(const Image &image, Point2i p) { return ClampZero(image.GetChannels(p)); }

// The pixels' average clamped RGB, row-major as PiecewiseConstant2D expects. Unlike
// Image::GetSamplingDistribution (pbrt-v4's, which averages raw values), the density is then
// zero only where the radiance is, so sampling stays unbiased next to negative channels.
std::vector<Float> SamplingFunction(const Image &image) {
    Point2i res = image.Resolution();
    std::vector<Float> f(size_t(res.x) * res.y);
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x)
            f[size_t(y) * res.x + x] = PixelRGB(image, Point2i(x, y)).Average();
    return f;
}

Float Mean(const std::vector<Float> &f) {
    return Float(std::accumulate(f.begin(), f.end(), 0.0) / double(f.size()));
}

// pbrt-v4's compensation: subtract the average and clamp; a constant image keeps its
// (uniform) density, since nothing would be left to sample.
std::vector<Float> Compensated(std::vector<Float> f) {
    Float average = Mean(f);
    bool allZero = true;
    for (Float &v : f) {
        v = std::max<Float>(v - average, 0);
        allZero &= v == 0;
    }
    if (allZero)
        std::fill(f.begin(), f.end(), Float(1));
    return f;
}

Image CheckedSquare(Image image) {
    Point2i res = image.Resolution();
    if (res.x != res.y || res.x <= 0)
        throw std::runtime_error("ImageInfiniteLight: image resolution " + std::to_string(res.x) +
                                 "x" + std::to_string(res.y) +
                                 " is not square; the equal-area octahedral mapping needs a "
                                 "square image");
    return image;
}

}  // namespace

ImageInfiniteLight::ImageInfiniteLight(const Transform &worldFromLight, Image image, Float scale,
                                       const RGBColorSpace *colorSpace)
    : worldFromLight(worldFromLight), image(CheckedSquare(std::move(image))),
      colorSpace(colorSpace ? colorSpace : &RGBColorSpace::sRGB()), scale(scale) {
    Point2i res = this->image.Resolution();
    std::vector<Float> f = SamplingFunction(this->image);
    meanChannel = Mean(f);
    distribution = PiecewiseConstant2D(f, res.x, res.y);
    compensatedDistribution = PiecewiseConstant2D(Compensated(std::move(f)), res.x, res.y);
}

void ImageInfiniteLight::Preprocess(const Bounds3f &sceneBounds) {
    sceneBounds.BoundingSphere(&sceneCenter, &sceneRadius);
}

// Nearest pixel, as pbrt-v4; uv on the square's far edges gives a pixel index one past the
// end, which the octahedral wrap folds back onto the image.
SampledSpectrum ImageInfiniteLight::ImageLe(Point2f uv, const SampledWavelengths &lambda) const {
    RGB rgb = ClampZero(image.LookupNearest(uv, WrapMode::OctahedralSphere));
    return scale * RGBIlluminantSpectrum(*colorSpace, rgb).Sample(lambda);
}

// Average radiance over the sphere times the 4 pi pi r^2 of a uniform environment.
SampledSpectrum ImageInfiniteLight::Phi(const SampledWavelengths &lambda) const {
    Point2i res = image.Resolution();
    SampledSpectrum sumL(0.f);
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x)
            sumL += RGBIlluminantSpectrum(*colorSpace, PixelRGB(image, Point2i(x, y))).Sample(lambda);
    return 4 * Pi * DiskArea(sceneRadius) * scale * sumL / (Float(res.x) * res.y);
}

pstd::optional<LightLiSample> ImageInfiniteLight::SampleLi(LightSampleContext ctx, Point2f u,
                                                           const SampledWavelengths &lambda,
                                                           bool allowIncompletePDF) const {
    Float mapPDF = 0;
    Point2f uv = allowIncompletePDF ? compensatedDistribution.Sample(u, &mapPDF)
                                    : distribution.Sample(u, &mapPDF);
    if (mapPDF == 0)
        return {};
    Vector3f wi = Normalize(worldFromLight(EqualAreaSquareToSphere(uv)));
    return LightLiSample{ImageLe(uv, lambda), wi, mapPDF / (4 * Pi),
                         PointOutsideScene(ctx.p, wi, sceneRadius), Normal3f(0, 0, 0)};
}

Float ImageInfiniteLight::PDF_Li(LightSampleContext, Vector3f wi, bool allowIncompletePDF) const {
    Point2f uv = EqualAreaSphereToSquare(Normalize(worldFromLight.ApplyInverse(wi)));
    Float mapPDF = allowIncompletePDF ? compensatedDistribution.PDF(uv) : distribution.PDF(uv);
    return mapPDF / (4 * Pi);
}

SampledSpectrum ImageInfiniteLight::Le(const Ray &ray, const SampledWavelengths &lambda) const {
    return ImageLe(EqualAreaSphereToSquare(Normalize(worldFromLight.ApplyInverse(ray.d))), lambda);
}

std::string ImageInfiniteLight::ToString() const {
    Point2i res = image.Resolution();
    return "[ ImageInfiniteLight resolution: " + std::to_string(res.x) + "x" +
           std::to_string(res.y) + " scale: " + Format(scale) + " ]";
}

}  // namespace pbrt
