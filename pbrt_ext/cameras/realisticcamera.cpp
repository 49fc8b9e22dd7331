#include "pbrt_ext/cameras/realisticcamera.h"

#include "pbrt_ext/util/lowdiscrepancy.h"
#include "pbrt_ext/util/scattering.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <span>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace pbrt {

namespace {

// Lens-system space is camera space mirrored in z.
Ray MirrorZ(const Ray &r) {
    return Ray(Point3f(r.o.x, r.o.y, -r.o.z), Vector3f(r.d.x, r.d.y, -r.d.z), r.medium, r.time);
}

// Air where a lens file leaves the index 0 (the stop's row).
Float IndexOf(Float eta) { return eta != 0 ? eta : 1; }

// The ray's hit with the sphere of the element (radius, centred on the axis at zCenter) on the
// side the element uses: the nearer root where the ray travels toward the sphere's convex side.
// The quadratic is solved in double: lens rays graze elements at their rims.
bool IntersectSphericalElement(Float radius, Float zCenter, const Ray &ray, Float *t,
                               Normal3f *n) {
    double ox = ray.o.x, oy = ray.o.y, oz = double(ray.o.z) - zCenter;
    double dx = ray.d.x, dy = ray.d.y, dz = ray.d.z;
    double a = dx * dx + dy * dy + dz * dz, b = 2 * (dx * ox + dy * oy + dz * oz);
    double c = ox * ox + oy * oy + oz * oz - double(radius) * radius;
    double discriminant = b * b - 4 * a * c;
    if (a == 0 || discriminant < 0) return false;
    double q = b < 0 ? -0.5 * (b - std::sqrt(discriminant)) : -0.5 * (b + std::sqrt(discriminant));
    if (q == 0) return false;
    double t0 = q / a, t1 = c / q;
    if (t0 > t1) std::swap(t0, t1);
    bool useCloserT = (ray.d.z > 0) != (radius < 0);
    double tHit = useCloserT ? t0 : t1;
    if (tHit < 0) return false;
    *t = Float(tHit);
    Vector3f p(Float(ox + tHit * dx), Float(oy + tHit * dy), Float(oz + tHit * dz));
    *n = FaceForward(Normalize(Normal3f(p)), -ray.d);
    return true;
}

// Where the ray meets the element's interface at elementZ along the axis: the stop's plane or
// the element's sphere, with the sphere's normal facing the ray.
bool IntersectElement(const LensElementInterface &element, Float elementZ, const Ray &ray,
                      Point3f *pHit, Normal3f *n) {
    Float t;
    if (element.curvatureRadius == 0) {
        t = (elementZ - ray.o.z) / ray.d.z;
        if (!(t >= 0)) return false;
    } else if (!IntersectSphericalElement(element.curvatureRadius,
                                          elementZ + element.curvatureRadius, ray, &t, n)) {
        return false;
    }
    *pHit = ray(t);
    return true;
}

// The ray continued from pHit: through the stop unchanged, refracted from index etaI into etaT
// at a lens surface of normal n; false on total internal reflection.
bool PassInterface(const LensElementInterface &element, Point3f pHit, Normal3f n, Float etaI,
                   Float etaT, Ray *ray) {
    ray->o = pHit;
    if (element.curvatureRadius == 0) return true;
    Vector3f w;
    if (!Refract(Normalize(-ray->d), n, etaT / etaI, nullptr, &w)) return false;
    ray->d = w;
    return true;
}

// Where a ray leaving the lens parallel to the axis (rIn) crosses it (the focal point) and
// where it meets rIn's line (the principal plane), as lens-system z.
void CardinalPoints(const Ray &rIn, const Ray &rOut, Float *pz, Float *fz) {
    Float tf = -rOut.o.x / rOut.d.x;
    *fz = -rOut(tf).z;
    Float tp = (rIn.o.x - rOut.o.x) / rOut.d.x;
    *pz = -rOut(tp).z;
}

// Pixel (x, y) of a res x res image holds shape(u, v) at its centre, with v up the image's
// rows from the bottom: the orientation pbrt-v4's aperture images have once flipped.
Image Rasterize(int res, const std::function<Float(Point2f)> &shape) {
    Image image(Point2i(res, res));
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x)
            image.SetChannel(Point2i(x, y), 0,
                             shape(Point2f(-1 + 2 * (x + 0.5f) / res, 1 - 2 * (y + 0.5f) / res)));
    return image;
}

// Inside the simple polygon (even-odd rule, which the nonzero one equals for it).
bool InsidePolygon(Point2f p, std::span<const Point2f> vertices) {
    bool inside = false;
    for (size_t i = 0, j = vertices.size() - 1; i < vertices.size(); j = i++) {
        Point2f a = vertices[i], b = vertices[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y))
            inside = !inside;
    }
    return inside;
}

