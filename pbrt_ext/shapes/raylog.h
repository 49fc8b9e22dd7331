// The rays of a render, recorded for the traversal-limit benchmark (benchmarks/traversal_bench):
// while a log is attached to the aggregate (EmbreeAggregate::SetRayLog), every query it answers
// is kept, closest-hit and shadow alike, so that Embree alone can later trace the same rays.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/ray.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <vector>

namespace pbrt {

struct LoggedRay {
    Ray ray;
    Float tMax = Infinity;
    bool shadow = false;  // an occlusion query (IntersectP) rather than a closest hit
};

// Lock-free, so that recording does not serialize the render's threads: each query claims a
// slot of storage allocated up front. Queries beyond the capacity are counted but not kept.
class RayLog {
  public:
    explicit RayLog(size_t capacity) : slots(capacity) {}

    void Add(const Ray &ray, Float tMax, bool shadow) {
        size_t i = next.fetch_add(1, std::memory_order_relaxed);
        if (i < slots.size())
            slots[i] = {ray, tMax, shadow};
    }
    // The rays kept, in no particular order across threads. Call once the render is done.
    std::vector<LoggedRay> Rays() const {
        size_t n = std::min(next.load(), slots.size());
        return {slots.begin(), slots.begin() + std::ptrdiff_t(n)};
    }
    size_t Queries() const { return next.load(); }

  private:
    std::vector<LoggedRay> slots;
    std::atomic<size_t> next{0};
};

}  // namespace pbrt
