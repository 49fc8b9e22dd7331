#include "pbrt_ext/lights/portallight.h"

#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/equalarea.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <cmath>

namespace pbrt {

namespace {

// The portal's frame: x along its sides 0-3, y along 0-1, z = x cross y, its normal.
Frame PortalFrame(const std::array<Point3f, 4> &p) {
    return Frame::FromXY(Normalize(p[3] - p[0]), Normalize(p[1] - p[0]));
}

// The sampling function of the rectified image: each texel's average channel times the solid
// angle per unit of (u, v) at its centre, so that samples follow radiance per solid angle
// (pbrt-v4's, whose "duv_dw" is this d(omega)/d(u,v)).
std::vector<Float> SamplingFunction(const Image &image, const std::vector<Float> &dwduv) {
    Point2i res = image.Resolution();
    std::vector<Float> f(size_t(res.x) * size_t(res.y));
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x) {
            size_t i = size_t(y) * size_t(res.x) + size_t(x);
            f[i] = ClampZero(image.GetChannels(Point2i(x, y))).Average() * dwduv[i];
        }
    return f;
}

}  // namespace

std::string PortalImageInfiniteLight::PortalFrameError(const std::array<Point3f, 4> &p) {
    Vector3f p01 = p[1] - p[0], p12 = p[2] - p[1], p32 = p[2] - p[3], p03 = p[3] - p[0];
    if (!(LengthSquared(p01) > 0) || !(LengthSquared(p03) > 0) || !(LengthSquared(p12) > 0) ||
        !(LengthSquared(p32) > 0))
        return "portal has coincident corners";
    p01 = Normalize(p01), p12 = Normalize(p12), p32 = Normalize(p32), p03 = Normalize(p03);
    // Opposite sides parallel and adjacent ones perpendicular, to pbrt-v4's tolerance.
    if (std::abs(Dot(p01, p32) - 1) > .001f || std::abs(Dot(p12, p03) - 1) > .001f ||
        std::abs(Dot(p01, p12)) > .001f || std::abs(Dot(p12, p32)) > .001f ||
        std::abs(Dot(p32, p03)) > .001f || std::abs(Dot(p03, p01)) > .001f)
        return "portal is not a planar rectangle (its corners in order)";
    return {};
}

PortalImageInfiniteLight::PortalImageInfiniteLight(const Transform &worldFromLight,
                                                   const Image &equalAreaImage, Float scale,
                                                   const RGBColorSpace *colorSpace,
                                                   const std::array<Point3f, 4> &portal)
    : portal(portal), portalFrame(PortalFrame(portal)), image(equalAreaImage.Resolution()),
      colorSpace(colorSpace), scale(scale), distribution({Float(1)}, 1, 1) {
    // Resample the environment into the rectified parameterization, and weigh each texel by
    // the solid angle it covers for the sampling function.
    Point2i res = image.Resolution();
    std::vector<Float> dwduv(size_t(res.x) * size_t(res.y));
    tbb::parallel_for(0, res.y, [&](int y) {
        for (int x = 0; x < res.x; ++x) {
            Point2f uv((x + 0.5f) / res.x, (y + 0.5f) / res.y);
            Float dwduvAt;
            Vector3f w = Normalize(worldFromLight.ApplyInverse(WorldFromImage(uv, &dwduvAt)));
            RGB rgb = equalAreaImage.Bilerp(EqualAreaSphereToSquare(w), WrapMode::OctahedralSphere);
            for (int c = 0; c < 3; ++c) image.SetChannel(Point2i(x, y), c, rgb[c]);
            dwduv[size_t(y) * size_t(res.x) + size_t(x)] = dwduvAt;
        }
    });
    distribution = WindowedPiecewiseConstant2D(SamplingFunction(image, dwduv), res.x, res.y);
    meanChannel = equalAreaImage.MeanChannel();
}

void PortalImageInfiniteLight::Preprocess(const Bounds3f &sceneBounds) {
    sceneBounds.BoundingSphere(&sceneCenter, &sceneRadius);
}

