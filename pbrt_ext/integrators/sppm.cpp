#include "pbrt_ext/integrators/sppm.h"

#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/lights/lightsamplers.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/lowdiscrepancy.h"
#include "pbrt_ext/util/progressreporter.h"
#include "pbrt_ext/util/sampling.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

namespace pbrt {

namespace {

// What a pixel gathers over the iterations (pbrt-v4's SPPMPixel), in the sensor's RGB.
struct SPPMPixel {
    Float radius = 0;
    RGB Ld{0, 0, 0};  // light found by the camera paths, summed over iterations
    // This iteration's visible point: where the camera path met a diffuse surface, with the
    // path's throughput beta (zero: none).
    struct VisiblePoint {
        Point3f p;
        Vector3f wo;
        std::optional<BSDF> bsdf;
        SampledSpectrum beta{0.f};
        bool secondaryLambdaTerminated = false;
    } vp;
    std::atomic<double> Phi[3] = {0, 0, 0};  // this iteration's photon flux at the visible point
    std::atomic<int> m{0};                    // this iteration's photons there
    RGB tau{0, 0, 0};                         // flux within the radius, over all iterations
    Float n = 0;                              // photons kept, over all iterations
};

// The visible points' grid: cells of the largest search radius over their bounds, hashed into
// as many buckets as there are pixels, each listing the pixels whose search sphere overlaps a
// cell that hashes to it (compressed rows: bucket b's pixels are entries[offsets[b]] to
// entries[offsets[b + 1]], in pixel order).
class VisiblePointGrid {
  public:
    VisiblePointGrid(const std::vector<SPPMPixel> &pixels) : hashSize(pixels.size()) {
        Float maxRadius = 0;
        for (const SPPMPixel &pixel : pixels)
            if (pixel.vp.beta) {
                bounds = Union(bounds, Expand(Bounds3f(pixel.vp.p), pixel.radius));
                maxRadius = std::max(maxRadius, pixel.radius);
            }
        if (maxRadius == 0)
            return;
        Vector3f diagonal = bounds.Diagonal();
        Float maxDiagonal = std::max({diagonal.x, diagonal.y, diagonal.z});
        int baseRes = int(std::min<Float>(maxDiagonal / maxRadius, 1 << 20));
        for (int i = 0; i < 3; ++i)
            resolution[i] = std::max(int(baseRes * diagonal[i] / maxDiagonal), 1);
        // Hashing the cells is most of the work (eight or more per visible point, every
        // iteration): it runs in parallel, into each pixel's own range of cellBuckets.
        std::vector<uint32_t> firstCell(pixels.size() + 1, 0);
        ParallelOverPixels(pixels, [&](size_t i) { firstCell[i + 1] = CellCount(pixels[i]); });
        for (size_t i = 0; i < pixels.size(); ++i)
            firstCell[i + 1] += firstCell[i];
        std::vector<uint32_t> cellBuckets(firstCell.back());
        ParallelOverPixels(pixels, [&](size_t i) {
            uint32_t k = firstCell[i];
            ForEachCell(pixels[i], [&](Point3i cell) { cellBuckets[k++] = Bucket(cell); });
        });
        // Counting sort of the (bucket, pixel) pairs by bucket.
        offsets.assign(hashSize + 1, 0);
        for (uint32_t bucket : cellBuckets)
            ++offsets[bucket + 1];
        for (size_t b = 0; b < hashSize; ++b)
            offsets[b + 1] += offsets[b];
        entries.resize(offsets[hashSize]);
        std::vector<uint32_t> cursor(offsets.begin(), offsets.end() - 1);
        for (size_t i = 0; i < pixels.size(); ++i)
            for (uint32_t k = firstCell[i]; k < firstCell[i + 1]; ++k)
                entries[cursor[cellBuckets[k]]++] = uint32_t(i);
    }

    // Calls f(pixel index) for every visible point whose cell p is in (more may be listed than
    // are near p: the caller checks the distance).
    template <typename F>
    void ForEachNear(Point3f p, F f) const {
        Point3i cell;
        if (offsets.empty() || !ToGrid(p, &cell))
            return;
        size_t bucket = Bucket(cell);
        for (uint32_t i = offsets[bucket]; i < offsets[bucket + 1]; ++i)
            f(entries[i]);
    }

