#include "pbrt_ext/cameras/cameras.h"

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
      fov(fov) {
    dxCamera = cameraFromRaster(Point3f(1, 0, 0)) - cameraFromRaster(Point3f(0, 0, 0));
    dyCamera = cameraFromRaster(Point3f(0, 1, 0)) - cameraFromRaster(Point3f(0, 0, 0));
}

pstd::optional<CameraRayDifferential> PerspectiveCamera::GenerateRayDifferential(CameraSample sample) const {
    Vector3f pCamera(cameraFromRaster(Point3f(sample.pFilm.x, sample.pFilm.y, 0)));
    RayDifferential rd(RayThrough(pCamera, sample));
    Ray rx = RayThrough(pCamera + dxCamera, sample), ry = RayThrough(pCamera + dyCamera, sample);
    rd.rxOrigin = rx.o;
    rd.rxDirection = rx.d;
    rd.ryOrigin = ry.o;
    rd.ryDirection = ry.d;
    rd.hasDifferentials = true;
    return CameraRayDifferential{rd};
}

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

pstd::optional<CameraRayDifferential> Camera::GenerateRayDifferential(CameraSample sample) const {
    return std::visit([&](const auto &c) {
        if constexpr (requires { c.GenerateRayDifferential(sample); })
            return c.GenerateRayDifferential(sample);
        else
            return ApproximateRayDifferential(sample);
    }, camera);
}

pstd::optional<CameraRayDifferential> Camera::ApproximateRayDifferential(CameraSample sample) const {
    pstd::optional<CameraRay> cr = GenerateRay(sample);
    if (!cr)
        return {};
    RayDifferential rd(cr->ray);
    auto neighbour = [&](int axis, Point3f *origin, Vector3f *direction) {
        for (Float eps : {.05f, -.05f}) {
            CameraSample shifted = sample;
            shifted.pFilm[axis] += eps;
            if (pstd::optional<CameraRay> r = GenerateRay(shifted)) {
                *origin = rd.o + (r->ray.o - rd.o) / eps;
                *direction = rd.d + (r->ray.d - rd.d) / eps;
                return true;
            }
        }
        return false;
    };
    bool x = neighbour(0, &rd.rxOrigin, &rd.rxDirection);
    bool y = neighbour(1, &rd.ryOrigin, &rd.ryDirection);
    rd.hasDifferentials = x && y;
    return CameraRayDifferential{rd, cr->weight};
}

CameraDifferentials::CameraDifferentials(const Camera &camera, Point2i fullResolution) {
    Vector3f inf(Infinity, Infinity, Infinity);
    minPosDifferentialX = minPosDifferentialY = minDirDifferentialX = minDirDifferentialY = inf;
    CameraSample sample;
    sample.pLens = Point2f(0.5f, 0.5f);
    sample.time = 0.5f;
    constexpr int n = 512;  // along the film's diagonal, as pbrt-v4
    for (int i = 0; i < n; ++i) {
        sample.pFilm = Point2f(Float(i) / (n - 1) * fullResolution.x,
                               Float(i) / (n - 1) * fullResolution.y);
        pstd::optional<CameraRayDifferential> crd = camera.GenerateRayDifferential(sample);
        if (!crd)
            continue;
        const RayDifferential &ray = crd->ray;
        Transform cameraFromWorld = Inverse(camera.WorldFromCamera(ray.time));
        auto keepShorter = [](Vector3f v, Vector3f *min) {
            if (Length(v) < Length(*min))
                *min = v;
        };
        keepShorter(cameraFromWorld(ray.rxOrigin - ray.o), &minPosDifferentialX);
        keepShorter(cameraFromWorld(ray.ryOrigin - ray.o), &minPosDifferentialY);
        Frame f = Frame::FromZ(Normalize(ray.d));
        Vector3f df = f.ToLocal(Normalize(ray.d));
        keepShorter(Normalize(f.ToLocal(Normalize(ray.rxDirection))) - df, &minDirDifferentialX);
        keepShorter(Normalize(f.ToLocal(Normalize(ray.ryDirection))) - df, &minDirDifferentialY);
    }
}

// The point and normal turned so that the camera looks at p straight down +z; the two
// approximate neighbour rays from the camera meet the tangent plane there, and their offsets
// from p, turned back, are dp/dx and dp/dy.
void CameraDifferentials::Approximate_dp_dxy(const Camera &camera, Point3f p, Normal3f n,
                                             Float time, int samplesPerPixel, Vector3f *dpdx,
                                             Vector3f *dpdy) const {
    Transform worldFromCamera = camera.WorldFromCamera(time);
    Point3f pCamera = worldFromCamera.ApplyInverse(p);
    Transform downZFromCamera = RotateFromTo(Normalize(Vector3f(pCamera)), Vector3f(0, 0, 1));
    Point3f pDownZ = downZFromCamera(pCamera);
    Normal3f nDownZ = downZFromCamera(worldFromCamera.ApplyInverse(n));
    Float d = nDownZ.z * pDownZ.z;
    auto meet = [&](Vector3f posDifferential, Vector3f dirDifferential) {
        Ray r(Point3f(0, 0, 0) + posDifferential, Vector3f(0, 0, 1) + dirDifferential);
        Float t = -(Dot(nDownZ, Vector3f(r.o)) - d) / Dot(nDownZ, r.d);
        return r(t);
    };
    Point3f px = meet(minPosDifferentialX, minDirDifferentialX);
    Point3f py = meet(minPosDifferentialY, minDirDifferentialY);
    Float scale = RayDifferentialScale(samplesPerPixel);
    *dpdx = scale * worldFromCamera(downZFromCamera.ApplyInverse(px - pDownZ));
    *dpdy = scale * worldFromCamera(downZFromCamera.ApplyInverse(py - pDownZ));
}

}  // namespace pbrt
