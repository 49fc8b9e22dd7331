// Shapes from scene-file entities (pbrt-v4's Shape::Create): meshes are transformed to world
// space once; PLY quads become bilinear patches, as pbrt-v4 makes them.
#include "pbrt_ext/scene/create.h"

#include "pbrt_ext/shapes/curves.h"
#include "pbrt_ext/shapes/meshdisplacement.h"

#include "pbrt_ext/shapes/loopsubdiv.h"
#include "pbrt_ext/util/error.h"
#include "pbrt_ext/util/ply.h"
#include "pbrt_ext/util/resourcelimits.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <limits>

namespace pbrt {

namespace {

// What a shape is made of, besides its geometry.
struct Appearance {
    int material;
    std::optional<AreaLightDescription> emission;
    std::optional<FloatTexture> alpha;
};

// pbrt-v4's alpha parameter: a float texture, or a constant below 1; alpha 1 needs no test.
std::optional<FloatTexture> Alpha(const ParameterDictionary &p, TextureResolver &textures) {
    if (!p.HasParameter("alpha") ||
        (p.ParameterType("alpha") != "texture" && p.GetOneFloat("alpha", 1) >= 1))
        return {};
    return textures.Float(p, "alpha", 1);
}

// Meshes count their primitives in an int, and an emitting mesh becomes one area light per
// primitive, each far larger than the primitive's indices: both are checked before the mesh is
// made.
void CheckPrimitives(const ShapeSceneEntity &e, const Appearance &a, size_t primitives) {
    if (primitives > size_t(std::numeric_limits<int>::max()))
        throw ParseError(e.loc, fmt::format("{} of {} primitives; expected at most {}", e.name,
                                            primitives, std::numeric_limits<int>::max()));
    if (a.emission)
        CheckMemory(e.loc, fmt::format("the {} area lights of an emitting {}", primitives, e.name),
                    SaturatingProduct({primitives, sizeof(Light)}));
}

// A PLY file's vertices, for the first of its two meshes: copied only when the second needs them.
template <typename T>
std::vector<T> TakeOrCopy(std::vector<T> &v, bool copy) {
    if (copy)
        return v;
    return std::move(v);
}

// Mesh construction errors (index ranges, sizes) at the shape's location.
template <typename Make>
auto AtShape(const ShapeSceneEntity &e, Make make) {
    try {
        return make();
    } catch (const ParseError &) {
        throw;
    } catch (const std::exception &error) {
        throw ParseError(e.loc, error.what());
    }
}

void AddTriangleMesh(SceneBuilder &builder, const ShapeSceneEntity &e,
                     const Appearance &a) {
    const ParameterDictionary &p = e.parameters;
    std::vector<int> indices = p.GetIntArray("indices");
    std::vector<Point3f> P = p.GetPoint3fArray("P");
    if (indices.empty() && P.size() == 3)
        indices = {0, 1, 2};  // pbrt-v4: a single triangle needs no indices
    if (P.empty() || indices.empty())
        throw ParseError(e.loc, "trianglemesh needs \"point3 P\" and \"integer indices\"");
    std::vector<Normal3f> N = p.GetNormal3fArray("N");
    std::vector<Point2f> uv = p.GetPoint2fArray("uv");
    std::vector<Vector3f> S = p.GetVector3fArray("S");
    p.GetIntArray("faceIndices");
    p.ReportUnused();
    CheckPrimitives(e, a, indices.size() / 3);
    auto mesh = AtShape(e, [&] {
        return std::make_shared<TriangleMesh>(MakeTriangleMesh(
            e.worldFromObject, e.reverseOrientation, std::move(indices), std::move(P),
            std::move(N), std::move(uv), std::move(S)));
    });
    builder.AddTriangleMesh(std::move(mesh), a.material, a.emission, a.alpha);
}

// pbrt-v4's "displacement" (a float texture) over edges refined below "edgelength"
// (meshdisplacement.h). pbrt-v4 gives the texture each vertex's object-space point as if it were
// a point of its render space, the world moved to put the camera at the origin; a 3D texture is
// then looked up at the object-space point plus the camera's position, and so it is here.
PlyMesh Displaced(const ShapeSceneEntity &e, PlyMesh ply, TextureResolver &textures,
                  Vector3f cameraPosition, Float edgeScale) {
    const ParameterDictionary &p = e.parameters;
    FloatTexture displacement = textures.Float(p, "displacement", 0);
    Float edgeLength = p.GetOneFloat("edgelength", 1) * edgeScale;
    // A vertex (p, n, uv), three indices and what the mesh and Embree keep per triangle.
    constexpr uint64_t kBytesPerTriangle = 128;
    try {
        return DisplaceMesh(std::move(ply), e.worldFromObject, edgeLength,
                            MemoryBudget() / kBytesPerTriangle, [&](Point3f pObject, Point2f uv) {
                                TextureEvalContext ctx;
                                ctx.p = pObject + cameraPosition;
                                ctx.uv = uv;
                                return displacement.Evaluate(ctx);
                            });
    } catch (const std::invalid_argument &error) {
        throw ParseError(*p.Loc("displacement"), error.what());
    }
}

void AddPlyMesh(SceneBuilder &builder, const ShapeSceneEntity &e, const Appearance &a,
                TextureResolver &textures, Float displacementEdgeScale) {
    const ParameterDictionary &p = e.parameters;
    std::string filename = p.GetOneString("filename", "");
    if (filename.empty())
        throw ParseError(e.loc, "plymesh needs \"string filename\"");
    bool displaced = p.HasParameter("displacement");
    if (!displaced) p.GetOneFloat("edgelength", 1);  // read by pbrt-v4 whether or not it displaces
    std::string path = ResolvePath(textures.Folder(), filename);
    if (!std::filesystem::is_regular_file(path))
        throw ParseError(*p.Loc("filename"), "cannot open PLY file \"" + filename +
                                                 "\" (looked for " + path + ")");
    PlyMesh ply = ReadPly(path);
    if (displaced)
        ply = Displaced(e, std::move(ply), textures,
                        Vector3f(builder.GetCamera().WorldFromCamera()(Point3f(0, 0, 0))),
                        displacementEdgeScale);
    p.ReportUnused();
    CheckPrimitives(e, a, ply.triIndices.size() / 3);
    CheckPrimitives(e, a, ply.quadIndices.size() / 4);
    bool hasQuads = !ply.quadIndices.empty();
    if (!ply.triIndices.empty()) {
        auto mesh = AtShape(e, [&] {
            return std::make_shared<TriangleMesh>(MakeTriangleMesh(
                e.worldFromObject, e.reverseOrientation, std::move(ply.triIndices),
                TakeOrCopy(ply.p, hasQuads), TakeOrCopy(ply.n, hasQuads),
                TakeOrCopy(ply.uv, hasQuads)));
        });
        builder.AddTriangleMesh(std::move(mesh), a.material, a.emission, a.alpha);
    }
    if (hasQuads) {
        // ReadPly already lists each quad as a bilinear patch's p00 p10 p01 p11.
        auto mesh = AtShape(e, [&] {
            return std::make_shared<BilinearPatchMesh>(MakeBilinearPatchMesh(
                e.worldFromObject, e.reverseOrientation, std::move(ply.quadIndices),
                std::move(ply.p), std::move(ply.n), std::move(ply.uv)));
        });
        builder.AddBilinearPatchMesh(std::move(mesh), a.material, a.emission, a.alpha);
    }
}

// pbrt-v4's "emissionfilename" on a bilinear mesh: the image's channel averages, t flipped as
// the area light reads it, as the density of its patches' (u, v); as in pbrt-v4, ignored (with a
// warning) where the mesh has its own "uv".
std::shared_ptr<const PiecewiseConstant2D> EmissionDistribution(const ShapeSceneEntity &e, bool uvIsPatchUV,
                                                                const std::string &folder) {
    const ParameterDictionary &p = e.parameters;
    std::string filename = p.GetOneString("emissionfilename", "");
    if (filename.empty()) return nullptr;
    if (!uvIsPatchUV) {
        WarningAt(*p.Loc("emissionfilename"), "\"emissionfilename\" is ignored where \"uv\" is given, as in pbrt-v4");
        return nullptr;
    }
    std::string path = ResolvePath(folder, filename);
    if (!std::filesystem::is_regular_file(path))
        throw ParseError(*p.Loc("emissionfilename"), "cannot open image \"" + filename + "\" (looked for " + path + ")");
    Image image = ReadFileAt(*p.Loc("emissionfilename"), [&] { return Image::Read(path); });
    Point2i res = image.Resolution();
    std::vector<Float> f = image.GetSamplingDistribution();
    for (int y = 0; y < res.y / 2; ++y)  // t = 0 is the file's bottom row
        std::swap_ranges(f.begin() + ptrdiff_t(y) * res.x, f.begin() + ptrdiff_t(y + 1) * res.x,
                         f.end() - ptrdiff_t(y + 1) * res.x);
    return std::make_shared<const PiecewiseConstant2D>(f, res.x, res.y);
}

void AddBilinearMesh(SceneBuilder &builder, const ShapeSceneEntity &e, const Appearance &a,
                     const std::string &folder) {
    const ParameterDictionary &p = e.parameters;
    std::vector<int> indices = p.GetIntArray("indices");
    std::vector<Point3f> P = p.GetPoint3fArray("P");
    if (indices.empty() && P.size() == 4)
        indices = {0, 1, 2, 3};
    if (P.empty() || indices.empty())
        throw ParseError(e.loc, "bilinearmesh needs \"point3 P\" and \"integer indices\"");
    std::vector<Normal3f> N = p.GetNormal3fArray("N");
    std::vector<Point2f> uv = p.GetPoint2fArray("uv");
    std::shared_ptr<const PiecewiseConstant2D> imageDistribution = EmissionDistribution(e, uv.empty(), folder);
    p.ReportUnused();
    CheckPrimitives(e, a, indices.size() / 4);
    auto mesh = AtShape(e, [&] {
        return std::make_shared<BilinearPatchMesh>(
            MakeBilinearPatchMesh(e.worldFromObject, e.reverseOrientation, std::move(indices),
                                  std::move(P), std::move(N), std::move(uv)));
    });
    mesh->imageDistribution = std::move(imageDistribution);
    builder.AddBilinearPatchMesh(std::move(mesh), a.material, a.emission, a.alpha);
}

CurveType CurveTypeFrom(const ParameterDictionary &p) {
    std::string type = p.GetOneString("type", "flat");
    if (type == "flat")
        return CurveType::Flat;
    if (type == "cylinder")
        return CurveType::Cylinder;
    if (type == "ribbon")
        return CurveType::Ribbon;
    throw ParseError(*p.Loc("type"), "curve \"type\" \"" + type +
                                         "\" is unknown; expected flat, cylinder or ribbon");
}

// pbrt-v4's curve, with its parameters; "splitdepth" is read and has no use (Embree refines
// curves itself). Curves do not emit (pbrt-v4 cannot sample them as lights).
void AddCurve(SceneBuilder &builder, const ShapeSceneEntity &e, const Appearance &a) {
    const ParameterDictionary &p = e.parameters;
    CurveDescription curve;
    curve.p = p.GetPoint3fArray("P");
    curve.basis = p.GetOneString("basis", "bezier");
    curve.degree = p.GetOneInt("degree", 3);
    curve.type = CurveTypeFrom(p);
    curve.n = p.GetNormal3fArray("N");
    Float width = p.GetOneFloat("width", 1);
    curve.width0 = p.GetOneFloat("width0", width);
    curve.width1 = p.GetOneFloat("width1", width);
    p.GetOneInt("splitdepth", 3);
    p.ReportUnused();
    if (curve.type != CurveType::Ribbon && !curve.n.empty()) {
        WarningAt(*p.Loc("N"), "curve normals are only used by \"ribbon\" curves: ignored");
        curve.n.clear();
    }
    if (a.emission)
        WarningAt(e.loc, "curves do not emit (as in pbrt-v4): the area light is ignored");
    CheckPrimitives(e, {a.material, {}, {}}, curve.p.size());
    auto mesh = AtShape(e, [&] {
        return std::make_shared<CurveMesh>(
            MakeCurveMesh(e.worldFromObject, e.reverseOrientation, curve));
    });
    builder.AddCurves(std::move(mesh), a.material, a.alpha);
}

// pbrt-v4's loopsubdiv: the control mesh refined `levels` times, as a triangle mesh with the
// limit surface's normals. Each level has four times the triangles of the last (and about 52
// bytes each while it is refined), so the size is checked before the first level.
void AddLoopSubdiv(SceneBuilder &builder, const ShapeSceneEntity &e, const Appearance &a) {
    const ParameterDictionary &p = e.parameters;
    int levels = p.GetOneInt("levels", 3);
    std::vector<int> indices = p.GetIntArray("indices");
    std::vector<Point3f> P = p.GetPoint3fArray("P");
    std::string scheme = p.GetOneString("scheme", "loop");
    p.ReportUnused();
    if (indices.empty() || P.empty())
        throw ParseError(e.loc, "loopsubdiv needs \"point3 P\" and \"integer indices\"");
    if (levels < 0)
        throw ParseError(*p.Loc("levels"),
                         fmt::format("loopsubdiv \"levels\" is {}; expected 0 or more", levels));
    if (scheme != "loop")
        throw ParseError(*p.Loc("scheme"), "loopsubdiv \"scheme\" \"" + scheme +
                                               "\" is unknown; expected \"loop\"");
    uint64_t triangles = indices.size() / 3;
    for (int level = 0; level < std::min(levels, 64); ++level)  // saturated by then
        triangles = SaturatingProduct({triangles, 4});
    CheckMemory(e.loc, fmt::format("loopsubdiv to level {}", levels),
                SaturatingProduct({triangles, 52}));
    CheckPrimitives(e, a, triangles);
    auto mesh = AtShape(e, [&] {
        SubdividedMesh limit = LoopSubdivide(levels, indices, P);
        return std::make_shared<TriangleMesh>(MakeTriangleMesh(
            e.worldFromObject, e.reverseOrientation, std::move(limit.indices),
            std::move(limit.p), std::move(limit.n)));
    });
    builder.AddTriangleMesh(std::move(mesh), a.material, a.emission, a.alpha);
}

// pbrt-v4's cylinder: the analytic quadric. A cylinder without area is an error, since an
// emitting one would have no density to sample it by.
void AddCylinder(SceneBuilder &builder, const ShapeSceneEntity &e, const Appearance &a) {
    const ParameterDictionary &p = e.parameters;
    Float radius = p.GetOneFloat("radius", 1), zMin = p.GetOneFloat("zmin", -1),
          zMax = p.GetOneFloat("zmax", 1), phiMax = p.GetOneFloat("phimax", 360);
    p.ReportUnused();
    if (!(radius > 0) || !IsFinite(radius))
        throw ParseError(p.Loc("radius") ? *p.Loc("radius") : e.loc,
                         fmt::format("cylinder \"radius\" is {}; expected a finite value > 0",
                                     radius));
    if (!(zMin != zMax) || !IsFinite(zMin) || !IsFinite(zMax))
        throw ParseError(e.loc, fmt::format("cylinder \"zmin\" {} and \"zmax\" {}: expected "
                                            "two different finite heights", zMin, zMax));
    if (!(phiMax > 0))
        throw ParseError(*p.Loc("phimax"),
                         fmt::format("cylinder \"phimax\" is {}; expected a value > 0", phiMax));
    builder.AddCylinder(Cylinder(e.worldFromObject, e.reverseOrientation, radius, zMin, zMax,
                                 phiMax),
                        a.material, a.emission, a.alpha);
}

}  // namespace

void AddShape(SceneBuilder &builder, const ShapeSceneEntity &e, int material,
              std::optional<AreaLightDescription> emission, TextureResolver &textures,
              Float displacementEdgeScale) {
    const ParameterDictionary &p = e.parameters;
    Appearance a{material, std::move(emission), Alpha(p, textures)};
    if (e.name == "trianglemesh")
        return AddTriangleMesh(builder, e, a);
    if (e.name == "plymesh")
        return AddPlyMesh(builder, e, a, textures, displacementEdgeScale);
    if (e.name == "bilinearmesh")
        return AddBilinearMesh(builder, e, a, textures.Folder());
    if (e.name == "cylinder")
        return AddCylinder(builder, e, a);
    if (e.name == "sphere") {
        Float radius = p.GetOneFloat("radius", 1);
        Sphere sphere(e.worldFromObject, e.reverseOrientation, radius,
                      p.GetOneFloat("zmin", -radius), p.GetOneFloat("zmax", radius),
                      p.GetOneFloat("phimax", 360));
        p.ReportUnused();
        return builder.AddSphere(sphere, a.material, a.emission, a.alpha);
    }
    if (e.name == "disk") {
        Disk disk(e.worldFromObject, e.reverseOrientation, p.GetOneFloat("height", 0),
                  p.GetOneFloat("radius", 1), p.GetOneFloat("innerradius", 0),
                  p.GetOneFloat("phimax", 360));
        p.ReportUnused();
        return builder.AddDisk(disk, a.material, a.emission, a.alpha);
    }
    if (e.name == "loopsubdiv")
        return AddLoopSubdiv(builder, e, a);
    if (e.name == "curve")
        return AddCurve(builder, e, a);
    throw ParseError(e.loc, "unknown Shape \"" + e.name + "\": expected trianglemesh, plymesh, "
                                "bilinearmesh, loopsubdiv, curve, sphere, disk or cylinder");
}

}  // namespace pbrt
