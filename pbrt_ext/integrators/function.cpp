#include "pbrt_ext/integrators/function.h"

#include "pbrt_ext/images/image.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/util/atomicfile.h"
#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/log.h"
#include "pbrt_ext/util/lowdiscrepancy.h"
#include "pbrt_ext/util/progressreporter.h"
#include "pbrt_ext/util/rng.h"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <fstream>
#include <numeric>
#include <stdexcept>

namespace pbrt {

namespace {

double Checkerboard(double x, double y) {
    constexpr int kFrequency = 10;
    int ix = int(x * kFrequency), iy = int(y * kFrequency);
    return ((ix & 1) ^ (iy & 1)) ? 2 : 0;
}

// The normal density of mean 0.5 and deviation 0.25 in x and in y, over its mass inside the
// unit square.
double Gaussian(Point2f p) {
    constexpr double mu = 0.5, sigma = 0.25;
    auto density = [](double x) {
        return std::exp(-Sqr(x - mu) / (2 * sigma * sigma)) / std::sqrt(2 * Pi * sigma * sigma);
    };
    static const double massInside = Sqr(std::erf((1 - mu) / (sigma * std::sqrt(2.0))));
    return density(p.x) * density(p.y) / massInside;
}

// pbrt-v4's choice of which counts a sampler's points are well distributed at.
bool WellDistributedAt(const Sampler &sampler, int n) {
    if (sampler.Get<StratifiedSampler>())
        return Sqr(int(std::sqrt(double(n)))) == n;
    if (sampler.Get<PaddedSobolSampler>())
        return (n & (n - 1)) == 0;
    if (sampler.Get<HaltonSampler>()) {
        int n2 = 0, n3 = 0;
        for (; n % 2 == 0; n /= 2) ++n2;
        for (; n % 3 == 0; n /= 3) ++n3;
        return n == 1 && n2 == n3;
    }
    return true;
}

// The 2D Halton point of index a, randomized per pixel as the Halton sampler randomizes.
Point2f HaltonPoint(const HaltonSampler &halton, uint64_t a, uint64_t pixelSeed) {
    Point2f u;
    for (int d = 0; d < 2; ++d) {
        uint32_t hash = uint32_t(Hash(pixelSeed, d));
        switch (halton.GetRandomizeStrategy()) {
        case RandomizeStrategy::PermuteDigits: {
            uint32_t base = uint32_t(kPrimes[size_t(d)]);
            u[d] = PermutedRadicalInverse(a, d, [&](int digitIndex, int digit, uint64_t) {
                return PermutationElement(uint32_t(digit), base, uint32_t(Hash(hash, digitIndex)));
            });
            break;
        }
        case RandomizeStrategy::Owen:
            u[d] = OwenScrambledRadicalInverse(d, a, hash);
            break;
        default:
            u[d] = RadicalInverse(d, a);
        }
    }
    return u;
}

// The 2D Sobol' point of index a, randomized per pixel as the padded Sobol' sampler randomizes,
// but unpermuted: the first 2^k indices are a (0, k, 2)-net.
Point2f SobolPoint(const PaddedSobolSampler &sobol, uint64_t a, uint64_t pixelSeed) {
    uint64_t hash = Hash(pixelSeed);
    return Point2f(SobolSample(a, 0, sobol.GetRandomizeStrategy(), uint32_t(hash)),
                   SobolSample(a, 1, sobol.GetRandomizeStrategy(), uint32_t(hash >> 32)));
}

// A fresh jittered grid of n points (as close to square as n's factors allow) per pixel.
double StratifiedEstimate(TestFunction f, int n, uint64_t pixelIndex) {
    int nx = int(std::sqrt(double(n)));
    while (n % nx != 0) --nx;
    int ny = n / nx;
    RNG rng(pixelIndex, MixBits(uint64_t(n)));
    double sum = 0;
    for (int x = 0; x < nx; ++x)
        for (int y = 0; y < ny; ++y)
            sum += EvaluateTestFunction(f, Point2f((x + rng.Uniform<Float>()) / Float(nx),
                                                   (y + rng.Uniform<Float>()) / Float(ny)));
    return sum / double(n);
}

void WriteFunctionImage(TestFunction f, const Bounds2i &pixels, const std::string &path) {
    Vector2i res = pixels.Diagonal();
    Image image(Point2i(res.x, res.y));
    RNG rng;
    constexpr int kSamples = 256;
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x) {
            double sum = 0;
            for (int i = 0; i < kSamples; ++i)
                sum += EvaluateTestFunction(f, Point2f((x + rng.Uniform<Float>()) / Float(res.x),
                                                       (y + rng.Uniform<Float>()) / Float(res.y)));
            for (int c = 0; c < 3; ++c) image.SetChannel(Point2i(x, y), c, Float(sum / kSamples));
        }
    image.Write(path);
}

}  // namespace

