// Loop subdivision on an index-based winged mesh: pbrt-v4's SDVertex/SDFace pointer structure
// becomes arrays, a face's four children are faces 4f..4f+3 of the next level, and a vertex
// keeps its index in every level (edge vertices are appended after them).
#include "pbrt_ext/shapes/loopsubdiv.h"

#include "pbrt_ext/util/math.h"

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

namespace pbrt {

namespace {

constexpr int Next(int i) { return (i + 1) % 3; }
constexpr int Prev(int i) { return (i + 2) % 3; }

// Loop's weight for the one-ring neighbours of an interior vertex. (pbrt-v4 also marks valence-6
// vertices "regular" and gives them 1/16, which is beta(6).)
Float Beta(int valence) { return valence == 3 ? 3.f / 16.f : 3.f / (8.f * valence); }

// The one-ring weight that moves an interior vertex to the limit surface.
Float LoopGamma(int valence) { return 1.f / (valence + 3.f / (8.f * Beta(valence))); }

struct Face {
    std::array<int, 3> v;             // counter-clockwise
    std::array<int, 3> f{-1, -1, -1};  // f[j]: the face across edge (v[j], v[Next(j)]), or -1
};

// One level of the subdivision mesh. Every vertex is on some face (startFace), from which walks
// around it begin; the mesh is an oriented manifold, so each walk is a cycle (an interior vertex)
// or a path that ends at the boundary.
class LoopMesh {
  public:
    LoopMesh(std::vector<Point3f> p, std::vector<Face> faces);
    LoopMesh Refine() const;
    // The limit-surface positions and normals, and the triangles.
    SubdividedMesh Limit() const;
    // This level's own vertices and triangles, without normals.
    SubdividedMesh Control() const { return {p, {}, Indices()}; }

  private:
    LoopMesh() = default;
    std::vector<int> Indices() const;
    int VertexNumber(int face, int vertex) const;
    int NextFace(int face, int vertex) const {
        return faces[face].f[VertexNumber(face, vertex)];
    }
    int PrevFace(int face, int vertex) const {
        return faces[face].f[Prev(VertexNumber(face, vertex))];
    }
    // The vertices around `vertex`, in pbrt-v4's order: for a boundary vertex from one boundary
    // neighbour to the other. Their number is the vertex's valence.
    void OneRing(int vertex, std::vector<int> &ring) const;
    // pbrt-v4's two masks, over a ring that OneRing filled.
    Point3f WeightOneRing(int vertex, Float beta, const std::vector<int> &ring) const;
    Point3f WeightBoundary(int vertex, Float beta, const std::vector<int> &ring) const;
    Point3f EvenVertex(int vertex, std::vector<int> &ring) const;
    Point3f OddVertex(int face, int edge) const;
    Normal3f LimitNormal(int vertex, const std::vector<Point3f> &pLimit,
                         std::vector<int> &ring) const;