  private:
    // The cell of p, clamped to the grid; whether p was inside it.
    bool ToGrid(Point3f p, Point3i *cell) const {
        Vector3f o = bounds.Offset(p);
        bool inside = true;
        for (int i = 0; i < 3; ++i) {
            int c = int(resolution[i] * o[i]);
            inside &= c >= 0 && c < resolution[i];
            (*cell)[i] = Clamp(c, 0, resolution[i] - 1);
        }
        return inside;
    }
    // The hash scaled to [0, hashSize) by a multiplication (Lemire's range reduction) instead of
    // a 64-bit division.
    size_t Bucket(Point3i cell) const {
        return size_t((Hash(cell.x, cell.y, cell.z) >> 32) * hashSize >> 32);  // hashSize < 2^32
    }
    // The cells a pixel's search sphere overlaps (none without a visible point): their corners.
    bool CellRange(const SPPMPixel &pixel, Point3i *pMin, Point3i *pMax) const {
        if (!pixel.vp.beta)
            return false;
        Vector3f r(pixel.radius, pixel.radius, pixel.radius);
        ToGrid(pixel.vp.p - r, pMin);
        ToGrid(pixel.vp.p + r, pMax);
        return true;
    }
    uint32_t CellCount(const SPPMPixel &pixel) const {
        Point3i pMin, pMax;
        if (!CellRange(pixel, &pMin, &pMax))
            return 0;
        Vector3i extent = pMax - pMin + Vector3i(1, 1, 1);
        return uint32_t(extent.x) * uint32_t(extent.y) * uint32_t(extent.z);
    }
    template <typename F>
    void ForEachCell(const SPPMPixel &pixel, F f) const {
        Point3i pMin, pMax;
        if (!CellRange(pixel, &pMin, &pMax))
            return;
        for (int z = pMin.z; z <= pMax.z; ++z)
            for (int y = pMin.y; y <= pMax.y; ++y)
                for (int x = pMin.x; x <= pMax.x; ++x)
                    f(Point3i(x, y, z));
    }
    template <typename F>
    static void ParallelOverPixels(const std::vector<SPPMPixel> &pixels, F f) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels.size(), 256),
                          [&](const tbb::blocked_range<size_t> &range) {
                              for (size_t i = range.begin(); i < range.end(); ++i)
                                  f(i);
                          });
    }

    size_t hashSize;
    Bounds3f bounds;
    int resolution[3] = {1, 1, 1};
    std::vector<uint32_t> offsets, entries;
};

class SPPM {
  public:
    SPPM(Scene &scene, const RenderOptions &renderOptions)
        : scene(scene), options(scene.integratorOptions), renderOptions(renderOptions),
          directLight(scene, IntegratorOptions{}),
          pixelBounds(scene.film.PixelBounds()), pixels(size_t(pixelBounds.Area())),
          shootLightSampler(scene.lights), permutations(uint32_t(options.photonSeed)) {
        photonsPerIteration = options.photonsPerIteration > 0 ? options.photonsPerIteration
                                                              : int64_t(pixelBounds.Area());
        for (SPPMPixel &pixel : pixels)
            pixel.radius = options.initialRadius;
    }

    RenderStatistics Render();

  private:
    void TraceCameraPaths(int iteration, const SampledWavelengths &lambda);
    void TraceCameraPath(Point2i pPixel, int iteration, SampledWavelengths lambda, Sampler &sampler,
                         RayCounts &rays);
    void TracePhotons(int iteration, const SampledWavelengths &lambda, const VisiblePointGrid &grid);
    void TracePhoton(uint64_t haltonIndex, SampledWavelengths lambda, const VisiblePointGrid &grid,
                     RayCounts &rays);
    void UpdatePixels();
    // Emission Le reached by a camera path after a bounce with BSDF density pdfBSDF from prevCtx,
    // weighted against light sampling.
    SampledSpectrum WeightedEmission(SampledSpectrum Le, int lightIndex, bool countFully,
                                     const LightSampleContext &prevCtx, Vector3f w, Float pdfBSDF) const;
    RGB SensorRGB(const SampledSpectrum &L, const SampledWavelengths &lambda) const {
        return scene.film.Sensor().ToSensorRGB(L, lambda);
    }
    SPPMPixel &PixelAt(Point2i p) {
        Vector2i o = p - pixelBounds.pMin;
        return pixels[size_t(o.y) * size_t(pixelBounds.pMax.x - pixelBounds.pMin.x) + size_t(o.x)];
    }

