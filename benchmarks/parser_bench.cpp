// Throughput of the scene-file readers on large meshes: a trianglemesh written inline in a scene
// file (tokenizer, parser and scene description) and a binary PLY decoded from memory. Counter:
// bytes/s of input. The parser's speed target lives here, not in a timed test.
#include "pbrt_ext/scene/scenedescription.h"
#include "pbrt_ext/util/ply.h"

#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstring>
#include <string>

using namespace pbrt;

namespace {

constexpr int kPoints = 300000;

std::string InlineMeshScene() {
    std::string text = "WorldBegin\nShape \"trianglemesh\" \"point3 P\" [";
    for (int i = 0; i < kPoints; ++i)
        text += " 0.125 -1.5 " + std::to_string(i);
    text += " ]\n\"integer indices\" [";
    for (int i = 0; i + 2 < kPoints; i += 3)
        text += " " + std::to_string(i) + " " + std::to_string(i + 1) + " " + std::to_string(i + 2);
    text += " ]\n";
    return text;
}

void BM_ParseInlineTriangleMesh(benchmark::State &state) {
    const std::string text = InlineMeshScene();
    for (auto _ : state)
        benchmark::DoNotOptimize(DescribeSceneString(text));
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(text.size()));
}
BENCHMARK(BM_ParseInlineTriangleMesh)->Unit(benchmark::kMillisecond);

template <typename T>
void Append(std::string *bytes, T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    bytes->append(raw, sizeof(T));
}

// A binary little-endian PLY of kPoints vertices and kPoints / 3 triangles.
std::string BinaryPly() {
    std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex " +
                      std::to_string(kPoints) +
                      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                      std::to_string(kPoints / 3) +
                      "\nproperty list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < kPoints; ++i) {
        Append(&ply, 0.125f);
        Append(&ply, -1.5f);
        Append(&ply, float(i));
    }
    for (int i = 0; i + 2 < kPoints; i += 3) {
        Append(&ply, uint8_t(3));
        for (int v = i; v < i + 3; ++v) Append(&ply, int32_t(v));
    }
    return ply;
}

void BM_ParseBinaryPly(benchmark::State &state) {
    const std::string ply = BinaryPly();
    for (auto _ : state)
        benchmark::DoNotOptimize(ParsePly(ply, "bench.ply"));
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(ply.size()));
}
BENCHMARK(BM_ParseBinaryPly)->Unit(benchmark::kMillisecond);

}  // namespace
