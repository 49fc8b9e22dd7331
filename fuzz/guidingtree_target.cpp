// The guiding-tree target: a file that --guiding-load reads (SDTree::Read), for a scene whose
// bounds are the unit cube, then sampled and evaluated where it is read. The input is the file after
// its magic number and bounds, which the target writes as a tree of that scene has them, so that
// every input reaches the spatial and directional trees rather than being refused by its header.
// Findings: a BSDF fraction outside (0, 1], a density that is negative or not finite, a sample outside the unit square or whose
// density differs from the one PDF reports there, a learned radiance that is not finite.
#include "fuzz/finding.h"
#include "fuzz/fuzz_targets.h"
#include "fuzz/scratch.h"

#include "pbrt_ext/integrators/sdtree.h"
#include "pbrt_ext/util/rng.h"

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace pbrt::fuzz {

namespace {

const Bounds3f kUnitCube(Point3f(0, 0, 0), Point3f(1, 1, 1));

// The header SDTree::Write gives a tree of kUnitCube: its magic number and bounds.
std::vector<uint8_t> TreeHeader() {
    std::string path = (ScratchDirectory("guidingtree") / "header.sdt").string();
    SDTree(kUnitCube).Write(path);
    std::ifstream in(path, std::ios::binary);
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    bytes.resize(8 + 6 * sizeof(Float));
    return bytes;
}

void CheckDirections(const DTree &tree) {
    RNG rng(1);
    for (int i = 0; i < 16; ++i) {
        Float pdf = -1;
        Point2f c = tree.Sample(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()), &pdf);
        if (!(c.x >= 0 && c.x < 1 && c.y >= 0 && c.y < 1))
            ReportFinding("guidingtree", "a sample outside the unit square");
        Float expected = tree.PDF(c);
        if (!(expected >= 0) || !std::isfinite(expected) || !(std::abs(pdf - expected) <= 1e-3f * expected))
            ReportFinding("guidingtree", "a sample's density is not the density PDF reports there");
        if (!std::isfinite(tree.Radiance(c)))
            ReportFinding("guidingtree", "a learned radiance that is not finite");
    }
}

}  // namespace

void FuzzGuidingTree(std::span<const uint8_t> data) {
    static const std::vector<uint8_t> header = TreeHeader();
    std::vector<uint8_t> file = header;
    file.insert(file.end(), data.begin(), data.end());
    std::string path = WriteScratchFile("guidingtree", "input.sdt", file);
    ExpectReadOrRejection("guidingtree", [&] {
        SDTree tree = SDTree::Read(path, kUnitCube);
        RNG rng(2);
        for (int i = 0; i < 8; ++i) {
            Point3f p(rng.Uniform<Float>(), rng.Uniform<Float>(), rng.Uniform<Float>());
            SDTree::Guide guide = tree.SamplingGuide(p);
            CheckDirections(guide.directions);
            if (!(guide.bsdfFraction > 0 && guide.bsdfFraction <= 1))
                ReportFinding("guidingtree", "a BSDF fraction outside (0, 1]");
        }
    });
}

}  // namespace pbrt::fuzz
