// Loop subdivision surfaces (pbrt-v4's src/pbrt/util/loopsubdiv.h, the "loopsubdiv" shape):
// a triangle control mesh refined `levels` times by Loop's rules, its vertices then moved to the
// limit surface and given the limit surface's normals.
//
// The rules are pbrt-v4's (book, 3rd edition, section 3.8): interior even vertices by the one-ring
// rule with Loop's beta (3/16 at valence 3, 3/(8 valence) otherwise), boundary even vertices by
// (1/8, 3/4, 1/8) along the boundary, odd vertices by (3/8, 3/8, 1/8, 1/8), or the midpoint on a
// boundary edge. pbrt-v4 has no crease rules, and so has none here.
#pragma once

#include "pbrt_ext/util/vecmath.h"

#include <vector>

namespace pbrt {

// An object-space triangle mesh with one limit normal per vertex (unnormalized, as pbrt-v4
// computes them; zero where the limit surface is degenerate).
struct SubdividedMesh {
    std::vector<Point3f> p;
    std::vector<Normal3f> n;
    std::vector<int> indices;
};

// Refines the control mesh (3 indices per triangle into p) nLevels >= 0 times. Vertices that no
// triangle uses are dropped; the others keep their order. The control mesh must be an oriented 2-manifold with boundary:
// throws std::runtime_error for indices out of range or not a multiple of 3, a triangle that
// repeats a vertex, or an edge traversed twice in the same direction (three or more triangles on
// one edge, or neighbours of opposite orientation), any of which pbrt-v4 would crash on.
SubdividedMesh LoopSubdivide(int nLevels, const std::vector<int> &indices,
                             const std::vector<Point3f> &p);

// The same refinement without the final move to the limit surface: the level-nLevels control
// vertices (the used control vertices first, in their order, then one per edge of each level),
// and no normals.
SubdividedMesh LoopRefine(int nLevels, const std::vector<int> &indices,
                          const std::vector<Point3f> &p);

}  // namespace pbrt
