// Image texture lookups per second for each MIP map filter (textures/mipmap.h), and the time to build
// a pyramid: what filtering costs a shading point.
//
//   build/release/benchmarks/texture_bench
//
// The image is 1024 x 1024 and 8-bit sRGB (as most scene textures are); lookups are at random
// points with a random footprint from a tenth of a texel to 64 texels wide, anisotropic up to 8:1,
// the spread a camera's differentials give over a receding floor.
#include "pbrt_ext/textures/mipmap.h"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

using namespace pbrt;

// A noisy, colourful 8-bit image read back from a PNG, so that it keeps its bytes.
Image EightBitImage(int size) {
    Image image(Point2i(size, size));
    std::mt19937 rng(3);
    std::uniform_real_distribution<Float> u(0, 1);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int c = 0; c < 3; ++c) image.SetChannel(Point2i(x, y), c, u(rng));
    std::string path = (std::filesystem::temp_directory_path() /
                        ("texture_bench_" + std::to_string(::getpid()) + ".png")).string();
    image.Write(path);
    Image eightBit = Image::Read(path);
    std::filesystem::remove(path);
    return eightBit;
}

struct Lookup {
    Point2f st;
    Vector2f dst0, dst1;
};

std::vector<Lookup> RandomLookups(int n, int size) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<Float> u(0, 1);
    std::vector<Lookup> lookups(static_cast<size_t>(n));
    for (Lookup &l : lookups) {
        Float width = std::exp2(-3.3f + 9.3f * u(rng)) / Float(size);  // 0.1 to 64 texels
        Float angle = 2 * Pi * u(rng), aspect = 1 + 7 * u(rng);
        Vector2f major(std::cos(angle), std::sin(angle));
        l = Lookup{Point2f(u(rng), u(rng)), width * major, (width / aspect) * Vector2f(-major.y, major.x)};
    }
    return lookups;
}

void BM_Filter(benchmark::State &state, FilterFunction filter) {
    constexpr int size = 1024;
    MIPMap mipmap(EightBitImage(size), WrapMode::Repeat, MIPMapFilterOptions{filter, 8});
    std::vector<Lookup> lookups = RandomLookups(1 << 16, size);
    size_t i = 0;
    for (auto _ : state) {
        const Lookup &l = lookups[i++ & (lookups.size() - 1)];
        benchmark::DoNotOptimize(mipmap.Filter(l.st, l.dst0, l.dst1));
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK_CAPTURE(BM_Filter, point, FilterFunction::Point);
BENCHMARK_CAPTURE(BM_Filter, bilinear, FilterFunction::Bilinear);
BENCHMARK_CAPTURE(BM_Filter, trilinear, FilterFunction::Trilinear);
BENCHMARK_CAPTURE(BM_Filter, ewa, FilterFunction::EWA);

// The pyramid of a 1000 x 1000 image (resized up to 1024 first) and of a 1024 x 1024 one.
void BM_GeneratePyramid(benchmark::State &state) {
    Image image = EightBitImage(int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(Image::GeneratePyramid(image, WrapMode::Repeat));
}
BENCHMARK(BM_GeneratePyramid)->Arg(1000)->Arg(1024)->Unit(benchmark::kMillisecond);

}  // namespace
