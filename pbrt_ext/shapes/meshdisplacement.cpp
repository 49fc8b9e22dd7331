#include "pbrt_ext/shapes/meshdisplacement.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

namespace pbrt {

namespace {

// Quads (listed as bilinear patches: p00 p10 p01 p11) as two triangles each.
void QuadsToTriangles(PlyMesh &mesh) {
    const std::vector<int> &q = mesh.quadIndices;
    for (size_t i = 0; i + 3 < q.size(); i += 4)
        mesh.triIndices.insert(mesh.triIndices.end(), {q[i], q[i + 1], q[i + 3], q[i], q[i + 3], q[i + 2]});
    mesh.quadIndices.clear();
}

void ComputeNormals(PlyMesh &mesh) {
    mesh.n.assign(mesh.p.size(), Normal3f(0, 0, 0));
    const std::vector<int> &t = mesh.triIndices;
    for (size_t i = 0; i + 2 < t.size(); i += 3) {
        Normal3f n(Cross(mesh.p[size_t(t[i + 1])] - mesh.p[size_t(t[i])],
                         mesh.p[size_t(t[i + 2])] - mesh.p[size_t(t[i + 1])]));
        if (LengthSquared(n) == 0) continue;
        n = Normalize(n);
        for (int k = 0; k < 3; ++k) mesh.n[size_t(t[i + size_t(k)])] += n;
    }
    for (Normal3f &n : mesh.n)
        if (LengthSquared(n) > 0) n = Normalize(n);
}

void TooMany(uint64_t maxTriangles) {
    throw std::invalid_argument("displacing the mesh makes more than " + std::to_string(maxTriangles) +
                                " triangles, more than memory allows; expected a larger \"edgelength\"");
}

class Refiner {
  public:
    Refiner(PlyMesh &mesh, const Transform &renderFromObject, Float maxEdge, uint64_t maxTriangles)
        : mesh(mesh), renderFromObject(renderFromObject), maxEdge(maxEdge), maxTriangles(maxTriangles) {}

    // Splits triangle (v0, v1, v2) at its longest edge until every edge is short enough,
    // appending the pieces to triangles.
    void Refine(int v0, int v1, int v2, std::vector<int> &triangles) {
        Float d01 = Length(v0, v1), d12 = Length(v1, v2), d20 = Length(v2, v0);
        if (d01 < maxEdge && d12 < maxEdge && d20 < maxEdge) {
            if (triangles.size() / 3 >= maxTriangles) TooMany(maxTriangles);
            triangles.insert(triangles.end(), {v0, v1, v2});
            return;
        }
        // The longest edge first, keeping the winding.
        std::array<int, 3> v = d01 > d12 ? (d01 > d20 ? std::array{v0, v1, v2} : std::array{v2, v0, v1})
                                         : (d12 > d20 ? std::array{v1, v2, v0} : std::array{v2, v0, v1});
        int mid = Midpoint(v[0], v[1]);
        Refine(v[0], mid, v[2], triangles);
        Refine(mid, v[1], v[2], triangles);
    }

  private:
    Float Length(int a, int b) const {
        return Distance(renderFromObject(mesh.p[size_t(a)]), renderFromObject(mesh.p[size_t(b)]));
    }
    // The edge's midpoint vertex, made once for both triangles that share the edge.
    int Midpoint(int a, int b) {
        uint64_t key = (uint64_t(uint32_t(std::min(a, b))) << 32) | uint32_t(std::max(a, b));
        auto [it, inserted] = midpoints.try_emplace(key, int(mesh.p.size()));
        if (!inserted) return it->second;
        size_t i = size_t(a), j = size_t(b);
        mesh.p.push_back((mesh.p[i] + mesh.p[j]) / 2);
        Normal3f n = mesh.n[i] + mesh.n[j];
        mesh.n.push_back(LengthSquared(n) > 0 ? Normalize(n) : n);
        mesh.uv.push_back((mesh.uv[i] + mesh.uv[j]) / 2);
        return it->second;
    }

    PlyMesh &mesh;
    const Transform &renderFromObject;
    Float maxEdge;
    uint64_t maxTriangles;
    std::unordered_map<uint64_t, int> midpoints;
};

// Before refining: a triangle whose longest edge is L makes about (L / maxEdge)^2 pieces.
void CheckTriangleEstimate(const PlyMesh &mesh, const Transform &renderFromObject, Float maxEdge,
                           uint64_t maxTriangles) {
    double estimate = 0;
    const std::vector<int> &t = mesh.triIndices;
    for (size_t i = 0; i + 2 < t.size(); i += 3) {
        auto q = [&](size_t k) { return renderFromObject(mesh.p[size_t(t[i + k])]); };
        double longest = std::max({Distance(q(0), q(1)), Distance(q(1), q(2)), Distance(q(2), q(0))});
        estimate += std::max(1.0, (longest / maxEdge) * (longest / maxEdge));
    }
    if (estimate > double(maxTriangles)) TooMany(maxTriangles);
}

}  // namespace

PlyMesh DisplaceMesh(PlyMesh mesh, const Transform &renderFromObject, Float maxEdge,
                     uint64_t maxTriangles, const std::function<Float(Point3f, Point2f)> &displacement) {
    if (mesh.uv.empty())
        throw std::invalid_argument("displacement needs the mesh's per-vertex uv (as in pbrt-v4)");
    if (!(maxEdge > 0))
        throw std::invalid_argument("\"edgelength\" must be positive");
    QuadsToTriangles(mesh);
    CheckTriangleEstimate(mesh, renderFromObject, maxEdge, maxTriangles);
    if (mesh.n.empty()) ComputeNormals(mesh);
    std::vector<int> triangles, original = std::move(mesh.triIndices);
    Refiner refiner(mesh, renderFromObject, maxEdge, maxTriangles);
    for (size_t i = 0; i + 2 < original.size(); i += 3)
        refiner.Refine(original[i], original[i + 1], original[i + 2], triangles);
    mesh.triIndices = std::move(triangles);
    mesh.faceIndices.clear();  // one per original face: they no longer match
    tbb::parallel_for(size_t(0), mesh.p.size(), [&](size_t i) {
        mesh.p[i] += displacement(mesh.p[i], mesh.uv[i]) * Vector3f(mesh.n[i]);
    });
    ComputeNormals(mesh);
    return mesh;
}

}  // namespace pbrt
