// pbrt-v4's mesh displacement: refinement leaves every edge below the length asked for and
// shares each split edge's midpoint between its two triangles (no cracks); vertices move along
// their normals by the displacement at their point and uv; normals are recomputed; quads split
// on pbrt-v4's diagonal; meshes without uv, non-positive lengths and refinements past the
// triangle budget are refused.
#include "pbrt_ext/shapes/meshdisplacement.h"

#include "tests/support/scenefolder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <utility>

namespace pbrt {
namespace {

// The unit square at z = 0 as two triangles (or one quad), normals +z, uv = (x, y).
PlyMesh Square(bool asQuad = false) {
    PlyMesh m;
    m.p = {Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(0, 1, 0), Point3f(1, 1, 0)};
    m.n.assign(4, Normal3f(0, 0, 1));
    m.uv = {Point2f(0, 0), Point2f(1, 0), Point2f(0, 1), Point2f(1, 1)};
    if (asQuad)
        m.quadIndices = {0, 1, 2, 3};  // a bilinear patch's p00 p10 p01 p11
    else
        m.triIndices = {0, 1, 3, 0, 3, 2};
    return m;
}

auto Flat = [](Point3f, Point2f) { return Float(0); };

TEST(MeshDisplacement, RefinedEdgesAreShortAndShared) {
    PlyMesh m = DisplaceMesh(Square(), Transform(), 0.3f, 1000000, Flat);
    ASSERT_GT(m.triIndices.size() / 3, 8u);
    std::map<std::pair<int, int>, int> edgeUses;
    double area = 0;
    for (size_t i = 0; i < m.triIndices.size(); i += 3) {
        for (int k = 0; k < 3; ++k) {
            int a = m.triIndices[i + size_t(k)], b = m.triIndices[i + size_t((k + 1) % 3)];
            EXPECT_LT(Distance(m.p[size_t(a)], m.p[size_t(b)]), 0.3f);
            ++edgeUses[{std::min(a, b), std::max(a, b)}];
        }
        Vector3f c = Cross(m.p[size_t(m.triIndices[i + 1])] - m.p[size_t(m.triIndices[i])],
                           m.p[size_t(m.triIndices[i + 2])] - m.p[size_t(m.triIndices[i])]);
        EXPECT_GT(c.z, 0);  // the winding kept
        area += 0.5 * Length(c);
    }
    EXPECT_NEAR(area, 1, 1e-5);
    // An edge inside the square has two triangles; only the square's border has one.
    for (const auto &[edge, uses] : edgeUses) {
        Point3f a = m.p[size_t(edge.first)], b = m.p[size_t(edge.second)];
        bool border = (a.x == b.x && (a.x == 0 || a.x == 1)) || (a.y == b.y && (a.y == 0 || a.y == 1));
        EXPECT_EQ(uses, border ? 1 : 2) << a.x << "," << a.y << " " << b.x << "," << b.y;
    }
    // A longer length leaves the square as it is.
    EXPECT_EQ(DisplaceMesh(Square(), Transform(), 2, 1000, Flat).triIndices.size(), 6u);
    // Lengths are measured in render space: scaled 10x, the same square splits much further.
    EXPECT_GT(DisplaceMesh(Square(), Scale(10, 10, 10), 0.3f, 1000000, Flat).triIndices.size(),
              50 * m.triIndices.size());
}

TEST(MeshDisplacement, VerticesMoveAlongTheirNormalsAndNormalsFollow) {
    PlyMesh m = DisplaceMesh(Square(), Transform(), 0.2f, 1000000,
                             [](Point3f p, Point2f uv) { return 0.1f * uv.x + p.y * 0; });
    for (size_t i = 0; i < m.p.size(); ++i) {
        EXPECT_NEAR(m.p[i].z, 0.1f * m.uv[i].x, 1e-6f);
        // The tilted plane z = 0.1 x has the normal (-0.1, 0, 1) / |.|.
        EXPECT_NEAR(m.n[i].x, -0.1f / std::sqrt(1.01f), 1e-5f);
        EXPECT_NEAR(m.n[i].z, 1 / std::sqrt(1.01f), 1e-5f);
    }
}

TEST(MeshDisplacement, QuadsSplitOnPbrtV4sDiagonal) {
    PlyMesh m = DisplaceMesh(Square(true), Transform(), 5, 1000, Flat);
    EXPECT_TRUE(m.quadIndices.empty());
    EXPECT_EQ(m.triIndices, (std::vector<int>{0, 1, 3, 0, 3, 2}));
}

TEST(MeshDisplacement, RefusesWhatItCannotDo) {
    PlyMesh noUV = Square();
    noUV.uv.clear();
    EXPECT_THROW(DisplaceMesh(noUV, Transform(), 0.1f, 1000, Flat), std::invalid_argument);
    EXPECT_THROW(DisplaceMesh(Square(), Transform(), 0, 1000, Flat), std::invalid_argument);
    EXPECT_THROW(DisplaceMesh(Square(), Transform(), 0.001f, 1000, Flat), std::invalid_argument);
}

// The scenes' tile displaced with edges below edgeLength, after the options (before
// WorldBegin); its path.
std::string DisplacedTileScene(const std::string &name, const std::string &options, const char *edgeLength) {
    std::filesystem::path dir = TestFolder("pbrt_ext_displacement_test");
    std::filesystem::copy_file(std::filesystem::path(PBRT_EXT_TEST_DATA_DIR) / "../../scenes/meshes/tile.ply",
                               dir / "tile.ply", std::filesystem::copy_options::overwrite_existing);
    std::filesystem::path scene = dir / name;
    std::ofstream(scene) << "Camera \"perspective\"\n" << options << "WorldBegin\n"
                         << "Texture \"d\" \"float\" \"constant\" \"float value\" 0.1\n"
                         << "Shape \"plymesh\" \"string filename\" \"tile.ply\" \"texture displacement\" \"d\" "
                            "\"float edgelength\" " << edgeLength << "\n";
    return scene.string();
}

constexpr const char *kTooFine = ":4:46: error: displacing the mesh makes more than";

TEST(MeshDisplacement, SceneErrorsAreAtTheDisplacementParameter) {
    EXPECT_THAT(LoadErrorAfterPath(DisplacedTileScene("fine.pbrt", "", "1e-7")),
                testing::AllOf(testing::StartsWith(kTooFine),
                               testing::HasSubstr("expected a larger \"edgelength\"")));
}

// pbrt-v4's --displacement-edge-scale and Option "displacementedgescale" multiply the edge
// length; the file's Option wins over the command line, as in pbrt-v4. Seen through the triangle
// budget: edges of 0.05 are fine, scaled by 1e-5 they are too many.
TEST(MeshDisplacement, EdgeScaleFromTheCommandLineOrTheFileScalesTheEdgeLength) {
    RenderOverrides scaled;
    scaled.displacementEdgeScale = 1e-5f;
    std::string plain = DisplacedTileScene("plain.pbrt", "", "0.05");
    EXPECT_EQ(LoadErrorAfterPath(plain), "no error");
    EXPECT_THAT(LoadErrorAfterPath(plain, scaled), testing::StartsWith(kTooFine));
    std::string option = DisplacedTileScene("option.pbrt", "Option \"displacementedgescale\" 1e-5\n", "0.05");
    EXPECT_THAT(LoadErrorAfterPath(option), testing::StartsWith(":5:46: error: displacing the mesh"));
    std::string unscaled = DisplacedTileScene("unscaled.pbrt", "Option \"displacementedgescale\" 1\n", "0.05");
    EXPECT_EQ(LoadErrorAfterPath(unscaled, scaled), "no error");
    std::string negative = DisplacedTileScene("negative.pbrt", "Option \"displacementedgescale\" -2\n", "0.05");
    EXPECT_EQ(LoadErrorAfterPath(negative),
              ":2:1: error: option \"displacementedgescale\" is -2; expected a positive scale");
}

}  // namespace
}  // namespace pbrt
