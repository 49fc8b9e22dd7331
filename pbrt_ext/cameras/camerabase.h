// What every camera shares (pbrt-v4's CameraBase, CameraSample, CameraRay): the sample a ray
// is generated from, the camera's motion over its shutter interval, and the rays it returns.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/util/animatedtransform.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/transform.h"
#include "pbrt_ext/util/vecmath.h"

namespace pbrt {

// pFilm in raster coordinates of the full resolution; pLens and time in [0, 1).
struct CameraSample {
    Point2f pFilm;
    Point2f pLens;
    Float time = 0;
    Float filterWeight = 1;
};

// Where the camera is while its shutter is open (pbrt-v4's CameraTransform with the shutter of
// CameraBaseParameters): a ray's time is drawn uniformly over [shutterOpen, shutterClose], and a
// moving camera is placed where it is at that time.
class CameraMotion {
  public:
    CameraMotion(const Transform &worldFromCamera) : worldFromCamera(worldFromCamera) {}
    CameraMotion(const AnimatedTransform &worldFromCamera, Float shutterOpen, Float shutterClose)
        : worldFromCamera(worldFromCamera), shutterOpen(shutterOpen), shutterClose(shutterClose) {}

    // The camera-space ray r, given the time u picks, in world space.
    Ray ToWorld(Ray r, Float u) const {
        r.time = Lerp(u, shutterOpen, shutterClose);
        return worldFromCamera(r);
    }
    // At the shutter's opening, and at a ray's time.
    const Transform &Start() const { return worldFromCamera.Start(); }
    Transform At(Float time) const { return worldFromCamera.Interpolate(time); }
    bool IsAnimated() const { return worldFromCamera.IsAnimated(); }

  private:
    AnimatedTransform worldFromCamera;
    Float shutterOpen = 0, shutterClose = 1;
};

struct CameraRay {
    Ray ray;
    SampledSpectrum weight = SampledSpectrum(1);
};

struct CameraRayDifferential {
    RayDifferential ray;
    SampledSpectrum weight = SampledSpectrum(1);
};

}  // namespace pbrt
