#include "pbrt_ext/cmd/pixelmaterial.h"

#include "pbrt_ext/scene.h"

#include <fmt/format.h>

#include <stdexcept>

namespace pbrt {

namespace {

template <typename T>
std::string Triple(const T &v) {
    return fmt::format("[ {}, {}, {} ]", v.x, v.y, v.z);
}

// Hits past this many are not followed (a ray caught between coincident surfaces).
constexpr int kMaxDepth = 100;

}  // namespace

void PrintPixelMaterial(const Scene &scene, Point2i pixel, std::ostream &out) {
    const Point2i res = scene.film.FullResolution();
    if (pixel.x < 0 || pixel.y < 0 || pixel.x >= res.x || pixel.y >= res.y)
        throw std::runtime_error(fmt::format("--pixelmaterial: pixel ({}, {}) is outside the {} x {} film",
                                             pixel.x, pixel.y, res.x, res.y));
    // The pixel's centre, the lens's centre, mid-shutter, as pbrt-v4 takes them.
    CameraSample cs;
    cs.pFilm = Point2f(pixel.x + 0.5f, pixel.y + 0.5f);
    cs.time = 0.5f;
    cs.pLens = Point2f(0.5f, 0.5f);
    pstd::optional<CameraRayDifferential> cr = scene.GenerateCameraRay(cs, 1);
    if (!cr)
        throw std::runtime_error(fmt::format("--pixelmaterial: the camera makes no ray at pixel ({}, {})",
                                             pixel.x, pixel.y));
    Ray ray = cr->ray;
    for (int depth = 1; depth <= kMaxDepth; ++depth) {
        pstd::optional<ShapeIntersection> hit = scene.Intersect(ray);
        if (!hit) {
            if (depth == 1)
                throw std::runtime_error(fmt::format("--pixelmaterial: no geometry is visible at pixel ({}, {})",
                                                     pixel.x, pixel.y));
            return;
        }
        const SurfaceInteraction &si = hit->intr;
        out << "Intersection depth " << depth << "\n"
            << "World-space p: " << Triple(si.p) << "\n"
            << "World-space n: " << Triple(si.n) << "\n"
            << "World-space ns: " << Triple(si.shading.n) << "\n"
            << "Distance from camera: " << Distance(si.p, cr->ray.o) << "\n";
        const int resolved = scene.ResolveMaterial(si);
        if (si.materialIndex < 0)
            out << "No material: an interface between media\n";
        else if (resolved != si.materialIndex)
            out << "Material: " << scene.materialDescriptions[size_t(resolved)] << ", chosen here by "
                << scene.materialDescriptions[size_t(si.materialIndex)] << "\n";
        else
            out << "Material: " << scene.materialDescriptions[size_t(resolved)] << "\n";
        out << "\n";
        ray = si.SpawnRay(ray.d);
    }
}

}  // namespace pbrt
