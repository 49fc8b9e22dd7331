// The lens target: a lens description (pbrt-v4's .dat lens files) read by ReadFloatFile and
// LensFromDescription, made into a RealisticCamera focused at 2 m (its exit pupils from 256 rays
// a ring instead of 2^20, for speed), and 64 camera rays generated across the film. A lens that
// cannot focus or pass light is refused with std::invalid_argument; any ray it gives must be
// finite, unit length, and weighted by a finite non-negative weight.
#include "fuzz/finding.h"
#include "fuzz/fuzz_targets.h"
#include "fuzz/scratch.h"

#include "pbrt_ext/cameras/realisticcamera.h"
#include "pbrt_ext/util/floatfile.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace pbrt::fuzz {

namespace {

void CheckRays(const RealisticCamera &camera) {
    for (int i = 0; i < 64; ++i) {
        CameraSample sample;
        sample.pFilm = Point2f(8 * ((i % 8) + 0.5f) / 8, 8 * ((i / 8) + 0.5f) / 8);
        sample.pLens = Point2f((i * 37 % 64 + 0.5f) / 64, (i * 11 % 64 + 0.5f) / 64);
        pstd::optional<CameraRay> cr = camera.GenerateRay(sample);
        if (!cr) continue;
        const Ray &r = cr->ray;
        Float w = cr->weight[0];
        bool finite = std::isfinite(r.o.x) && std::isfinite(r.o.y) && std::isfinite(r.o.z) &&
                      std::isfinite(r.d.x) && std::isfinite(r.d.y) && std::isfinite(r.d.z);
        if (!finite || std::abs(Length(r.d) - 1) > 1e-3f || !std::isfinite(w) || w < 0)
            ReportFinding("lens", "a camera ray that is not finite, not unit length, or weighted " +
                                      std::to_string(w));
    }
}

}  // namespace

void FuzzLens(std::span<const uint8_t> data) {
    std::string path = WriteScratchFile("lens", "lens.dat", data);
    ExpectReadOrRejection("lens", [&] {
        std::vector<double> values = ReadFloatFile(path, FileLoc{path, 1, 1}, "lens file", kLensDescriptionFormat);
        try {
            bool clamped;
            std::vector<LensElementInterface> lens = LensFromDescription(values, 5, &clamped);
            RealisticCamera camera(Transform(), Point2i(8, 8), 0.035f, std::move(lens), 2, {}, 256);
            CheckRays(camera);
        } catch (const std::invalid_argument &) {
            // the promised refusal of a lens that is malformed, blocks all light or cannot focus
        }
    });
}

}  // namespace pbrt::fuzz
