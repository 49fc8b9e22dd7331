// Cameras: rays and ray differentials from film positions (pbrt-v4's cameras.h, reduced to the
// perspective, orthographic and spherical cameras, without importance functions; the realistic
// camera is in realisticcamera.h).
//
// Spaces as in pbrt-v4: camera space looks down +z with +y up and +x to the right of the image;
// screen space is the image plane with the screen window's extent; raster space counts pixels of
// the full resolution from the top-left corner, y down. The render space is world space here,
// so cameras take worldFromCamera (the inverse of a scene file's LookAt/CTM, cameraFromWorld).
#pragma once

#include "pbrt_ext/cameras/camerabase.h"
#include "pbrt_ext/cameras/realisticcamera.h"
#include "pbrt_ext/film/filters.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/samplers/samplers.h"
#include "pbrt_ext/util/animatedtransform.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/equalarea.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/transform.h"
#include "pbrt_ext/util/vecmath.h"

#include <string>
#include <type_traits>
#include <utility>
#include <variant>

namespace pbrt {

// pbrt-v4's default screen window: [-1, 1] along the shorter image axis and the aspect ratio's
// extent along the longer, so that a perspective fov spans the shorter axis.
Bounds2f DefaultScreenWindow(Point2i fullResolution);

// The transformations shared by cameras defined by a projection (pbrt-v4's ProjectiveCamera),
// and the thin-lens model: a lens of lensRadius focused at focalDistance along +z.
class ProjectiveCamera {
  public:
    const Transform &WorldFromCamera() const { return worldFromCamera.Start(); }
    const CameraMotion &Motion() const { return worldFromCamera; }
    const Transform &CameraFromRaster() const { return cameraFromRaster; }
    Float LensRadius() const { return lensRadius; }
    Float FocalDistance() const { return focalDistance; }

  protected:
    ProjectiveCamera(CameraMotion worldFromCamera, Point2i fullResolution,
                     Transform screenFromCamera, Bounds2f screenWindow, Float lensRadius,
                     Float focalDistance);

    // The ray through pLens (on the lens disk) toward where the pinhole ray r reaches the plane
    // of focus, so that points on that plane stay sharp.
    PBRT_CPU_GPU Ray FocusThroughLens(Ray r, Point2f uLens) const {
        if (lensRadius <= 0) return r;
        Point2f pLens = SampleUniformDiskConcentric(uLens) * lensRadius;
        Point3f pFocus = r(focalDistance / r.d.z);
        Point3f o(r.o.x + pLens.x, r.o.y + pLens.y, r.o.z);
        return Ray(o, Normalize(pFocus - o));
    }

    CameraMotion worldFromCamera;
    Transform screenFromCamera, cameraFromRaster, rasterFromScreen, screenFromRaster;
    Float lensRadius, focalDistance;
};

// fov (degrees) spans the shorter image axis with the default screen window.
class PerspectiveCamera : public ProjectiveCamera {
  public:
    PerspectiveCamera(CameraMotion worldFromCamera, Point2i fullResolution, Bounds2f screenWindow,
                      Float fov, Float lensRadius = 0, Float focalDistance = 1e6f);

    static constexpr const char *Name() { return "perspective"; }
    PBRT_CPU_GPU pstd::optional<CameraRay> GenerateRay(CameraSample sample) const {
        return CameraRay{RayThrough(Vector3f(cameraFromRaster(Point3f(sample.pFilm.x, sample.pFilm.y, 0))), sample)};
    }
    // pbrt-v4's PerspectiveCamera::GenerateRayDifferential: the neighbours are the rays through
    // the film one pixel over in x and in y, through the same point of the lens, found from the
    // camera-space size of a pixel rather than by generating more camera rays.
    pstd::optional<CameraRayDifferential> GenerateRayDifferential(CameraSample sample) const;
    std::string ToString() const;

  private:
    // The world-space ray through camera-space film point pCamera and the sample's lens point.
    PBRT_CPU_GPU Ray RayThrough(Vector3f pCamera, const CameraSample &sample) const {
        Ray pinhole(Point3f(0, 0, 0), Normalize(pCamera));
        return worldFromCamera.ToWorld(FocusThroughLens(pinhole, sample.pLens), sample.time);
    }

    Float fov;
    Vector3f dxCamera, dyCamera;  // one pixel along raster x and y, in camera space
};

// Parallel rays along +z; the screen window is the visible extent in camera-space units.
class OrthographicCamera : public ProjectiveCamera {
  public:
    OrthographicCamera(CameraMotion worldFromCamera, Point2i fullResolution,
                       Bounds2f screenWindow, Float lensRadius = 0, Float focalDistance = 1e6f);

    static constexpr const char *Name() { return "orthographic"; }
    PBRT_CPU_GPU pstd::optional<CameraRay> GenerateRay(CameraSample sample) const {
        Point3f pCamera = cameraFromRaster(Point3f(sample.pFilm.x, sample.pFilm.y, 0));
        Ray r(pCamera, Vector3f(0, 0, 1));
        return CameraRay{worldFromCamera.ToWorld(FocusThroughLens(r, sample.pLens), sample.time)};
    }
    std::string ToString() const;
};

// Every direction around the camera (pbrt-v4's SphericalCamera): the film position, as a
// fraction of the resolution, mapped to the sphere by the equal-area octahedral square (each
// pixel the same solid angle) or the equirectangular map (longitude along x, latitude down y),
// then camera space's y and z exchanged, so that the image's up is the camera's +y.
class SphericalCamera {
  public:
    enum class Mapping { EqualArea, EquiRectangular };
    SphericalCamera(CameraMotion worldFromCamera, Point2i fullResolution, Mapping mapping)
        : worldFromCamera(std::move(worldFromCamera)), fullResolution(fullResolution),
          mapping(mapping) {}