    Scene &scene;
    const IntegratorOptions &options;
    const RenderOptions &renderOptions;
    // Direct light at the camera paths' vertices: the path tracer's, by MIS (pbrt-v4's
    // SPPMIntegrator::SampleLd is the same estimator).
    PathIntegrator directLight;
    Bounds2i pixelBounds;
    std::vector<SPPMPixel> pixels;
    PowerLightSampler shootLightSampler;
    HaltonDigitPermutations permutations;
    int64_t photonsPerIteration;
    tbb::enumerable_thread_specific<RayCounts> rayCounts;
};

SampledSpectrum SPPM::WeightedEmission(SampledSpectrum Le, int lightIndex, bool countFully,
                                       const LightSampleContext &prevCtx, Vector3f w,
                                       Float pdfBSDF) const {
    if (!Le || countFully)
        return Le;
    const Light &light = scene.lights[lightIndex];
    Float pdfLight = scene.lightSampler.PMF(prevCtx, lightIndex) * light.PDF_Li(prevCtx, w, true);
    return PowerHeuristic(1, pdfBSDF, 1, pdfLight) * Le;
}

void SPPM::TraceCameraPath(Point2i pPixel, int iteration, SampledWavelengths lambda,
                           Sampler &sampler, RayCounts &rays) {
    sampler.StartPixelSample(pPixel, iteration);
    CameraSample cs = GetCameraSample(sampler, pPixel, scene.film.GetFilter(), false,
                                      scene.switches.pixelJitter);
    // pbrt-v4 scales SPPM's differentials by 1/sqrt(iterations), without the 1/8 floor.
    pstd::optional<CameraRayDifferential> cr =
        scene.GenerateCameraRay(cs, 1 / std::sqrt(Float(scene.sampler.SamplesPerPixel())));
    if (!cr || !cr->weight)
        return;
    RayDifferential ray = cr->ray;
    SampledSpectrum beta = cr->weight, L(0.f);
    SPPMPixel &pixel = PixelAt(pPixel);
    Float etaScale = 1, pdfBSDF = 1;
    bool specularBounce = true, haveVisiblePoint = false;
    LightSampleContext prevCtx;
    for (int depth = 0;;) {
        ++rays.closest;
        pstd::optional<ShapeIntersection> hit = scene.Intersect(ray);
        if (!hit) {
            for (int index : scene.infiniteLights)
                L += beta * WeightedEmission(scene.lights[index].Le(ray, lambda), index,
                                             depth == 0 || specularBounce, prevCtx, ray.d, pdfBSDF);
            break;
        }
        SurfaceInteraction &si = hit->intr;
        scene.ComputeDifferentials(si, ray);
        std::optional<BSDF> bsdf = scene.GetBSDF(si, lambda);
        if (!bsdf) {
            ray = RayDifferential(si.SpawnRay(ray.d));  // an interface: media are ignored
            continue;
        }
        if (si.areaLightIndex >= 0)
            L += beta * WeightedEmission(scene.lights[si.areaLightIndex].L(si.p, si.n, si.uv, -ray.d, lambda),
                                         si.areaLightIndex, depth == 0 || specularBounce, prevCtx,
                                         ray.d, pdfBSDF);
        // The path goes one bounce past its visible point: what BSDF sampling finds of the
        // lights there is the other half of its direct light's MIS.
        if (depth++ == options.maxDepth || haveVisiblePoint)
            break;
        L += beta * directLight.SampleLd(si, *bsdf, lambda, sampler, rays);
        // The first diffuse surface (or a glossy one at the last bounce) keeps the photons.
        BxDFFlags flags = bsdf->Flags();
        if (IsDiffuse(flags) || (IsGlossy(flags) && depth == options.maxDepth)) {
            pixel.vp = {si.p, si.wo, *bsdf, beta, lambda.SecondaryTerminated()};
            haveVisiblePoint = true;
        }
        Float u = sampler.Get1D();
        pstd::optional<BSDFSample> bs = bsdf->Sample_f(si.wo, u, sampler.Get2D());
        if (!bs)
            break;
        specularBounce = bs->IsSpecular();
        if (bs->IsTransmission())
            etaScale *= Sqr(bs->eta);
        beta *= bs->f * AbsDot(bs->wi, Vector3f(si.shading.n)) / bs->pdf;
        pdfBSDF = bs->pdfIsProportional ? bsdf->PDF(si.wo, bs->wi) : bs->pdf;
        SampledSpectrum rrBeta = beta * etaScale;
        if (rrBeta.MaxComponentValue() < 1) {
            Float q = std::max<Float>(0.05f, 1 - rrBeta.MaxComponentValue());
            if (sampler.Get1D() < q)
                break;
            beta /= 1 - q;
        }
        prevCtx = LightSampleContext(si);
        ray = si.SpawnRay(ray, bs->wi, bs->flags, bs->eta);
    }
    pixel.Ld += SensorRGB(L, lambda);
}

