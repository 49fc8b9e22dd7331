// Small scenes built through SceneBuilder for the end-to-end tests and benchmarks.
#pragma once

#include "pbrt_ext/scene.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/spectra/spectrum.h"

#include <memory>
#include <vector>

namespace pbrt::testscenes {

inline Camera LookingAt(Point3f eye, Point3f look, Float fovDegrees, Point2i resolution) {
    Transform cameraFromWorld = LookAt(eye, look, Vector3f(0, 1, 0));
    return PerspectiveCamera(Inverse(cameraFromWorld), resolution, DefaultScreenWindow(resolution),
                             fovDegrees);
}

// The path tracer's options: maxDepth bounces, by one strategy.
inline IntegratorOptions PathTracer(int maxDepth, PathStrategy strategy = PathStrategy::MIS) {
    IntegratorOptions o;
    o.type = IntegratorType::Path;
    o.maxDepth = maxDepth;
    o.strategy = strategy;
    return o;
}

inline RGBFilm BoxFilteredFilm(Point2i resolution) {
    return RGBFilm(resolution, Bounds2i(Point2i(0, 0), resolution), BoxFilter(), "test.exr");
}

// A reflectance as a scene's "rgb reflectance" makes it: the sRGB albedo spectrum of rgb.
inline Spectrum RGBReflectance(Float r, Float g, Float b) {
    return RGBAlbedoSpectrum(RGBColorSpace::sRGB(), RGB(r, g, b));
}

// An emitter as a scene's "rgb L [r g b]" makes it (pbrt_ext/scene/create_lights.cpp): the sRGB
// illuminant spectrum of rgb, with the light's scale divided by the illuminant's luminance
// (pbrt-v4's SpectrumToPhotometric), so that rgb (1, 1, 1) is D65 at 1 nit and, through the
// default sensor and sRGB output, an emitter of rgb renders to about rgb.
struct Emission {
    Spectrum spectrum;
    Float scale;
};
inline Emission RGBEmission(Float r, Float g, Float b, Float scale = 1) {
    Spectrum L = RGBIlluminantSpectrum(RGBColorSpace::sRGB(), RGB(r, g, b));
    return {L, scale / SpectrumToPhotometric(L)};
}
// White light of the given luminance (nits): "rgb L [1 1 1]" with that scale.
inline Emission WhiteEmission(Float scale) { return RGBEmission(1, 1, 1, scale); }
inline AreaLightDescription RGBAreaLight(Float r, Float g, Float b, Float scale = 1,
                                         bool twoSided = false) {
    Emission e = RGBEmission(r, g, b, scale);
    return AreaLightDescription{e.spectrum, e.scale, twoSided};
}

// An axis-aligned rectangle at height z, facing +z (or -z when facingDown), as two triangles.
inline std::shared_ptr<TriangleMesh> Rectangle(Float x0, Float x1, Float y0, Float y1, Float z,
                                               bool facingDown = false) {
    std::vector<Point3f> p{Point3f(x0, y0, z), Point3f(x1, y0, z), Point3f(x1, y1, z),
                           Point3f(x0, y1, z)};
    std::vector<int> indices = facingDown ? std::vector<int>{0, 2, 1, 0, 3, 2}
                                          : std::vector<int>{0, 1, 2, 0, 2, 3};
    return std::make_shared<TriangleMesh>(
        MakeTriangleMesh(Transform(), false, std::move(indices), std::move(p)));
}

inline Sphere UnitSphereAt(Point3f center, Float radius = 1) {
    return Sphere(Translate(Vector3f(center)), false, radius, -radius, radius, 360);
}

// A box of the given size centered at (cx, 0, cz) standing on y = 0, turned about y; 12 triangles.
inline std::shared_ptr<TriangleMesh> Cuboid(Float cx, Float cz, Vector3f size, Float degrees) {
    Transform worldFromBox = Translate(Vector3f(cx, 0, cz)) * RotateY(degrees) *
                             Scale(size.x / 2, size.y, size.z / 2) * Translate(Vector3f(0, 0.5f, 0));
    std::vector<Point3f> p;
    for (int i = 0; i < 8; ++i)
        p.push_back(Point3f(i & 1 ? 1 : -1, i & 2 ? 0.5f : -0.5f, i & 4 ? 1 : -1));
    std::vector<int> indices{0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                             2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    return std::make_shared<TriangleMesh>(
        MakeTriangleMesh(worldFromBox, false, std::move(indices), std::move(p)));
}

// A quad from its four corners in order (two triangles).
inline std::shared_ptr<TriangleMesh> Quad(Point3f a, Point3f b, Point3f c, Point3f d) {
    return std::make_shared<TriangleMesh>(
        MakeTriangleMesh(Transform(), false, {0, 1, 2, 0, 2, 3}, {a, b, c, d}));
}

// The Cornell box of the issue: 5 diffuse walls, 2 boxes, 1 area light below the ceiling, the camera
// outside the open side (the classic dimensions, in units of 100 mm).
inline std::unique_ptr<Scene> CornellBox(Point2i resolution, int spp, IntegratorOptions options,
                                         Material boxMaterial = DiffuseMaterial{
                                             Spectrum(0.73f)}) {
    SceneBuilder builder(LookingAt(Point3f(2.78f, 2.73f, -8.0f), Point3f(2.78f, 2.73f, 0), 39.3f,
                                   resolution),
                         RGBFilm(resolution, Bounds2i(Point2i(0, 0), resolution), GaussianFilter(),
                                 "cornell.exr"),
                         ZSobolSampler(spp, resolution));
    int white = builder.AddMaterial(DiffuseMaterial{Spectrum(0.73f)});
    int red = builder.AddMaterial(DiffuseMaterial{RGBReflectance(0.65f, 0.05f, 0.05f)});
    int green = builder.AddMaterial(DiffuseMaterial{RGBReflectance(0.12f, 0.45f, 0.15f)});
    int boxes = builder.AddMaterial(std::move(boxMaterial));
    const Float s = 5.5f;
    builder.AddTriangleMesh(Quad(Point3f(0, 0, 0), Point3f(s, 0, 0), Point3f(s, 0, s), Point3f(0, 0, s)), white);
    builder.AddTriangleMesh(Quad(Point3f(0, s, 0), Point3f(0, s, s), Point3f(s, s, s), Point3f(s, s, 0)), white);
    builder.AddTriangleMesh(Quad(Point3f(0, 0, s), Point3f(s, 0, s), Point3f(s, s, s), Point3f(0, s, s)), white);
    builder.AddTriangleMesh(Quad(Point3f(s, 0, 0), Point3f(s, s, 0), Point3f(s, s, s), Point3f(s, 0, s)), red);
    builder.AddTriangleMesh(Quad(Point3f(0, 0, 0), Point3f(0, 0, s), Point3f(0, s, s), Point3f(0, s, 0)), green);
    builder.AddTriangleMesh(Cuboid(1.85f, 1.69f, Vector3f(1.65f, 1.65f, 1.65f), -18), boxes);
    builder.AddTriangleMesh(Cuboid(3.68f, 3.51f, Vector3f(1.65f, 3.3f, 1.65f), 15), boxes);
    // The light faces down (toward -y): its triangles wind clockwise seen from below.
    const Float y = s - 0.01f;
    builder.AddTriangleMesh(Quad(Point3f(2.13f, y, 2.27f), Point3f(3.43f, y, 2.27f),
                                 Point3f(3.43f, y, 3.32f), Point3f(2.13f, y, 3.32f)),
                            white, RGBAreaLight(17, 12, 4));
    builder.SetIntegrator(options);
    return builder.Build();
}

}  // namespace pbrt::testscenes
