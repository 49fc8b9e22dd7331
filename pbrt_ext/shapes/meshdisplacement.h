// pbrt-v4's displacement of a PLY mesh ("displacement" and "edgelength" on plymesh; its
// TriQuadMesh::Displace): quads split into two triangles; each triangle split at its longest
// edge's midpoint, which its neighbour shares, until every edge is shorter than maxEdge in render
// space; each vertex moved along its normal by the displacement at its object-space point and
// (u, v); then the vertex normals recomputed as the normalized sum of the unit normals of the
// triangles around each vertex.
#pragma once

#include "pbrt_ext/util/ply.h"
#include "pbrt_ext/util/transform.h"

#include <cstdint>
#include <functional>

namespace pbrt {

// Throws std::invalid_argument where the mesh has no per-vertex uv (pbrt-v4 needs them too),
// maxEdge is not positive, or the refinement would make more than maxTriangles triangles.
PlyMesh DisplaceMesh(PlyMesh mesh, const Transform &renderFromObject, Float maxEdge,
                     uint64_t maxTriangles, const std::function<Float(Point3f, Point2f)> &displacement);

}  // namespace pbrt
