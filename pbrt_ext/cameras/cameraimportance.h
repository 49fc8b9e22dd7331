// The camera seen from the scene (pbrt-v4's PerspectiveCamera::We, PDF_We and SampleWi): the
// importance a ray leaving the lens carries, the densities with which camera rays are drawn, and
// the sampling of a lens point toward a point of the scene, for paths traced from the lights
// (bdpt, lightpath). As in pbrt-v4, only the perspective camera has it.
//
// Importance is normalized over the film's full resolution, at z = 1 of camera space (area A),
// and over the lens (area pi r^2, or 1 for a pinhole): camera rays through the film with the
// filter's footprint around the pixels (the film's sample bounds) carry importance; others none.
#pragma once

#include "pbrt_ext/cameras/cameras.h"
#include "pbrt_ext/film/film.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

namespace pbrt {

// A lens point that sees the reference point (pbrt-v4's CameraWiSample).
struct CameraWiSample {
    SampledSpectrum Wi;  // importance arriving at the reference point along -wi
    Vector3f wi;         // unit, from the reference point toward the lens
    Float pdf;           // of the lens point, per unit solid angle at the reference point
    Point2f pRaster;     // where the ray meets the film
    Point3f pLens;
    Normal3f nLens;      // the camera's viewing direction
};

struct CameraPDF {
    Float pos = 0, dir = 0;
};

class CameraImportance {
  public:
    // Throws std::invalid_argument for a camera other than the perspective one.
    CameraImportance(const Camera &camera, const RGBFilm &film);

    // The importance of ray (leaving the lens), and where it meets the film.
    SampledSpectrum We(const Ray &ray, Point2f *pRaster = nullptr) const;
    // The densities of ray's origin on the lens (per unit area) and of its direction (per unit
    // solid angle) among camera rays; zero for a ray that carries no importance.
    CameraPDF PDF_We(const Ray &ray) const;
    // A point on the lens seen from p at the time given, by u; none if the lens sees no film
    // position there.
    pstd::optional<CameraWiSample> SampleWi(Point3f p, Float time, Point2f u) const;

  private:
    // Where ray (from the lens) meets the film, if in front of the camera (cosTheta: its cosine
    // with the viewing direction).
    pstd::optional<Point2f> RasterPosition(const Ray &ray, Float *cosTheta) const;
    Transform WorldFromCamera(Float time) const { return motion.At(time); }
    Float LensArea() const { return lensRadius != 0 ? Pi * Sqr(lensRadius) : 1; }

    CameraMotion motion;
    Transform cameraFromRaster;
    Float lensRadius, focalDistance;
    Float A;              // the film's area at z = 1 of camera space
    Float cosTotalWidth;  // the cosine of the widest direction that can carry importance
    Bounds2f sampleBounds;
};

}  // namespace pbrt