Image Polygon(std::span<const Point2f> vertices) {
    return Rasterize(256, [&](Point2f p) { return InsidePolygon(p, vertices) ? 1.f : 0.f; });
}

}  // namespace

std::vector<LensElementInterface> LensFromDescription(std::span<const double> values,
                                                      Float stopDiameter, bool *clamped) {
    if (values.empty() || values.size() % 4 != 0)
        throw std::invalid_argument(
            fmt::format("has {} values, expected {}", values.size(), kLensDescriptionFormat));
    if (values.size() / 4 > kMaxLensInterfaces)
        throw std::invalid_argument(fmt::format("has {} element interfaces; expected at most {} "
                                                "(lens designs have a few dozen)",
                                                values.size() / 4, kMaxLensInterfaces));
    *clamped = false;
    std::vector<LensElementInterface> lens;
    for (size_t i = 0; i < values.size(); i += 4) {
        Float radius = Float(values[i]), thickness = Float(values[i + 1]),
              eta = Float(values[i + 2]), diameter = Float(values[i + 3]);
        if (thickness < 0 || eta < 0 || !(diameter > 0))
            throw std::invalid_argument(fmt::format(
                "row {}: thickness {}, index {}, diameter {}; expected a thickness and an index of "
                "at least 0 and a positive diameter", i / 4 + 1, thickness, eta, diameter));
        if (radius == 0 && stopDiameter > diameter)
            *clamped = true;
        else if (radius == 0)
            diameter = stopDiameter;
        lens.push_back({radius / 1000, thickness / 1000, eta, diameter / 2000});
    }
    return lens;
}

ApertureShape::ApertureShape(Image shape) : image(std::move(shape)) {
    Point2i res = image.Resolution();
    double sum = 0;
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x) sum += image.GetChannel(Point2i(x, y), 0);
    if (!(sum > 0)) throw std::runtime_error("the aperture image lets no light through");
    // A circle of the stop's radius covers pi/4 of its square.
    Float scale = Float((Pi / 4) / (sum / (double(res.x) * res.y)));
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x)
            image.SetChannel(Point2i(x, y), 0, image.GetChannel(Point2i(x, y), 0) * scale);
}

std::optional<ApertureShape> ApertureShape::BuiltIn(const std::string &name) {
    if (name == "gaussian")
        return ApertureShape(Rasterize(256, [](Point2f p) {
            return std::max<Float>(0, std::exp(-(Sqr(p.x) + Sqr(p.y))) - std::exp(-1.f));
        }));
    if (name == "square")
        return ApertureShape(Rasterize(256, [](Point2f p) {
            return std::abs(p.x) < 0.5f && std::abs(p.y) < 0.5f ? 1.f : 0.f;
        }));
    if (name == "pentagon") {  // a regular pentagon, a vertex up, at 0.8 of the stop
        std::vector<Point2f> vertices;
        for (int i = 0; i < 5; ++i)
            vertices.push_back(0.8f * Point2f(std::sin(2 * Pi * i / 5), std::cos(2 * Pi * i / 5)));
        return ApertureShape(Polygon(vertices));
    }
    if (name == "star") {  // five points at the stop's rim, the inner vertices on their pentagon
        std::vector<Point2f> vertices;
        Float inner = std::cos(Radians(72.f)) / std::cos(Radians(36.f));
        for (int i = 0; i < 10; ++i) {
            Float r = (i & 1) ? 1.f : inner;
            vertices.push_back(Point2f(r * std::cos(Pi * i / 5), r * std::sin(Pi * i / 5)));
        }
        return ApertureShape(Polygon(vertices));
    }
    return std::nullopt;
}

ApertureShape ApertureShape::FromImage(const std::string &path) {
    Image file = Image::Read(path);
    Point2i res = file.Resolution();
    Image shape(res);
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x) {
            RGB rgb = file.GetChannels(Point2i(x, res.y - 1 - y));
            shape.SetChannel(Point2i(x, y), 0, (rgb.r + rgb.g + rgb.b) / 3);
        }
    return ApertureShape(std::move(shape));
}

Float ApertureShape::Transmission(Point2f pStop) const {
    return image.BilerpChannel(Point2f((pStop.x + 1) / 2, (pStop.y + 1) / 2), 0, WrapMode::Black);
}

