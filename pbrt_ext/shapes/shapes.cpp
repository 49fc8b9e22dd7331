// Shapes (pbrt-v4's src/pbrt/shapes.h/.cpp): the meshes that triangles and bilinear patches
// index, and moving an interaction between spaces. The shape families are in triangles.cpp,
// quadrics.cpp and bilinearpatches.cpp.
#include "pbrt_ext/shapes/shapes.h"
#include "pbrt_ext/shapes/shapes_internal.h"

#include <cstdio>
#include <stdexcept>
#include <utility>

namespace pbrt {

using namespace shapedetail;

namespace {

template <typename Mesh>
Mesh MakeMesh(const char *name, int verticesPerPrimitive, const Transform &worldFromObject,
              bool reverseOrientation, std::vector<int> indices, std::vector<Point3f> p,
              std::vector<Normal3f> n, std::vector<Point2f> uv) {
    auto fail = [&](const std::string &what) {
        throw std::runtime_error(std::string(name) + ": " + what);
    };
    if (indices.size() % verticesPerPrimitive != 0)
        fail("the number of indices, " + std::to_string(indices.size()) +
             ", is not a multiple of " + std::to_string(verticesPerPrimitive));
    for (int i : indices)
        if (i < 0 || size_t(i) >= p.size())
            fail("vertex index " + std::to_string(i) + " is out of range (" +
                 std::to_string(p.size()) + " vertices)");
    if (!n.empty() && n.size() != p.size())
        fail(std::to_string(n.size()) + " normals for " + std::to_string(p.size()) + " vertices");
    if (!uv.empty() && uv.size() != p.size())
        fail(std::to_string(uv.size()) + " uvs for " + std::to_string(p.size()) + " vertices");

    Mesh mesh;
    for (Point3f &pi : p) pi = worldFromObject(pi);
    for (Normal3f &ni : n) ni = reverseOrientation ? -worldFromObject(ni) : worldFromObject(ni);
    mesh.p = std::move(p);
    mesh.indices = std::move(indices);
    mesh.n = std::move(n);
    mesh.uv = std::move(uv);
    mesh.reverseOrientation = reverseOrientation;
    mesh.transformSwapsHandedness = worldFromObject.SwapsHandedness();
    return mesh;
}

std::string Describe(const char *kind, size_t prims, size_t vertices, bool hasN, bool hasUV,
                     bool reverseOrientation, bool swaps) {
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "[ %s primitives: %zu vertices: %zu n: %s uv: %s reverseOrientation: %s "
                  "transformSwapsHandedness: %s ]",
                  kind, prims, vertices, hasN ? "yes" : "no", hasUV ? "yes" : "no",
                  reverseOrientation ? "true" : "false", swaps ? "true" : "false");
    return buf;
}

}  // namespace

std::string TriangleMesh::ToString() const {
    return Describe("TriangleMesh", indices.size() / 3, p.size(), !n.empty(), !uv.empty(),
                    reverseOrientation, transformSwapsHandedness);
}
std::string BilinearPatchMesh::ToString() const {
    return Describe("BilinearPatchMesh", indices.size() / 4, p.size(), !n.empty(), !uv.empty(),
                    reverseOrientation, transformSwapsHandedness);
}

TriangleMesh MakeTriangleMesh(const Transform &worldFromObject, bool reverseOrientation,
                              std::vector<int> indices, std::vector<Point3f> p,
                              std::vector<Normal3f> n, std::vector<Point2f> uv,
                              std::vector<Vector3f> s) {
    if (!s.empty() && s.size() != p.size())
        throw std::runtime_error("trianglemesh: " + std::to_string(s.size()) + " tangents \"S\" for " +
                                 std::to_string(p.size()) + " vertices");
    TriangleMesh mesh = MakeMesh<TriangleMesh>("trianglemesh", 3, worldFromObject,
                                               reverseOrientation, std::move(indices),
                                               std::move(p), std::move(n), std::move(uv));
    for (Vector3f &si : s) si = worldFromObject(si);
    mesh.s = std::move(s);
    return mesh;
}
BilinearPatchMesh MakeBilinearPatchMesh(const Transform &worldFromObject,
                                        bool reverseOrientation, std::vector<int> indices,
                                        std::vector<Point3f> p, std::vector<Normal3f> n,
                                        std::vector<Point2f> uv) {
    return MakeMesh<BilinearPatchMesh>("bilinearmesh", 4, worldFromObject, reverseOrientation,
                                       std::move(indices), std::move(p), std::move(n),
                                       std::move(uv));
}

SurfaceInteraction TransformInteraction(const Transform &t, const SurfaceInteraction &si) {
    SurfaceInteraction r = si;
    r.p = t(si.p);
    r.n = Normalize(t(si.n));
    r.dpdu = t(si.dpdu);
    r.dpdv = t(si.dpdv);
    r.shading.n = FaceForward(Normalize(t(si.shading.n)), r.n);
    r.shading.dpdu = t(si.shading.dpdu);
    r.shading.dpdv = t(si.shading.dpdv);
    r.shading.dndu = t(si.shading.dndu);
    r.shading.dndv = t(si.shading.dndv);
    if (LengthSquared(si.wo) > 0)
        r.wo = Normalize(t(si.wo));
    return r;
}

}  // namespace pbrt