void SPPM::TraceCameraPaths(int iteration, const SampledWavelengths &lambda) {
    tbb::parallel_for(tbb::blocked_range<int>(pixelBounds.pMin.y, pixelBounds.pMax.y),
                      [&](const tbb::blocked_range<int> &rows) {
                          Sampler sampler = scene.sampler;
                          RayCounts &rays = rayCounts.local();
                          for (int y = rows.begin(); y < rows.end(); ++y)
                              for (int x = pixelBounds.pMin.x; x < pixelBounds.pMax.x; ++x)
                                  TraceCameraPath(Point2i(x, y), iteration, lambda, sampler, rays);
                      });
}

void SPPM::TracePhoton(uint64_t haltonIndex, SampledWavelengths lambda, const VisiblePointGrid &grid,
                       RayCounts &rays) {
    // The photon's dimensions are the consecutive bases of a scrambled Halton sequence.
    int dimension = 0;
    auto get1D = [&] {
        return ScrambledRadicalInverse(dimension++ % kPrimeTableSize, haltonIndex, permutations);
    };
    auto get2D = [&] {
        Float u0 = get1D();
        return Point2f(u0, get1D());
    };
    pstd::optional<SampledLight> sampled = shootLightSampler.Sample(get1D());
    if (!sampled)
        return;
    const Light &light = scene.lights[sampled->lightIndex];
    Point2f u0 = get2D(), u1 = get2D();
    pstd::optional<LightLeSample> les = light.SampleLe(u0, u1, lambda, 0);
    if (!les || les->pdfPos == 0 || les->pdfDir == 0 || !les->L)
        return;
    SampledSpectrum beta = les->L * les->AbsCosTheta(les->ray.d) / (sampled->p * les->pdfPos * les->pdfDir);
    RayDifferential ray(les->ray);
    for (int depth = 0; depth < options.maxDepth && beta; ++depth) {
        ++rays.closest;
        pstd::optional<ShapeIntersection> hit = scene.Intersect(ray);
        if (!hit)
            break;
        SurfaceInteraction &si = hit->intr;
        // Direct light is the camera paths' (SampleLd): photons count from their second hit.
        if (depth > 0)
            grid.ForEachNear(si.p, [&](int index) {
                SPPMPixel &pixel = pixels[size_t(index)];
                if (DistanceSquared(pixel.vp.p, si.p) > Sqr(pixel.radius))
                    return;
                SampledWavelengths photonLambda = lambda;
                if (pixel.vp.secondaryLambdaTerminated)
                    photonLambda.TerminateSecondary();
                SampledSpectrum Phi = pixel.vp.beta * beta * pixel.vp.bsdf->f(pixel.vp.wo, -ray.d);
                RGB rgb = SensorRGB(Phi, photonLambda);
                for (int c = 0; c < 3; ++c)
                    pixel.Phi[c].fetch_add(rgb[c], std::memory_order_relaxed);
                pixel.m.fetch_add(1, std::memory_order_relaxed);
            });
        scene.ComputeDifferentials(si, ray);
        std::optional<BSDF> bsdf = scene.GetBSDF(si, lambda);
        if (!bsdf) {
            ray = RayDifferential(si.SpawnRay(ray.d));
            --depth;
            continue;
        }
        Float u = get1D();
        pstd::optional<BSDFSample> bs = bsdf->Sample_f(si.wo, u, get2D(), TransportMode::Importance);
        if (!bs)
            break;
        SampledSpectrum betaNew = beta * bs->f * AbsDot(bs->wi, Vector3f(si.shading.n)) / bs->pdf;
        // Russian roulette by how much the bounce keeps.
        Float q = std::max<Float>(0, 1 - betaNew.MaxComponentValue() / beta.MaxComponentValue());
        if (get1D() < q)
            break;
        beta = betaNew / (1 - q);
        ray = RayDifferential(si.SpawnRay(bs->wi));
    }
}