RealisticCamera::RealisticCamera(CameraMotion worldFromCamera, Point2i fullResolution,
                                 Float filmDiagonal, std::vector<LensElementInterface> lens,
                                 Float focusDistance, std::optional<ApertureShape> aperture,
                                 int pupilSamples)
    : worldFromCamera(std::move(worldFromCamera)), fullResolution(fullResolution),
      filmDiagonal(filmDiagonal), elements(std::move(lens)), aperture(std::move(aperture)) {
    if (elements.empty()) throw std::invalid_argument("the lens has no elements");
    // The film's physical extent: the diagonal at the image's aspect ratio.
    Float aspect = Float(fullResolution.y) / Float(fullResolution.x);
    Float x = std::sqrt(Sqr(filmDiagonal) / (1 + Sqr(aspect))), y = aspect * x;
    physicalExtent = Bounds2f(Point2f(-x / 2, -y / 2), Point2f(x / 2, y / 2));

    elements.back().thickness = FocusThickLens(focusDistance);

    // Exit pupils of 64 rings of the film, as pbrt-v4 tabulates them. Every ring tries the
    // same points of the rear element's plane, computed once.
    std::vector<Point2f> rearPoints = RearPlanePoints(pupilSamples);
    exitPupilBounds.resize(64);
    tbb::parallel_for(0, int(exitPupilBounds.size()), [&](int i) {
        Float r0 = Float(i) / exitPupilBounds.size() * filmDiagonal / 2;
        Float r1 = Float(i + 1) / exitPupilBounds.size() * filmDiagonal / 2;
        exitPupilBounds[size_t(i)] = BoundExitPupil(r0, r1, rearPoints);
    });
}

Bounds2f RealisticCamera::RearPlaneSquare() const {
    Float r = 1.5f * RearElementRadius();
    return Bounds2f(Point2f(-r, -r), Point2f(r, r));
}

// The square 1.5 times the rear element's radius, covered by the first n points of the 2D
// Halton sequence.
std::vector<Point2f> RealisticCamera::RearPlanePoints(int n) const {
    Bounds2f square = RearPlaneSquare();
    std::vector<Point2f> points(size_t(std::max(n, 0)));
    tbb::parallel_for(0, n, [&](int i) {
        points[size_t(i)] = square.Lerp(Point2f(RadicalInverse(0, uint64_t(i)), RadicalInverse(1, uint64_t(i))));
    });
    return points;
}

Float RealisticCamera::LensFrontZ() const {
    Float z = 0;
    for (const LensElementInterface &element : elements) z += element.thickness;
    return z;
}

Float RealisticCamera::TraceLensesFromFilm(const Ray &rCamera, Ray *rOut) const {
    Float elementZ = 0, weight = 1;
    Ray rLens = MirrorZ(rCamera);
    for (int i = int(elements.size()) - 1; i >= 0; --i) {
        const LensElementInterface &element = elements[size_t(i)];
        elementZ -= element.thickness;
        Point3f pHit;
        Normal3f n;
        if (!IntersectElement(element, elementZ, rLens, &pHit, &n)) return 0;
        if (element.curvatureRadius == 0 && aperture) {
            weight = aperture->Transmission(
                Point2f(pHit.x / element.apertureRadius, pHit.y / element.apertureRadius));
            if (weight == 0) return 0;
        } else if (Sqr(pHit.x) + Sqr(pHit.y) > Sqr(element.apertureRadius)) {
            return 0;
        }
        // Into the glass (or air) in front of this interface, toward the scene.
        Float etaT = i > 0 ? IndexOf(elements[size_t(i - 1)].eta) : 1;
        if (!PassInterface(element, pHit, n, IndexOf(element.eta), etaT, &rLens)) return 0;
    }
    if (rOut) *rOut = MirrorZ(rLens);
    return weight;
}

// The aperture shape is not applied here, as in pbrt-v4: only the focus uses this direction.
Float RealisticCamera::TraceLensesFromScene(const Ray &rCamera, Ray *rOut) const {
    Float elementZ = -LensFrontZ();
    Ray rLens = MirrorZ(rCamera);
    for (size_t i = 0; i < elements.size(); ++i) {
        const LensElementInterface &element = elements[i];
        Point3f pHit;
        Normal3f n;
        if (!IntersectElement(element, elementZ, rLens, &pHit, &n) ||
            Sqr(pHit.x) + Sqr(pHit.y) > Sqr(element.apertureRadius))
            return 0;
        Float etaI = i > 0 ? IndexOf(elements[i - 1].eta) : 1;
        if (!PassInterface(element, pHit, n, etaI, IndexOf(element.eta), &rLens)) return 0;
        elementZ += element.thickness;
    }
    if (rOut) *rOut = MirrorZ(rLens);
    return 1;
}

