// Rendering a scene: tiles over all cores (TBB), a progress bar, final statistics (pbrt-v4's
// ImageTileIntegrator::Render, reduced to one pass over the pixels with all their samples).
#pragma once

#include <cstdint>
#include <string>

namespace pbrt {

class Scene;

struct RenderOptions {
    int nThreads = 0;  // 0: all cores
    bool quiet = false;
};

struct RenderStatistics {
    double seconds = 0;
    int64_t cameraSamples = 0;
    int64_t closestRays = 0, shadowRays = 0;
    int64_t discardedSamples = 0;  // radiance NaN or infinite: counted, never written

    double CameraSamplesPerSecond() const { return cameraSamples / seconds; }
    double RaysPerSecond() const { return (closestRays + shadowRays) / seconds; }
    std::string ToString() const;
};

// Renders every pixel of the scene's film with all its samples; the film accumulates the result.
RenderStatistics Render(Scene &scene, const RenderOptions &options);

}  // namespace pbrt