void SPPM::TracePhotons(int iteration, const SampledWavelengths &lambda, const VisiblePointGrid &grid) {
    const uint64_t first = uint64_t(iteration) * uint64_t(photonsPerIteration);
    tbb::parallel_for(tbb::blocked_range<int64_t>(0, photonsPerIteration, 1024),
                      [&](const tbb::blocked_range<int64_t> &range) {
                          RayCounts &rays = rayCounts.local();
                          for (int64_t i = range.begin(); i < range.end(); ++i)
                              TracePhoton(first + uint64_t(i), lambda, grid, rays);
                      });
}

void SPPM::UpdatePixels() {
    tbb::parallel_for(size_t(0), pixels.size(), [&](size_t i) {
        SPPMPixel &p = pixels[i];
        if (int m = p.m.load(std::memory_order_relaxed); m > 0) {
            // Keep 2/3 of the new photons; the radius shrinks to hold that many.
            const Float gamma = Float(2) / 3;
            Float nNew = p.n + gamma * m;
            Float rNew = p.radius * std::sqrt(nNew / (p.n + m));
            RGB Phi(Float(p.Phi[0].load()), Float(p.Phi[1].load()), Float(p.Phi[2].load()));
            p.tau = (p.tau + Phi) * Sqr(rNew) / Sqr(p.radius);
            p.n = nNew;
            p.radius = rNew;
            p.m = 0;
            for (std::atomic<double> &phi : p.Phi)
                phi = 0;
        }
        p.vp.beta = SampledSpectrum(0.f);
        p.vp.bsdf.reset();
    });
}

RenderStatistics SPPM::Render() {
    const int iterations = scene.sampler.SamplesPerPixel();
    ProgressReporter progress(2 * int64_t(iterations), "Rendering", renderOptions.quiet);
    int done = 0;
    for (int iteration = 0; iteration < iterations; ++iteration) {
        // One set of wavelengths per iteration, so that photons and visible points share them.
        SampledWavelengths lambda = scene.SampleWavelengths(RadicalInverse(1, uint64_t(iteration)));
        TraceCameraPaths(iteration, lambda);
        progress.Update();
        VisiblePointGrid grid(pixels);
        TracePhotons(iteration, lambda, grid);
        progress.Update();
        UpdatePixels();
        done = iteration + 1;
        bool cancelled = renderOptions.Cancelled();
        bool timeUp = renderOptions.timeLimitSeconds > 0 &&
                      progress.ElapsedSeconds() >= renderOptions.timeLimitSeconds;
        if (cancelled || timeUp)
            break;
    }
    progress.Done();
    // Each pixel: the camera paths' light per iteration, plus the photons' flux within the
    // radius over the photons shot and the disk's area.
    const double photons = double(done) * double(photonsPerIteration);
    for (Point2i p : pixelBounds) {
        const SPPMPixel &pixel = PixelAt(p);
        RGB L = pixel.Ld / Float(done) + pixel.tau / Float(photons * Pi * Sqr(pixel.radius));
        scene.film.AddSensorRGB(p, L, 1);
    }
    RenderStatistics stats;
    stats.seconds = progress.ElapsedSeconds();
    stats.cameraSamples = int64_t(done) * pixelBounds.Area();
    stats.samplesPerPixel = stats.maxSamplesPerPixel = done;
    stats.cancelled = done < iterations && renderOptions.Cancelled();
    for (const RayCounts &r : rayCounts) {
        stats.closestRays += r.closest;
        stats.shadowRays += r.shadow;
    }
    return stats;
}

}  // namespace

RenderStatistics RenderSPPM(Scene &scene, const RenderOptions &options) {
    return SPPM(scene, options).Render();
}

}  // namespace pbrt
