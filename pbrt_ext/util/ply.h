// PLY polygon meshes (pbrt-v4's TriQuadMesh::ReadPLY, host only), without a PLY library: the
// whole file is read at once and decoded in memory.
//
// Formats: ascii, binary_little_endian, binary_big_endian (version 1.0). Property types: char,
// uchar, short, ushort, int, uint, float, double and their sized aliases int8 ... float64.
// From the "vertex" element: x y z (required), nx ny nz, and texture coordinates under the first
// complete pair of u v, s t, texture_u texture_v, texture_s texture_t (pbrt-v4's search order).
// From the "face" element: the list vertex_indices (triangles and quads only) and the optional
// scalar face_indices. Other elements and properties are skipped.
//
// Malformed input throws ParseError located in the file: header problems at their line and
// column, ascii body problems at the offending value; binary body problems carry no line and
// name the byte offset instead. Body messages name the element as e.g. "face[12]" (0-based).
#pragma once

#include "pbrt_ext/util/vecmath.h"

#include <string>
#include <string_view>
#include <vector>

namespace pbrt {

// n and uv are empty or one per vertex. quadIndices use pbrt-v4's bilinear-patch order: the
// file's face (v0, v1, v2, v3) is stored as (v0, v1, v3, v2). faceIndices is empty or one per
// face, the triangles' values first and then the quads', so that entry i belongs to triangle i
// and entry triIndices.size() / 3 + j to quad j.
struct PlyMesh {
    std::vector<Point3f> p;
    std::vector<Normal3f> n;
    std::vector<Point2f> uv;
    std::vector<int> triIndices, quadIndices;
    std::vector<int> faceIndices;
};

// Reads and decodes filename; throws ParseError for unreadable or malformed files.
PlyMesh ReadPly(const std::string &filename);

// Decodes a PLY file already in memory; filename is used in error messages only.
PlyMesh ParsePly(std::string_view contents, const std::string &filename);

}  // namespace pbrt