// Rays parallel to the axis, a thousandth of the film's diagonal off it, traced both ways.
ThickLens RealisticCamera::ThickLensApproximation() const {
    Float x = .001f * filmDiagonal;
    ThickLens lens;
    Ray rScene(Point3f(x, 0, LensFrontZ() + 1), Vector3f(0, 0, -1)), rFilm;
    if (TraceLensesFromScene(rScene, &rFilm) == 0)
        throw std::invalid_argument("no ray parallel to the axis passes the lens from the scene "
                                    "to the film; is the aperture stop too small?");
    CardinalPoints(rScene, rFilm, &lens.pzFilm, &lens.fzFilm);
    rFilm = Ray(Point3f(x, 0, LensRearZ() - 1), Vector3f(0, 0, 1));
    if (TraceLensesFromFilm(rFilm, &rScene) == 0)
        throw std::invalid_argument("no ray parallel to the axis passes the lens from the film "
                                    "to the scene; is the aperture stop too small?");
    CardinalPoints(rFilm, rScene, &lens.pzScene, &lens.fzScene);
    return lens;
}

// The film's distance from the rear element that images the plane focusDistance in front of
// the film sharply, by the thick lens's equation (pbrt-v4's FocusThickLens).
Float RealisticCamera::FocusThickLens(Float focusDistance) const {
    ThickLens lens = ThickLensApproximation();
    Float f = lens.FocalLength(), z = -focusDistance;
    Float c = (lens.pzScene - z - lens.pzFilm) * (lens.pzScene - z - 4 * f - lens.pzFilm);
    if (!(c > 0)) {
        std::ostringstream message;
        message << "the lens (focal length " << f * 1000 << " mm) cannot focus at "
                << focusDistance << " m; expected a focus distance beyond four focal lengths";
        throw std::invalid_argument(message.str());
    }
    Float delta = (lens.pzScene - z + lens.pzFilm - std::sqrt(c)) / 2;
    return elements.back().thickness + delta;
}

// Points of the film segment paired with the rear plane's points; the bounds of those whose ray
// passes, widened by the points' spacing.
Bounds2f RealisticCamera::BoundExitPupil(Float r0, Float r1, std::span<const Point2f> rearPoints) const {
    size_t n = rearPoints.size();
    Bounds2f pupil;
    for (size_t i = 0; i < n; ++i) {
        Point3f pFilm(Lerp((i + 0.5f) / n, r0, r1), 0, 0);
        Point2f pRear = rearPoints[i];
        if (!Inside(pRear, pupil) &&
            TraceLensesFromFilm(Ray(pFilm, Point3f(pRear.x, pRear.y, LensRearZ()) - pFilm), nullptr) != 0)
            pupil = Union(pupil, pRear);
    }
    if (pupil.IsDegenerate()) return pupil;
    return Expand(pupil, 2 * Length(RearPlaneSquare().Diagonal()) / std::sqrt(Float(n)));
}

Bounds2f RealisticCamera::ExitPupilBounds(Float r) const {
    size_t i = size_t(r / (filmDiagonal / 2) * exitPupilBounds.size());
    return exitPupilBounds[std::min(i, exitPupilBounds.size() - 1)];
}

// A point of the film (mirrored in x: the lens turns the image), a point of its ring's exit
// pupil bounds turned to the point's angle, and the ray between them traced through the lens.
pstd::optional<CameraRay> RealisticCamera::GenerateRay(CameraSample sample) const {
    Point2f s(sample.pFilm.x / fullResolution.x, sample.pFilm.y / fullResolution.y);
    Point2f pFilm2 = physicalExtent.Lerp(s);
    Point3f pFilm(-pFilm2.x, pFilm2.y, 0);
    Float rFilm = std::sqrt(Sqr(pFilm.x) + Sqr(pFilm.y));
    Bounds2f pupil = ExitPupilBounds(rFilm);
    if (pupil.IsDegenerate()) return {};
    Point2f pLens = pupil.Lerp(sample.pLens);
    Float pdf = 1 / pupil.Area();
    Float sinTheta = rFilm != 0 ? pFilm.y / rFilm : 0, cosTheta = rFilm != 0 ? pFilm.x / rFilm : 1;
    Point3f pPupil(cosTheta * pLens.x - sinTheta * pLens.y, sinTheta * pLens.x + cosTheta * pLens.y,
                   LensRearZ());
    Ray fromFilm(pFilm, pPupil - pFilm), ray;
    Float weight = TraceLensesFromFilm(fromFilm, &ray);
    if (weight == 0) return {};
    ray = worldFromCamera.ToWorld(ray, sample.time);
    ray.d = Normalize(ray.d);
    Float cosFilm = Normalize(fromFilm.d).z;
    weight *= Sqr(Sqr(cosFilm)) / (pdf * Sqr(LensRearZ()));
    return CameraRay{ray, SampledSpectrum(weight)};
}

std::string RealisticCamera::ToString() const {
    std::ostringstream s;
    s << "[ RealisticCamera filmDiagonal: " << filmDiagonal << " elements: " << elements.size()
      << " rearZ: " << LensRearZ() << " frontZ: " << LensFrontZ()
      << " aperture: " << (aperture ? "shaped" : "circular") << " ]";
    return s.str();
}

}  // namespace pbrt