    std::vector<Point3f> p;
    std::vector<int> startFace;
    std::vector<char> boundary;
    std::vector<Face> faces;
};

LoopMesh::LoopMesh(std::vector<Point3f> points, std::vector<Face> faceList)
    : p(std::move(points)), startFace(p.size(), -1), faces(std::move(faceList)) {
    // Neighbours through each directed edge's twin; a directed edge seen twice is not a manifold.
    auto key = [](int a, int b) { return (uint64_t(uint32_t(a)) << 32) | uint32_t(b); };
    std::unordered_map<uint64_t, int> faceOfEdge;
    faceOfEdge.reserve(3 * faces.size());
    for (int fi = 0; fi < int(faces.size()); ++fi)
        for (int j = 0; j < 3; ++j) {
            int a = faces[fi].v[j], b = faces[fi].v[Next(j)];
            if (!faceOfEdge.emplace(key(a, b), fi).second)
                throw std::runtime_error(
                    "loopsubdiv: edge " + std::to_string(a) + "-" + std::to_string(b) +
                    " is used twice in the same direction (triangles " +
                    std::to_string(faceOfEdge[key(a, b)]) + " and " + std::to_string(fi) +
                    "): the mesh must be a consistently oriented manifold");
            startFace[a] = fi;
        }
    for (Face &face : faces)
        for (int j = 0; j < 3; ++j)
            if (auto twin = faceOfEdge.find(key(face.v[Next(j)], face.v[j]));
                twin != faceOfEdge.end())
                face.f[j] = twin->second;
    boundary.resize(p.size());
    for (size_t v = 0; v < p.size(); ++v) {
        int f = startFace[v];
        do {
            f = NextFace(f, int(v));
        } while (f != -1 && f != startFace[v]);
        boundary[v] = f == -1;
    }
}

int LoopMesh::VertexNumber(int face, int vertex) const {
    const std::array<int, 3> &v = faces[face].v;
    return v[0] == vertex ? 0 : v[1] == vertex ? 1 : 2;
}

void LoopMesh::OneRing(int vertex, std::vector<int> &ring) const {
    ring.clear();
    int face = startFace[vertex];
    if (!boundary[vertex]) {
        do {
            ring.push_back(faces[face].v[Next(VertexNumber(face, vertex))]);
            face = NextFace(face, vertex);
        } while (face != startFace[vertex]);
        return;
    }
    for (int f2; (f2 = NextFace(face, vertex)) != -1;)
        face = f2;
    ring.push_back(faces[face].v[Next(VertexNumber(face, vertex))]);
    do {
        ring.push_back(faces[face].v[Prev(VertexNumber(face, vertex))]);
        face = PrevFace(face, vertex);
    } while (face != -1);
}

Point3f LoopMesh::WeightOneRing(int vertex, Float beta, const std::vector<int> &ring) const {
    Point3f sum = (1 - ring.size() * beta) * p[vertex];
    for (int r : ring)
        sum += beta * p[r];
    return sum;
}

Point3f LoopMesh::WeightBoundary(int vertex, Float beta, const std::vector<int> &ring) const {
    return (1 - 2 * beta) * p[vertex] + beta * p[ring.front()] + beta * p[ring.back()];
}

Point3f LoopMesh::EvenVertex(int vertex, std::vector<int> &ring) const {
    OneRing(vertex, ring);
    if (boundary[vertex])
        return WeightBoundary(vertex, 1.f / 8.f, ring);
    return WeightOneRing(vertex, Beta(int(ring.size())), ring);
}

Point3f LoopMesh::OddVertex(int face, int edge) const {
    const Face &f = faces[face];
    Point3f a = p[f.v[edge]], b = p[f.v[Next(edge)]];
    if (f.f[edge] == -1)
        return 0.5f * a + 0.5f * b;
    const Face &g = faces[f.f[edge]];
    int opposite = g.v[Prev(VertexNumber(f.f[edge], f.v[Next(edge)]))];
    return 3.f / 8.f * a + 3.f / 8.f * b + 1.f / 8.f * p[f.v[Prev(edge)]] +
           1.f / 8.f * p[opposite];
}

LoopMesh LoopMesh::Refine() const {
    int nv = int(p.size()), nf = int(faces.size());
    LoopMesh child;
    // One new vertex per edge, made by the first of its faces.
    std::vector<std::array<int, 3>> edgeVertex(nf);
    child.p.resize(nv);
    child.boundary = boundary;
    child.startFace.resize(nv);
    for (int fi = 0; fi < nf; ++fi)
        for (int k = 0; k < 3; ++k) {
            int g = faces[fi].f[k];
            if (g != -1 && g < fi) {
                int shared = VertexNumber(g, faces[fi].v[Next(k)]);
                edgeVertex[fi][k] = edgeVertex[g][shared];
                continue;
            }
            edgeVertex[fi][k] = int(child.p.size());
            child.p.push_back(OddVertex(fi, k));
            child.boundary.push_back(g == -1);
            child.startFace.push_back(4 * fi + 3);
        }
    std::vector<int> ring;
    for (int v = 0; v < nv; ++v) {
        child.p[v] = EvenVertex(v, ring);
        child.startFace[v] = 4 * startFace[v] + VertexNumber(startFace[v], v);
    }
    // Face j of a face's children is at its corner j; child 3 is the middle one.
    child.faces.resize(4 * size_t(nf));
    auto childAt = [&](int face, int vertex) {
        return face == -1 ? -1 : 4 * face + VertexNumber(face, vertex);
    };
    for (int fi = 0; fi < nf; ++fi) {
        const Face &f = faces[fi];
        Face *c = &child.faces[4 * fi];
        for (int j = 0; j < 3; ++j) {
            c[j].v[j] = f.v[j];
            c[j].v[Next(j)] = edgeVertex[fi][j];
            c[j].v[Prev(j)] = edgeVertex[fi][Prev(j)];
            c[3].v[j] = edgeVertex[fi][j];
            c[3].f[j] = 4 * fi + Next(j);
            c[j].f[Next(j)] = 4 * fi + 3;
            c[j].f[j] = childAt(f.f[j], f.v[j]);
            c[j].f[Prev(j)] = childAt(f.f[Prev(j)], f.v[j]);
        }
    }
    return child;
}

// pbrt-v4's tangents of the limit surface: Loop's cosine and sine weights around an interior
// vertex, Hoppe et al.'s boundary masks along a boundary.
Normal3f LoopMesh::LimitNormal(int vertex, const std::vector<Point3f> &pLimit,
                               std::vector<int> &ring) const {
    OneRing(vertex, ring);
    int valence = int(ring.size());
    auto P = [&](int k) { return Vector3f(pLimit[ring[k]]); };
    Vector3f pv(pLimit[vertex]), S(0, 0, 0), T(0, 0, 0);
    if (!boundary[vertex]) {
        for (int j = 0; j < valence; ++j) {
            S += std::cos(2 * Pi * j / valence) * P(j);
            T += std::sin(2 * Pi * j / valence) * P(j);
        }
        return Normal3f(Cross(S, T));
    }
    S = P(valence - 1) - P(0);
    if (valence == 2)
        T = P(0) + P(1) - 2 * pv;
    else if (valence == 3)
        T = P(1) - pv;
    else if (valence == 4)
        T = -1 * P(0) + 2 * P(1) + 2 * P(2) - 1 * P(3) - 2 * pv;
    else {
        Float theta = Pi / Float(valence - 1);
        T = std::sin(theta) * (P(0) + P(valence - 1));
        for (int k = 1; k < valence - 1; ++k)
            T += (2 * std::cos(theta) - 2) * std::sin(k * theta) * P(k);
        T = -T;
    }
    return Normal3f(Cross(S, T));
}

SubdividedMesh LoopMesh::Limit() const {
    SubdividedMesh mesh;
    std::vector<int> ring;
    mesh.p.resize(p.size());
    for (size_t v = 0; v < p.size(); ++v) {
        OneRing(int(v), ring);
        mesh.p[v] = boundary[v] ? WeightBoundary(int(v), 1.f / 5.f, ring)
                                : WeightOneRing(int(v), LoopGamma(int(ring.size())), ring);
    }
    mesh.n.resize(p.size());
    for (size_t v = 0; v < p.size(); ++v)
        mesh.n[v] = LimitNormal(int(v), mesh.p, ring);
    mesh.indices = Indices();
    return mesh;
}

std::vector<int> LoopMesh::Indices() const {
    std::vector<int> indices;
    indices.reserve(3 * faces.size());
    for (const Face &f : faces)
        indices.insert(indices.end(), f.v.begin(), f.v.end());
    return indices;
}

// The control mesh's triangles over its used vertices only, renumbered in their order.
LoopMesh ControlMesh(const std::vector<int> &indices, const std::vector<Point3f> &p) {
    if (indices.size() % 3 != 0)
        throw std::runtime_error("loopsubdiv: the number of indices, " +
                                 std::to_string(indices.size()) + ", is not a multiple of 3");
    std::vector<int> renumbered(p.size(), -1);
    for (int index : indices) {
        if (index < 0 || size_t(index) >= p.size())
            throw std::runtime_error("loopsubdiv: vertex index " + std::to_string(index) +
                                     " is out of range (" + std::to_string(p.size()) +
                                     " vertices)");
        renumbered[index] = 0;
    }
    std::vector<Point3f> used;
    for (size_t i = 0; i < p.size(); ++i)
        if (renumbered[i] == 0) {
            renumbered[i] = int(used.size());
            used.push_back(p[i]);
        }
    std::vector<Face> faces(indices.size() / 3);
    for (size_t fi = 0; fi < faces.size(); ++fi) {
        std::array<int, 3> &v = faces[fi].v;
        for (int j = 0; j < 3; ++j)
            v[j] = renumbered[indices[3 * fi + j]];
        if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
            throw std::runtime_error("loopsubdiv: triangle " + std::to_string(fi) +
                                     " repeats a vertex");
    }
    return LoopMesh(std::move(used), std::move(faces));
}

LoopMesh Refined(int nLevels, const std::vector<int> &indices, const std::vector<Point3f> &p) {
    LoopMesh mesh = ControlMesh(indices, p);
    for (int level = 0; level < nLevels; ++level)
        mesh = mesh.Refine();
    return mesh;
}

}  // namespace

SubdividedMesh LoopSubdivide(int nLevels, const std::vector<int> &indices,
                             const std::vector<Point3f> &p) {
    return Refined(nLevels, indices, p).Limit();
}

SubdividedMesh LoopRefine(int nLevels, const std::vector<int> &indices,
                          const std::vector<Point3f> &p) {
    return Refined(nLevels, indices, p).Control();
}

}  // namespace pbrt