double EvaluateTestFunction(TestFunction f, Point2f p) {
    switch (f) {
    case TestFunction::Step:
        return p.x < 0.5f ? 2 : 0;
    case TestFunction::Diagonal:
        return p.x + p.y < 1 ? 2 : 0;
    case TestFunction::Disk:
        return Sqr(p.x - 0.5f) + Sqr(p.y - 0.5f) < Sqr(0.5f) ? 1 / (Pi * Sqr(0.5)) : 0;
    case TestFunction::Checkerboard:
        return Checkerboard(p.x, p.y);
    case TestFunction::RotatedCheckerboard: {
        // pbrt-v4's: the checkerboard turned 45 degrees, over the fraction of the square it covers.
        constexpr double kArea = 1.00006866455078125;
        const double s = std::sin(Radians(45.0)), c = std::cos(Radians(45.0));
        return Checkerboard(Float(10 + p.x * c - p.y * s), Float(10 + p.x * s + p.y * c)) / kArea;
    }
    case TestFunction::Gaussian:
        return Gaussian(p);
    }
    return 0;
}

std::vector<std::pair<int, double>> FunctionErrorTable(const Scene &scene, const RenderOptions &options) {
    const FunctionOptions &fo = scene.integratorOptions.function;
    const Bounds2i pixels = scene.film.PixelBounds();
    const int64_t nPixels = pixels.Area(), width = pixels.Diagonal().x;
    const int nSamples = scene.sampler.SamplesPerPixel();
    const HaltonSampler *halton = scene.sampler.Get<HaltonSampler>();
    const PaddedSobolSampler *sobol = scene.sampler.Get<PaddedSobolSampler>();
    const bool stratified = scene.sampler.Get<StratifiedSampler>() != nullptr;
    std::vector<double> sums(size_t(nPixels), 0);  // per pixel, the sum of f over its samples
    tbb::enumerable_thread_specific<Sampler> samplers(scene.sampler);
    ProgressReporter progress(nSamples, "Sampling", options.quiet);
    std::vector<std::pair<int, double>> table;
    for (int sampleIndex = 0, taken = 0; sampleIndex < nSamples; ++sampleIndex) {
        const int n = sampleIndex + 1;
        const bool report = !fo.skipBad || WellDistributedAt(scene.sampler, n);
        // pbrt-v4 skips the stratified counts it would not report: each makes a grid of its own.
        if (stratified && fo.skipBad && !report) {
            progress.Update();
            continue;
        }
        ++taken;
        tbb::parallel_for(int64_t(0), nPixels, [&](int64_t i) {
            const Point2i p(pixels.pMin.x + int(i % width), pixels.pMin.y + int(i / width));
            double &sum = sums[size_t(i)];
            if (stratified) {
                sum = StratifiedEstimate(fo.function, n, uint64_t(i)) * taken;  // mean of sum / taken
            } else if (halton) {
                sum += EvaluateTestFunction(fo.function, HaltonPoint(*halton, uint64_t(sampleIndex),
                                                                     Hash(uint64_t(i), fo.seed)));
            } else if (sobol) {
                sum += EvaluateTestFunction(fo.function, SobolPoint(*sobol, uint64_t(sampleIndex),
                                                                    Hash(uint64_t(i), fo.seed)));
            } else {
                Sampler &sampler = samplers.local();
                sampler.StartPixelSample(p, sampleIndex, 0);
                sum += EvaluateTestFunction(fo.function, sampler.GetPixel2D());
            }
        });
        if (report) {
            double squaredErrors = 0;
            for (double s : sums) squaredErrors += Sqr(s / taken - 1);
            table.emplace_back(n, squaredErrors / double(nPixels));
        }
        progress.Update();
        if (options.Cancelled())
            break;
    }
    progress.Done();
    return table;
}

RenderStatistics RenderFunction(Scene &scene, const RenderOptions &options) {
    const FunctionOptions &fo = scene.integratorOptions.function;
    if (!fo.imageFile.empty())
        WriteFunctionImage(fo.function, scene.film.PixelBounds(), fo.imageFile);
    ProgressReporter timer(1, "", true);
    std::vector<std::pair<int, double>> table = FunctionErrorTable(scene, options);
    WriteFileAtomically(fo.outputFile, [&](const std::string &tmpPath) {
        std::ofstream out(tmpPath);
        for (const auto &[n, mse] : table) out << n << ' ' << fmt::format("{:.9g}", mse) << '\n';
        if (!out.flush())
            throw std::runtime_error(fo.outputFile + ": error: cannot write the error table");
    });
    RenderStatistics stats;
    stats.seconds = timer.ElapsedSeconds();
    stats.samplesPerPixel = stats.maxSamplesPerPixel = table.empty() ? 0 : table.back().first;
    stats.cameraSamples = int64_t(stats.samplesPerPixel) * scene.film.PixelBounds().Area();
    return stats;
}

}  // namespace pbrt