pstd::optional<Point2f> PortalImageInfiniteLight::ImageFromWorld(Vector3f wWorld, Float *dwduv) const {
    Vector3f w = portalFrame.ToLocal(wWorld);
    if (w.z <= 0) return {};
    if (dwduv) *dwduv = Sqr(Pi) * (1 - Sqr(w.x)) * (1 - Sqr(w.y)) / w.z;
    Float alpha = std::atan2(w.x, w.z), beta = std::atan2(w.y, w.z);
    return Point2f(Clamp((alpha + Pi / 2) / Pi, 0, 1), Clamp((beta + Pi / 2) / Pi, 0, 1));
}

Vector3f PortalImageInfiniteLight::WorldFromImage(Point2f uv, Float *dwduv) const {
    Float alpha = -Pi / 2 + uv[0] * Pi, beta = -Pi / 2 + uv[1] * Pi;
    Vector3f w = Normalize(Vector3f(std::tan(alpha), std::tan(beta), 1));
    if (dwduv) *dwduv = Sqr(Pi) * (1 - Sqr(w.x)) * (1 - Sqr(w.y)) / w.z;
    return portalFrame.FromLocal(w);
}

pstd::optional<Bounds2f> PortalImageInfiniteLight::ImageBounds(Point3f p) const {
    pstd::optional<Point2f> p0 = ImageFromWorld(Normalize(portal[0] - p));
    pstd::optional<Point2f> p1 = ImageFromWorld(Normalize(portal[2] - p));
    if (!p0 || !p1) return {};
    return Bounds2f(*p0, *p1);
}

SampledSpectrum PortalImageInfiniteLight::ImageLookup(Point2f uv, const SampledWavelengths &lambda) const {
    RGB rgb = ClampZero(image.LookupNearest(uv));
    return scale * RGBIlluminantSpectrum(*colorSpace, rgb).Sample(lambda);
}

// pbrt-v4's: the fluence through the portal (radiance over the solid angle of each texel) times
// its area.
SampledSpectrum PortalImageInfiniteLight::Phi(const SampledWavelengths &lambda) const {
    Point2i res = image.Resolution();
    SampledSpectrum sum(0.f);
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x) {
            Float dwduv;
            WorldFromImage(Point2f((x + 0.5f) / res.x, (y + 0.5f) / res.y), &dwduv);
            RGB rgb = ClampZero(image.GetChannels(Point2i(x, y)));
            sum += RGBIlluminantSpectrum(*colorSpace, rgb).Sample(lambda) / dwduv;
        }
    return scale * Area() * sum / Float(res.x * res.y);
}

SampledSpectrum PortalImageInfiniteLight::Le(const Ray &ray, const SampledWavelengths &lambda) const {
    pstd::optional<Point2f> uv = ImageFromWorld(Normalize(ray.d));
    pstd::optional<Bounds2f> b = ImageBounds(ray.o);
    if (!uv || !b || !Inside(*uv, *b)) return SampledSpectrum(0.f);
    return ImageLookup(*uv, lambda);
}

pstd::optional<LightLiSample> PortalImageInfiniteLight::SampleLi(LightSampleContext ctx, Point2f u,
                                                                 const SampledWavelengths &lambda,
                                                                 bool) const {
    pstd::optional<Bounds2f> b = ImageBounds(ctx.p);
    if (!b) return {};
    Float mapPDF;
    pstd::optional<Point2f> uv = distribution.Sample(u, *b, &mapPDF);
    if (!uv) return {};
    Float dwduv;
    Vector3f wi = WorldFromImage(*uv, &dwduv);
    if (dwduv == 0) return {};
    return LightLiSample{ImageLookup(*uv, lambda), wi, mapPDF / dwduv, ctx.p + 2 * sceneRadius * wi,
                         Normal3f(0, 0, 0)};
}

Float PortalImageInfiniteLight::PDF_Li(LightSampleContext ctx, Vector3f w, bool) const {
    Float dwduv;
    pstd::optional<Point2f> uv = ImageFromWorld(w, &dwduv);
    if (!uv || dwduv == 0) return 0;
    pstd::optional<Bounds2f> b = ImageBounds(ctx.p);
    if (!b) return 0;
    return distribution.PDF(*uv, *b) / dwduv;
}

std::string PortalImageInfiniteLight::ToString() const {
    return fmt::format("[ PortalImageInfiniteLight scale: {} image: {}x{} portal area: {} ]", scale,
                       image.Resolution().x, image.Resolution().y, Area());
}

}  // namespace pbrt
