#include "pbrt_ext/cameras/cameraimportance.h"

#include "pbrt_ext/util/sampling.h"

#include <stdexcept>
#include <string>

namespace pbrt {

namespace {

const PerspectiveCamera &Perspective(const Camera &camera) {
    const PerspectiveCamera *perspective = camera.CastOrNullptr<PerspectiveCamera>();
    if (!perspective)
        throw std::invalid_argument(std::string("paths traced from the lights need a perspective "
                                                "camera (as in pbrt-v4), not \"") +
                                    camera.Name() + "\"");
    return *perspective;
}

}  // namespace

CameraImportance::CameraImportance(const Camera &camera, const RGBFilm &film)
    : motion(Perspective(camera).Motion()),
      cameraFromRaster(Perspective(camera).CameraFromRaster()),
      lensRadius(Perspective(camera).LensRadius()),
      focalDistance(Perspective(camera).FocalDistance()) {
    Vector2f radius = film.GetFilter().Radius();
    Bounds2i pixels = film.PixelBounds();
    sampleBounds = Bounds2f(Point2f(pixels.pMin.x - radius.x + 0.5f, pixels.pMin.y - radius.y + 0.5f),
                            Point2f(pixels.pMax.x + radius.x - 0.5f, pixels.pMax.y + radius.y - 0.5f));
    // The corner of the film's footprint is its widest direction (pbrt-v4's cosTotalWidth).
    cosTotalWidth = Normalize(Vector3f(cameraFromRaster(Point3f(-radius.x, -radius.y, 0)))).z;
    Point2i res = film.FullResolution();
    Point3f pMin = cameraFromRaster(Point3f(0, 0, 0)), pMax = cameraFromRaster(Point3f(res.x, res.y, 0));
    pMin /= pMin.z;
    pMax /= pMax.z;
    A = std::abs((pMax.x - pMin.x) * (pMax.y - pMin.y));
}

pstd::optional<Point2f> CameraImportance::RasterPosition(const Ray &ray, Float *cosTheta) const {
    Transform worldFromCamera = WorldFromCamera(ray.time);
    *cosTheta = Dot(ray.d, Normalize(worldFromCamera(Vector3f(0, 0, 1))));
    if (*cosTheta <= cosTotalWidth)
        return {};
    // The point the ray focuses on, projected to the film (the thin lens maps it to the pinhole's
    // raster position).
    Point3f pFocus = ray((lensRadius > 0 ? focalDistance : 1) / *cosTheta);
    Point3f pRaster = cameraFromRaster.ApplyInverse(worldFromCamera.ApplyInverse(pFocus));
    Point2f p(pRaster.x, pRaster.y);
    if (!Inside(p, sampleBounds))
        return {};
    return p;
}

SampledSpectrum CameraImportance::We(const Ray &ray, Point2f *pRaster) const {
    Float cosTheta;
    pstd::optional<Point2f> p = RasterPosition(ray, &cosTheta);
    if (!p)
        return SampledSpectrum(0.f);
    if (pRaster)
        *pRaster = *p;
    return SampledSpectrum(1 / (A * LensArea() * Pow<4>(cosTheta)));
}

CameraPDF CameraImportance::PDF_We(const Ray &ray) const {
    Float cosTheta;
    if (!RasterPosition(ray, &cosTheta))
        return {};
    return {1 / LensArea(), 1 / (A * Pow<3>(cosTheta))};
}

pstd::optional<CameraWiSample> CameraImportance::SampleWi(Point3f p, Float time, Point2f u) const {
    Transform worldFromCamera = WorldFromCamera(time);
    Point2f pLensCamera = lensRadius * SampleUniformDiskConcentric(u);
    Point3f pLens = worldFromCamera(Point3f(pLensCamera.x, pLensCamera.y, 0));
    Normal3f n(Normalize(worldFromCamera(Vector3f(0, 0, 1))));
    Vector3f wi = pLens - p;
    Float dist = Length(wi);
    if (dist == 0)
        return {};
    wi /= dist;
    Float pdf = Sqr(dist) / (AbsDot(n, wi) * LensArea());
    Point2f pRaster;
    SampledSpectrum Wi = We(Ray(pLens, -wi, -1, time), &pRaster);
    if (!Wi)
        return {};
    return CameraWiSample{Wi, wi, pdf, pRaster, pLens, n};
}

}  // namespace pbrt
