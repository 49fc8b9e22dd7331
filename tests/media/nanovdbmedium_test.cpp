// The NanoVDB medium (NanoVDBMedium in pbrt_ext/media/media.h): grids written through NanoVDB's API
// read back at their voxels, with majorants that bound them; bad files are errors naming the
// file and the fault, never a crash.
#include "pbrt_ext/media/media.h"

#include <iostream>  // GridValidator.h, included through IO.h, uses std::cerr
#define NANOVDB_USE_ZIP 1
#include <nanovdb/util/GridBuilder.h>
#include <nanovdb/util/IO.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace pbrt {
namespace {

std::string TempPath(const std::string &name) {
    return (std::filesystem::temp_directory_path() / ("pbrt_ext_nanovdb_test_" + name)).string();
}

// density(i, j, k) = (i + 2j + 3k) / 100 on the index box [0, 7]^3, voxel size 0.5.
float TestDensity(int i, int j, int k) { return float(i + 2 * j + 3 * k) / 100; }

std::string WriteTestGrid(const std::string &name, nanovdb::io::Codec codec) {
    nanovdb::GridBuilder<float> builder(0.f, nanovdb::GridClass::FogVolume);
    builder([](const nanovdb::Coord &c) { return TestDensity(c[0], c[1], c[2]); },
            nanovdb::CoordBBox(nanovdb::Coord(0), nanovdb::Coord(7)));
    std::string path = TempPath(name);
    nanovdb::io::writeGrid(path, builder.getHandle<>(0.5, nanovdb::Vec3d(0), "density"), codec);
    return path;
}

NanoVDBMedium Open(const std::string &path, const std::string &grid = "density") {
    return NanoVDBMedium(path, grid, "temperature", Transform(), Spectrum(1.f), Spectrum(2.f), 1,
                         0, 1, 0, 1);
}

std::string ErrorOpening(const std::string &path, const std::string &grid = "density") {
    try {
        Open(path, grid);
    } catch (const std::runtime_error &e) {
        return e.what();
    }
    return "";
}

TEST(NanoVDBMedium, ReadsTheDensityAtVoxelCentres) {
    for (auto codec : {nanovdb::io::Codec::NONE, nanovdb::io::Codec::ZIP}) {
        std::string path = WriteTestGrid("plain.nvdb", codec);
        NanoVDBMedium m = Open(path);
        std::remove(path.c_str());
        SampledWavelengths lambda = SampledWavelengths::SampleUniform(0.5f);
        EXPECT_FALSE(m.IsEmissive());
        for (int i : {1, 3, 6})
            for (int j : {2, 5})
                for (int k : {0, 4}) {
                    // NanoVDB's index (i, j, k) sits at world (i, j, k) * voxel size.
                    MediumProperties mp = m.SamplePoint(Point3f(0.5f * i, 0.5f * j, 0.5f * k), lambda);
                    EXPECT_NEAR(mp.sigma_a[0], TestDensity(i, j, k), 1e-5f) << i << j << k;
                    EXPECT_NEAR(mp.sigma_s[0], 2 * TestDensity(i, j, k), 1e-5f);
                }
        // Between voxels the density is interpolated linearly (the test grid is linear).
        MediumProperties mid = m.SamplePoint(Point3f(0.25f * 3, 0.5f * 2, 0.5f * 4), lambda);
        EXPECT_NEAR(mid.sigma_a[0], (TestDensity(1, 2, 4) + TestDensity(2, 2, 4)) / 2, 1e-5f);
    }
}

TEST(NanoVDBMedium, MajorantsBoundTheDensity) {
    std::string path = WriteTestGrid("majorants.nvdb", nanovdb::io::Codec::NONE);
    NanoVDBMedium m = Open(path);
    std::remove(path.c_str());
    const MajorantGrid &g = m.Majorants();
    Bounds3f b = m.Bounds();
    SampledWavelengths lambda = SampledWavelengths::SampleUniform(0.5f);
    RNG rng(9);
    for (int n = 0; n < 20000; ++n) {
        Point3f u(rng.Uniform<Float>(), rng.Uniform<Float>(), rng.Uniform<Float>());
        Float d = m.SamplePoint(b.Lerp(u), lambda).sigma_a[0];
        Float majorant = g.Lookup(std::min(int(u.x * g.res.x), g.res.x - 1),
                                  std::min(int(u.y * g.res.y), g.res.y - 1),
                                  std::min(int(u.z * g.res.z), g.res.z - 1));
        ASSERT_LE(d, majorant * (1 + 1e-5f)) << u.x << " " << u.y << " " << u.z;
    }
}

TEST(NanoVDBMedium, BadFilesAreErrorsNamingTheFault) {
    std::string missing = TempPath("missing.nvdb");
    EXPECT_NE(ErrorOpening(missing).find(missing), std::string::npos) << ErrorOpening(missing);

    std::string good = WriteTestGrid("good.nvdb", nanovdb::io::Codec::NONE);
    EXPECT_EQ(ErrorOpening(good, "smoke"), good + ": grid \"smoke\" not found");

    // The file cut short, and the file with its grid's bytes overwritten.
    std::ifstream in(good, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::remove(good.c_str());
    std::string cut = TempPath("cut.nvdb"), garbled = TempPath("garbled.nvdb");
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    for (size_t i = bytes.size() / 3; i < bytes.size(); i += 7)
        bytes[i] = char(0xA5 ^ bytes[i]);
    std::ofstream(garbled, std::ios::binary) << bytes;
    std::string cutError = ErrorOpening(cut), garbledError = ErrorOpening(garbled);
    std::remove(cut.c_str());
    std::remove(garbled.c_str());
    EXPECT_EQ(cutError.rfind(cut + ": ", 0), 0u) << cutError;
    EXPECT_EQ(garbledError.rfind(garbled + ": ", 0), 0u) << garbledError;
}

}  // namespace
}  // namespace pbrt
