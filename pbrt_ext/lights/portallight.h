// An environment seen through a window (pbrt-v4's PortalImageInfiniteLight): an equal-area
// environment map that reaches the scene only through a rectangular portal, sampled over the
// part of the sky each point sees through it.
//
// The map is resampled once into the portal's rectified parameterization: (u, v) are the angles
// of a direction in the portal's frame (x, y along its sides, z its normal toward the sky), each
// over (-pi/2, pi/2) and mapped to [0, 1]. Seen from a point, the portal covers an axis-aligned
// rectangle of (u, v), so sampling the image within that rectangle (util/summedareatable.h) puts
// every sample through the portal. As in pbrt-v4, the light is infinite (escaping rays that
// leave through the portal see it, all others see nothing) and its portal is in world space.
#pragma once

#include "pbrt_ext/images/image.h"
#include "pbrt_ext/interaction.h"
#include "pbrt_ext/lights/lightbounds.h"
#include "pbrt_ext/lights/lightsample.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/summedareatable.h"
#include "pbrt_ext/util/transform.h"
#include "pbrt_ext/util/vecmath.h"

#include <array>
#include <string>

namespace pbrt {

class RGBColorSpace;

class PortalImageInfiniteLight {
  public:
    // portal: the rectangle's corners in order (world space); PortalFrameError says whether they
    // make one. The light's direction +z faces away from the scene through the portal.
    PortalImageInfiniteLight(const Transform &worldFromLight, const Image &equalAreaImage, Float scale,
                             const RGBColorSpace *colorSpace, const std::array<Point3f, 4> &portal);

    // Why four points do not make a portal (a planar rectangle), or empty.
    static std::string PortalFrameError(const std::array<Point3f, 4> &portal);

    LightType Type() const { return LightType::Infinite; }
    void Preprocess(const Bounds3f &sceneBounds);
    SampledSpectrum Phi(const SampledWavelengths &lambda) const;
    // As the whole environment's: the portal only lowers it.
    UnboundedLightImportance Importance(bool) const { return {Pi * scale * meanChannel, {}}; }
    pstd::optional<LightLiSample> SampleLi(LightSampleContext ctx, Point2f u,
                                           const SampledWavelengths &lambda,
                                           bool allowIncompletePDF = false) const;
    Float PDF_Li(LightSampleContext ctx, Vector3f wi, bool allowIncompletePDF = false) const;
    pstd::optional<LightLeSample> SampleLe(Point2f u1, Point2f u2, const SampledWavelengths &lambda,
                                           Float time) const;
    LightLePDF PDF_Le(const Ray &ray) const;
    SampledSpectrum Le(const Ray &ray, const SampledWavelengths &lambda) const;
    std::string ToString() const;

  private:
    // The rectified (u, v) of a world direction, and d(omega)/d(u,v) there; none for directions
    // that do not point out of the portal's front.
    pstd::optional<Point2f> ImageFromWorld(Vector3f w, Float *dwduv = nullptr) const;
    Vector3f WorldFromImage(Point2f uv, Float *dwduv = nullptr) const;
    // The rectangle of (u, v) that p sees through the portal.
    pstd::optional<Bounds2f> ImageBounds(Point3f p) const;
    SampledSpectrum ImageLookup(Point2f uv, const SampledWavelengths &lambda) const;
    Float Area() const { return Length(portal[1] - portal[0]) * Length(portal[3] - portal[0]); }

    std::array<Point3f, 4> portal;
    Frame portalFrame;
    Image image;  // rectified, float RGB
    const RGBColorSpace *colorSpace;
    Float scale;
    WindowedPiecewiseConstant2D distribution;
    Point3f sceneCenter;
    Float sceneRadius = 0;
    Float meanChannel;  // the environment's, over all pixels and channels
};

}  // namespace pbrt
