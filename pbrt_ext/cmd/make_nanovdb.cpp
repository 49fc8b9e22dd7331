// make_nanovdb: writes a puff of smoke as a NanoVDB file through NanoVDB's own API (GridBuilder
// and io::writeGrids), the input of the "nanovdb" medium in scenes/media-nanovdb-smoke.pbrt and
// of the reader's tests. Generated rather than downloaded, like the sky, so that the scenes
// need no external assets.
//
// The "density" grid is a sphere of radius 1 whose density, in [0, 1], is five octaves of
// Perlin noise thinning toward the rim; the "temperature" grid (kelvin) is hottest at the
// centre, for the blackbody emission of a fire. Voxel size 2 / resolution, centred on the
// origin, zip-compressed unless asked not to be (the fuzz seeds).
//
// Usage: make_nanovdb [--resolution N] [--uncompressed] out.nvdb
#include "pbrt_ext/util/noise.h"

#include <iostream>  // GridValidator.h, included through IO.h, uses std::cerr
#define NANOVDB_USE_ZIP 1
#include <nanovdb/util/GridBuilder.h>
#include <nanovdb/util/IO.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

using namespace pbrt;

namespace {

constexpr const char *kUsage = "usage: make_nanovdb [--resolution N] [--uncompressed] out.nvdb\n";

// Density in [0, 1] at p (world units): noise inside the unit sphere, fading out at its rim.
float SmokeDensity(Point3f p) {
    float r = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    if (r >= 1)
        return 0;
    float noise = 0, omega = 0.5f, lambda = 3;
    for (int i = 0; i < 5; ++i) {
        noise += omega * Noise(lambda * p);
        omega *= 0.5f;
        lambda *= 1.99f;
    }
    float falloff = 1 - r * r;
    return std::clamp(falloff * (0.6f + 1.6f * noise), 0.f, 1.f);
}

// Temperature in kelvin: 2500 K at the centre, room temperature at the rim.
float Temperature(Point3f p) {
    float r = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    return r >= 1 ? 0.f : 300 + 2200 * (1 - r) * (1 - r);
}

template <typename F>
nanovdb::GridHandle<> Build(const std::string &name, int resolution, F value) {
    nanovdb::GridBuilder<float> builder(0.f, nanovdb::GridClass::FogVolume);
    double voxel = 2.0 / resolution;
    int half = resolution / 2;
    builder(
        [&](const nanovdb::Coord &ijk) {
            return value(Point3f((ijk[0] + 0.5f) * voxel, (ijk[1] + 0.5f) * voxel,
                                 (ijk[2] + 0.5f) * voxel));
        },
        nanovdb::CoordBBox(nanovdb::Coord(-half), nanovdb::Coord(half - 1)));
    return builder.getHandle<>(voxel, nanovdb::Vec3d(0), name);
}

}  // namespace

int main(int argc, char **argv) {
    int resolution = 64;
    nanovdb::io::Codec codec = nanovdb::io::Codec::ZIP;
    std::string out;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--resolution" && i + 1 < argc)
            resolution = std::atoi(argv[++i]);
        else if (a == "--uncompressed")
            codec = nanovdb::io::Codec::NONE;
        else if (!a.empty() && a[0] != '-' && out.empty())
            out = a;
        else {
            std::cerr << kUsage;
            return 2;
        }
    }
    if (out.empty() || resolution < 2 || resolution > 1024) {
        std::cerr << kUsage;
        return 2;
    }
    try {
        std::vector<nanovdb::GridHandle<>> grids;
        grids.push_back(Build("density", resolution, SmokeDensity));
        grids.push_back(Build("temperature", resolution, Temperature));
        nanovdb::io::writeGrids(out, grids, codec);
    } catch (const std::exception &e) {
        std::cerr << "make_nanovdb: " << out << ": " << e.what() << "\n";
        return 1;
    }
    return 0;
}
