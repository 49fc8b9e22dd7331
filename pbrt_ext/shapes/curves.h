// Curves (pbrt-v4's Curve shape: hair, fur, grass, yarn), intersected by Embree's own curve
// primitives: "flat" curves as Embree's ray-facing flat curves, "cylinder" curves as its round
// (swept-circle) curves, "ribbon" curves as its normal-oriented curves. Every curve pbrt-v4
// reads (Bézier or uniform B-spline, degree 2 or 3) is stored as cubic Bézier segments in world
// space. The interaction at a hit is pbrt-v4's: u runs along each segment, v across the width,
// dp/du is the curve's tangent, dp/dv spans the width (facing the ray for flat and cylinder
// curves, turned about the tangent for a cylinder's round look, along the ribbon's normal
// otherwise).
//
// Where this differs from pbrt-v4, and why: pbrt-v4 intersects every type as a ray-facing strip
// (narrowed by the ribbon's cosine); Embree's round and normal-oriented curves are the real
// surfaces, so hit distances differ by up to the curve's radius and a ribbon seen at a slant
// has its true outline. Widths are object-space widths times the transform's mean scale
// (cube root of its determinant): a curve keeps a round cross-section under any transform.
#pragma once

#include "pbrt_ext/interaction.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/util/transform.h"
#include "pbrt_ext/util/vecmath.h"

#include <string>
#include <vector>

namespace pbrt {

enum class CurveType { Flat, Cylinder, Ribbon };

// A curve as the scene file gives it, in object space.
struct CurveDescription {
    std::vector<Point3f> p;
    std::string basis = "bezier";  // or "bspline"
    int degree = 3;                // 2 or 3
    CurveType type = CurveType::Flat;
    std::vector<Normal3f> n;  // ribbons: one per segment end (segments + 1)
    Float width0 = 1, width1 = 1;
};

// World-space cubic Bézier segments: cp holds 4 control points per segment, width 2 values per
// segment (at u = 0 and u = 1), n 2 unit normals per segment for ribbons.
struct CurveMesh {
    CurveType type;
    std::vector<Point3f> cp;
    std::vector<Float> width;
    std::vector<Normal3f> n;
    bool reverseOrientation = false, transformSwapsHandedness = false;

    int NumSegments() const { return int(cp.size() / 4); }
    std::string ToString() const;
};

// Throws std::runtime_error, with pbrt-v4's conditions, for a degree other than 2 or 3, an
// unknown basis, a control point count the basis cannot use, ribbon normals missing or of the
// wrong count, or widths that are negative or not finite.
CurveMesh MakeCurveMesh(const Transform &worldFromObject, bool reverseOrientation,
                        const CurveDescription &curve);

// The interaction where the ray met segment `segment` at parameter u and ray distance t.
SurfaceInteraction CurveInteraction(const CurveMesh &mesh, int segment, Float u, const Ray &ray,
                                    Float t);

}  // namespace pbrt
