// A camera that traces each ray through a lens system (pbrt-v4's RealisticCamera, after Kolb,
// Mitchell and Hanrahan 1995): spherical element interfaces and an aperture stop, described
// from the scene side to the film, as pbrt-v4's lens files list them.
//
// Lens-system space has the film at z = 0 and the scene toward -z (camera space mirrored in
// z), so element positions read as in the lens designs. The film is a physical sensor of the
// given diagonal behind the lens; a ray's weight is the sensor's measurement of radiance,
// cos^4(theta) / (pdf z^2) over the exit pupil, so images are as bright as the lens makes them.
#pragma once

#include "pbrt_ext/cameras/camerabase.h"
#include "pbrt_ext/images/image.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/pstd.h"

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace pbrt {

// One row of a lens description, in metres.
struct LensElementInterface {
    Float curvatureRadius = 0;  // 0 marks the aperture stop; positive: centre toward the film
    Float thickness = 0;        // along the axis to the next interface (the last: to the film)
    Float eta = 0;              // index of refraction behind it, toward the film (0: air)
    Float apertureRadius = 0;
};

// A lens description's numbers (pbrt-v4's lens files: per interface from the scene side, its
// curvature radius, thickness, index of refraction and aperture diameter, in millimetres; a
// radius of 0 is the aperture stop) as interfaces in metres. The stop takes stopDiameter (mm)
// where the lens allows it; *clamped tells where it does not. Throws std::invalid_argument for
// a count that is not 4 per interface, more than kMaxLensInterfaces interfaces, or a negative
// thickness or index or a diameter that is not positive.
inline constexpr size_t kMaxLensInterfaces = 256;  // the pupil search traces 2^26 rays through each
inline constexpr const char *kLensDescriptionFormat =
    "rows of curvature radius, thickness, index of refraction and aperture diameter (mm)";
std::vector<LensElementInterface> LensFromDescription(std::span<const double> values,
                                                      Float stopDiameter, bool *clamped);

// The aperture stop's shape: a transmission over the square [-1, 1]^2 of the stop's radius,
// scaled to pass as much light as the full circle (pbrt-v4's aperture images).
class ApertureShape {
  public:
    // pbrt-v4's built-in diaphragms "gaussian", "square", "pentagon" and "star"; nullopt for
    // another name, which is an image file.
    static std::optional<ApertureShape> BuiltIn(const std::string &name);
    // The image's channel average, its first row at the stop's +y; throws std::runtime_error
    // where the file cannot be read or lets no light through.
    static ApertureShape FromImage(const std::string &path);

    Float Transmission(Point2f pStop) const;  // pStop in [-1, 1]^2

  private:
    explicit ApertureShape(Image image);
    Image image;  // its channels equal
};

// The cardinal points of a thick lens along the axis (lens-system z): the principal plane and
// the focal point on each side.
struct ThickLens {
    Float pzFilm = 0, fzFilm = 0;    // of rays entering parallel from the scene
    Float pzScene = 0, fzScene = 0;  // of rays leaving the film parallel
    Float FocalLength() const { return fzFilm - pzFilm; }
};

class RealisticCamera {
  public:
    // elements from the scene side; the last one's thickness is replaced by the distance that
    // focuses the lens at focusDistance (metres from the film). Throws std::invalid_argument
    // where no ray passes the lens or it cannot focus that close. pupilSamples: the rays per
    // ring of the film that find its exit pupil (pbrt-v4's 2^20; tests take fewer).
    RealisticCamera(CameraMotion worldFromCamera, Point2i fullResolution, Float filmDiagonal,
                    std::vector<LensElementInterface> elements, Float focusDistance,
                    std::optional<ApertureShape> aperture = {}, int pupilSamples = 1 << 20);

    static constexpr const char *Name() { return "realistic"; }
    pstd::optional<CameraRay> GenerateRay(CameraSample sample) const;
    const Transform &WorldFromCamera() const { return worldFromCamera.Start(); }
    const CameraMotion &Motion() const { return worldFromCamera; }
    std::string ToString() const;

    // A camera-space ray from the film through the lens (or from the scene back through it):
    // its weight (0 where it is blocked or totally reflected, else 1 or the aperture shape's
    // transmission) and the ray leaving the lens.
    Float TraceLensesFromFilm(const Ray &rCamera, Ray *rOut) const;
    Float TraceLensesFromScene(const Ray &rCamera, Ray *rOut) const;
    ThickLens ThickLensApproximation() const;
    // The tabulated bounds for a film point at distance r from the centre.
    Bounds2f ExitPupilBounds(Float r) const;
    Float LensRearZ() const { return elements.back().thickness; }
    Float LensFrontZ() const;
    Float RearElementRadius() const { return elements.back().apertureRadius; }

  private:
    Float FocusThickLens(Float focusDistance) const;
    Bounds2f RearPlaneSquare() const;
    std::vector<Point2f> RearPlanePoints(int n) const;
    // The bounds on the rear element's plane that hold every ray from film points at distances
    // [r0, r1] from the centre along +x that passes the lens (pbrt-v4's BoundExitPupil), found
    // by rays to RearPlanePoints.
    Bounds2f BoundExitPupil(Float r0, Float r1, std::span<const Point2f> rearPoints) const;

    CameraMotion worldFromCamera;
    Point2i fullResolution;
    Float filmDiagonal;
    Bounds2f physicalExtent;
    std::vector<LensElementInterface> elements;
    std::optional<ApertureShape> aperture;
    std::vector<Bounds2f> exitPupilBounds;
};

}  // namespace pbrt
