// pbrt-v4's --pixelstats: per pixel of the film's pixel bounds (row-major, (0, 0) at pMin), the
// milliseconds its samples took and the rays they traced, summed over waves
// (RenderOptions::pixelStatistics). A pixel belongs to one tile, which one thread renders at a
// time, so no two threads add to an entry at once.
#pragma once

#include "pbrt_ext/util/bounds.h"

#include <cstdint>
#include <vector>

namespace pbrt {

struct PixelStatistics {
    explicit PixelStatistics(const Bounds2i &pixels)
        : pixels(pixels), milliseconds(size_t(pixels.Area())), rays(size_t(pixels.Area())) {}
    void Add(Point2i p, double ms, int64_t nRays) {
        size_t i = size_t(p.y - pixels.pMin.y) * size_t(pixels.pMax.x - pixels.pMin.x) +
                   size_t(p.x - pixels.pMin.x);
        milliseconds[i] += ms;
        rays[i] += double(nRays);
    }
    Bounds2i pixels;
    std::vector<double> milliseconds, rays;
};

}  // namespace pbrt
