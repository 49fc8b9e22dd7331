#include "pbrt_ext/cameras.h"

#include <cstdio>
#include <utility>

namespace pbrt {

Bounds2f DefaultScreenWindow(Point2i fullResolution) {
    Float frame = Float(fullResolution.x) / Float(fullResolution.y);
    if (frame > 1) return Bounds2f(Point2f(-frame, -1), Point2f(frame, 1));
    return Bounds2f(Point2f(-1, -1 / frame), Point2f(1, 1 / frame));
}

ProjectiveCamera::ProjectiveCamera(CameraMotion worldFromCamera, Point2i fullResolution,
                                   Transform screenFromCamera, Bounds2f screenWindow, Float lensRadius,
                                   Float focalDistance)
    : worldFromCamera(std::move(worldFromCamera)), screenFromCamera(screenFromCamera), lensRadius(lensRadius),
      focalDistance(focalDistance) {
    // Screen window -> NDC with the top-left corner at the origin (y in [-1, 0]), then -> pixels
    // with y flipped, since raster y runs down.
    Transform NDCFromScreen =
        Scale(1 / (screenWindow.pMax.x - screenWindow.pMin.x), 1 / (screenWindow.pMax.y - screenWindow.pMin.y), 1) *
        Translate(Vector3f(-screenWindow.pMin.x, -screenWindow.pMax.y, 0));
    Transform rasterFromNDC = Scale(Float(fullResolution.x), -Float(fullResolution.y), 1);
    rasterFromScreen = rasterFromNDC * NDCFromScreen;
    screenFromRaster = Inverse(rasterFromScreen);
    cameraFromRaster = Inverse(screenFromCamera) * screenFromRaster;
}

PerspectiveCamera::PerspectiveCamera(CameraMotion worldFromCamera, Point2i fullResolution,
                                     Bounds2f screenWindow, Float fov, Float lensRadius,
                                     Float focalDistance)
    : ProjectiveCamera(std::move(worldFromCamera), fullResolution, Perspective(fov, 1e-2f, 1000.f), screenWindow,
                       lensRadius, focalDistance),
      fov(fov) {}

std::string PerspectiveCamera::ToString() const {
    char buf[160];
    std::snprintf(buf, sizeof(buf), "[ PerspectiveCamera fov: %g lensRadius: %g focalDistance: %g ]", fov,
                  lensRadius, focalDistance);
    return buf;
}

OrthographicCamera::OrthographicCamera(CameraMotion worldFromCamera, Point2i fullResolution,
                                       Bounds2f screenWindow, Float lensRadius, Float focalDistance)
    : ProjectiveCamera(std::move(worldFromCamera), fullResolution, Orthographic(0, 1), screenWindow, lensRadius,
                       focalDistance) {}

std::string OrthographicCamera::ToString() const {
    char buf[160];
    std::snprintf(buf, sizeof(buf), "[ OrthographicCamera lensRadius: %g focalDistance: %g ]", lensRadius,
                  focalDistance);
    return buf;
}

std::string SphericalCamera::ToString() const {
    return std::string("[ SphericalCamera mapping: ") +
           (mapping == Mapping::EqualArea ? "equalarea" : "equirectangular") + " ]";
}

}  // namespace pbrt