    static constexpr const char *Name() { return "spherical"; }
    pstd::optional<CameraRay> GenerateRay(CameraSample sample) const {
        Point2f uv(sample.pFilm.x / fullResolution.x, sample.pFilm.y / fullResolution.y);
        Vector3f dir;
        if (mapping == Mapping::EquiRectangular) {
            Float theta = Pi * uv[1], phi = 2 * Pi * uv[0];
            dir = SphericalDirection(std::sin(theta), std::cos(theta), phi);
        } else {
            dir = EqualAreaSquareToSphere(WrapEqualAreaSquare(uv));
        }
        std::swap(dir.y, dir.z);
        return CameraRay{worldFromCamera.ToWorld(Ray(Point3f(0, 0, 0), dir), sample.time)};
    }
    const Transform &WorldFromCamera() const { return worldFromCamera.Start(); }
    const CameraMotion &Motion() const { return worldFromCamera; }
    std::string ToString() const;

  private:
    CameraMotion worldFromCamera;
    Point2i fullResolution;
    Mapping mapping;
};

// The closed set of cameras.
class Camera {
    using Variant = std::variant<PerspectiveCamera, OrthographicCamera, SphericalCamera,
                                 RealisticCamera>;

  public:
    template <typename C>
        requires std::is_constructible_v<Variant, C> && (!std::is_same_v<std::remove_cvref_t<C>, Camera>)
    Camera(C &&c) : camera(std::forward<C>(c)) {}

    pstd::optional<CameraRay> GenerateRay(CameraSample sample) const {
        return std::visit([&](const auto &c) { return c.GenerateRay(sample); }, camera);
    }
    // The camera's own ray differentials where it has them (the perspective camera, as in
    // pbrt-v4), else pbrt-v4's CameraBase::GenerateRayDifferential: the neighbours are the rays
    // a twentieth of a pixel over (or back, where that has none), extrapolated to a whole pixel.
    pstd::optional<CameraRayDifferential> GenerateRayDifferential(CameraSample sample) const;
    // The finite-difference differentials, for cameras without their own.
    pstd::optional<CameraRayDifferential> ApproximateRayDifferential(CameraSample sample) const;
    Transform WorldFromCamera(Float time) const {
        return std::visit([&](const auto &c) { return c.Motion().At(time); }, camera);
    }
    bool IsMoving() const {
        return std::visit([](const auto &c) { return c.Motion().IsAnimated(); }, camera);
    }
    const Transform &WorldFromCamera() const {
        return std::visit([](const auto &c) -> const Transform & { return c.WorldFromCamera(); }, camera);
    }
    const char *Name() const {
        return std::visit([](const auto &c) { return c.Name(); }, camera);
    }
    std::string ToString() const {
        return std::visit([](const auto &c) { return c.ToString(); }, camera);
    }
    template <typename T>
    const T *CastOrNullptr() const {
        return std::get_if<T>(&camera);
    }

  private:
    Variant camera;
};

// The smallest of the camera's ray differentials over its film, in camera space (pbrt-v4's
// CameraBase::FindMinimumDifferentials), which stand in for the differentials of rays that
// have none: Approximate_dp_dxy gives the footprint of a pixel at a point p of a surface with
// normal n as the film sees it, for rays from anywhere.
struct CameraDifferentials {
    CameraDifferentials() = default;
    CameraDifferentials(const Camera &camera, Point2i fullResolution);

    void Approximate_dp_dxy(const Camera &camera, Point3f p, Normal3f n, Float time,
                            int samplesPerPixel, Vector3f *dpdx, Vector3f *dpdy) const;

    Vector3f minPosDifferentialX, minPosDifferentialY, minDirDifferentialX, minDirDifferentialY;
};

// pbrt-v4's scale of a camera ray's differentials with the sample count: 1 / sqrt(spp), so
// that textures are filtered over the area each sample stands for, but at least 1/8.
inline Float RayDifferentialScale(int samplesPerPixel) {
    return std::max<Float>(0.125f, 1 / std::sqrt(Float(samplesPerPixel)));
}

// The camera sample for pixel pPixel (pbrt-v4's GetCameraSample): the film position is offset
// from the pixel center by a point drawn from the filter, whose weight the film applies; then
// the time and the lens position, in pbrt-v4's order of sample dimensions. The time takes its
// dimension only where something moves (`moving`): a still scene draws the samples it drew
// before motion blur existed, and pays nothing for it. Without `jitter` (pbrt-v4's
// --disable-pixel-jitter) the same dimensions are drawn, and the pixel centre, the lens centre and
// mid-shutter taken instead, with weight 1.
inline CameraSample GetCameraSample(Sampler &sampler, Point2i pPixel, const Filter &filter,
                                    bool moving = false, bool jitter = true) {
    FilterSample fs = filter.Sample(sampler.GetPixel2D());
    CameraSample cs;
    cs.pFilm = Point2f(pPixel.x + 0.5f + fs.p.x, pPixel.y + 0.5f + fs.p.y);
    if (moving)
        cs.time = sampler.Get1D();
    cs.pLens = sampler.Get2D();
    cs.filterWeight = fs.weight;
    if (!jitter) {
        cs.pFilm = Point2f(pPixel.x + 0.5f, pPixel.y + 0.5f);
        cs.time = 0.5f;
        cs.pLens = Point2f(0.5f, 0.5f);
        cs.filterWeight = 1;
    }
    return cs;
}

}  // namespace pbrt
