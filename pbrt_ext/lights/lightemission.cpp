// Emission sampling of every light (pbrt-v4's SampleLe and PDF_Le): the rays that paths traced
// from the lights start with (bdpt, lightpath), and the densities of given ones for the MIS
// weights of bidirectional strategies. lights.cpp and its siblings hold the other direction,
// sampling a light from a receiving point.
//
// As in pbrt-v4: point-like lights emit from their position in a direction drawn uniformly over
// the sphere (over the cone for spot lights, over the image for projection lights); area lights
// from a point drawn by the shape's area sampling, cosine-distributed about the normal; distant
// and infinite lights along a direction they choose, from a point drawn uniformly on the disk of
// the scene's bounding sphere that faces it.
#include "pbrt_ext/lights/lights.h"

#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/equalarea.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/sampling.h"

namespace pbrt {

namespace {

// A ray in direction w from a point drawn uniformly on the disk through the scene's bounding
// sphere's center facing w, moved back outside the sphere; its origin's density is 1 / (pi r^2).
Ray RayFromSceneDisk(Point3f center, Float radius, Vector3f w, Point2f u, Float time) {
    Frame frame = Frame::FromZ(-w);
    Point2f cd = SampleUniformDiskConcentric(u);
    Point3f pDisk = center + radius * frame.FromLocal(Vector3f(cd.x, cd.y, 0));
    return Ray(pDisk + radius * -w, w, -1, time);
}

Float SceneDiskPDF(Float radius) { return 1 / (Pi * Sqr(radius)); }

// A point light's ray: from p in the unit light-space direction wLight drawn with density pdfDir.
LightLeSample PointLightRay(const Transform &worldFromLight, Vector3f wLight, SampledSpectrum I,
                            Float pdfDir, Float time) {
    Ray ray(worldFromLight(Point3f(0, 0, 0)), Normalize(worldFromLight(wLight)), -1, time);
    return LightLeSample{I, ray, Normal3f(0, 0, 0), Point2f(), 1, pdfDir};
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Point-like lights

pstd::optional<LightLeSample> PointLight::SampleLe(Point2f u1, Point2f, const SampledWavelengths &lambda,
                                                   Float time) const {
    Ray ray(pLight, SampleUniformSphere(u1), -1, time);
    return LightLeSample{scale * I.Sample(lambda), ray, Normal3f(0, 0, 0), Point2f(), 1,
                         UniformSpherePDF()};
}

LightLePDF PointLight::PDF_Le(const Ray &) const { return {0, UniformSpherePDF()}; }

pstd::optional<LightLeSample> SpotLight::SampleLe(Point2f u1, Point2f, const SampledWavelengths &lambda,
                                                  Float time) const {
    Vector3f wLight = SampleUniformCone(u1, cosFalloffEnd);
    return PointLightRay(worldFromLight, wLight, I(wLight, lambda), UniformConePDF(cosFalloffEnd), time);
}

LightLePDF SpotLight::PDF_Le(const Ray &ray) const {
    Vector3f wLight = Normalize(worldFromLight.ApplyInverse(ray.d));
    return {0, CosTheta(wLight) >= cosFalloffEnd ? UniformConePDF(cosFalloffEnd) : 0};
}

pstd::optional<LightLeSample> GoniometricLight::SampleLe(Point2f u1, Point2f,
                                                         const SampledWavelengths &lambda,
                                                         Float time) const {
    Vector3f wLight = SampleUniformSphere(u1);
    return PointLightRay(worldFromLight, wLight, I(wLight, lambda), UniformSpherePDF(), time);
}

LightLePDF GoniometricLight::PDF_Le(const Ray &) const { return {0, UniformSpherePDF()}; }

// Uniform over the image plane z = 1 (pbrt-v4 follows the image's brightness instead): the
// density per unit area 1 / A is 1 / (A cos^3 theta) per unit solid angle.
pstd::optional<LightLeSample> ProjectionLight::SampleLe(Point2f u1, Point2f,
                                                        const SampledWavelengths &lambda,
                                                        Float time) const {
    Point2f ps = screenBounds.Lerp(u1);
    Vector3f wLight = Normalize(Vector3f(ps.x * tanHalfFov, ps.y * tanHalfFov, 1));
    SampledSpectrum L = I(wLight, lambda);
    if (!L)
        return {};
    return PointLightRay(worldFromLight, wLight, L, 1 / (A * Pow<3>(wLight.z)), time);
}

LightLePDF ProjectionLight::PDF_Le(const Ray &ray) const {
    Vector3f w = Normalize(worldFromLight.ApplyInverse(ray.d));
    if (w.z < hither)
        return {};
    Point3f ps = screenFromLight(Point3f(w.x, w.y, w.z));
    if (!Inside(Point2f(ps.x, ps.y), screenBounds))
        return {};
    return {0, 1 / (A * Pow<3>(w.z))};
}

// ---------------------------------------------------------------------------------------
// Distant and infinite lights

pstd::optional<LightLeSample> DistantLight::SampleLe(Point2f u1, Point2f, const SampledWavelengths &lambda,
                                                     Float time) const {
    Ray ray = RayFromSceneDisk(sceneCenter, sceneRadius, -wLight, u1, time);
    return LightLeSample{scale * Lemit.Sample(lambda), ray, Normal3f(0, 0, 0), Point2f(),
                         SceneDiskPDF(sceneRadius), 1};
}

LightLePDF DistantLight::PDF_Le(const Ray &) const { return {SceneDiskPDF(sceneRadius), 0}; }

pstd::optional<LightLeSample> UniformInfiniteLight::SampleLe(Point2f u1, Point2f u2,
                                                             const SampledWavelengths &lambda,
                                                             Float time) const {
    Vector3f w = -SampleUniformSphere(u1);
    Ray ray = RayFromSceneDisk(sceneCenter, sceneRadius, w, u2, time);
    return LightLeSample{scale * Lemit.Sample(lambda), ray, Normal3f(0, 0, 0), Point2f(),
                         SceneDiskPDF(sceneRadius), UniformSpherePDF()};
}

LightLePDF UniformInfiniteLight::PDF_Le(const Ray &) const {
    return {SceneDiskPDF(sceneRadius), UniformSpherePDF()};
}

pstd::optional<LightLeSample> ImageInfiniteLight::SampleLe(Point2f u1, Point2f u2,
                                                           const SampledWavelengths &lambda,
                                                           Float time) const {
    Float mapPDF = 0;
    Point2f uv = distribution.Sample(u1, &mapPDF);
    if (mapPDF == 0)
        return {};
    Vector3f wToLight = Normalize(worldFromLight(EqualAreaSquareToSphere(uv)));
    Ray ray = RayFromSceneDisk(sceneCenter, sceneRadius, -wToLight, u2, time);
    return LightLeSample{ImageLe(uv, lambda), ray, Normal3f(0, 0, 0), Point2f(),
                         SceneDiskPDF(sceneRadius), mapPDF / (4 * Pi)};
}

LightLePDF ImageInfiniteLight::PDF_Le(const Ray &ray) const {
    Vector3f wToLight = -Normalize(worldFromLight.ApplyInverse(ray.d));
    return {SceneDiskPDF(sceneRadius), distribution.PDF(EqualAreaSphereToSquare(wToLight)) / (4 * Pi)};
}

pstd::optional<LightLeSample> PortalImageInfiniteLight::SampleLe(Point2f u1, Point2f u2,
                                                                 const SampledWavelengths &lambda,
                                                                 Float time) const {
    Float mapPDF = 0;
    Bounds2f all(Point2f(0, 0), Point2f(1, 1));
    pstd::optional<Point2f> uv = distribution.Sample(u1, all, &mapPDF);
    if (!uv || mapPDF == 0)
        return {};
    Float dwduv;
    Vector3f wToLight = WorldFromImage(*uv, &dwduv);
    if (dwduv == 0)
        return {};
    Ray ray = RayFromSceneDisk(sceneCenter, sceneRadius, -wToLight, u2, time);
    return LightLeSample{ImageLookup(*uv, lambda), ray, Normal3f(0, 0, 0), Point2f(),
                         SceneDiskPDF(sceneRadius), mapPDF / dwduv};
}

LightLePDF PortalImageInfiniteLight::PDF_Le(const Ray &ray) const {
    Float dwduv = 0;
    pstd::optional<Point2f> uv = ImageFromWorld(-Normalize(ray.d), &dwduv);
    if (!uv || dwduv == 0)
        return {};
    Bounds2f all(Point2f(0, 0), Point2f(1, 1));
    return {SceneDiskPDF(sceneRadius), distribution.PDF(*uv, all) / dwduv};
}

// ---------------------------------------------------------------------------------------
// Area lights

pstd::optional<LightLeSample> DiffuseAreaLight::SampleLe(Point2f u1, Point2f u2,
                                                         const SampledWavelengths &lambda,
                                                         Float time) const {
    pstd::optional<ShapeSample> ss = shape.Sample(u1);
    if (!ss || !(ss->pdf > 0))
        return {};
    // Two-sided lights pick a side with the first dimension, reused for the direction.
    Vector3f w;
    Float pdfDir;
    if (twoSided) {
        bool back = u2[0] >= 0.5f;
        u2[0] = std::min(back ? (u2[0] - 0.5f) * 2 : u2[0] * 2, OneMinusEpsilon);
        w = SampleCosineHemisphere(u2);
        if (back)
            w.z = -w.z;
        pdfDir = CosineHemispherePDF(std::abs(w.z)) / 2;
    } else {
        w = SampleCosineHemisphere(u2);
        pdfDir = CosineHemispherePDF(w.z);
    }
    if (pdfDir == 0)
        return {};
    const ShapeSamplePoint &pt = ss->intr;
    w = Frame::FromZ(pt.n).FromLocal(w);
    // No medium: the caller knows the light's (MediumInterface's default).
    Ray ray(OffsetRayOrigin(pt.p, pt.n, w), w, -1, time);
    return LightLeSample{L(pt.p, pt.n, pt.uv, w, lambda), ray, pt.n, pt.uv, ss->pdf, pdfDir};
}

LightLePDF DiffuseAreaLight::PDF_Le(Point3f p, Normal3f n, Point2f uv, Vector3f w) const {
    Float pdfDir = twoSided ? CosineHemispherePDF(AbsDot(n, w)) / 2
                            : CosineHemispherePDF(std::max<Float>(0, Dot(n, w)));
    return {shape.PDF(p, uv), pdfDir};
}

}  // namespace pbrt
