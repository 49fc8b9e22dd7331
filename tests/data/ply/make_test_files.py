#!/usr/bin/env python3
"""Writes the PLY test inputs: good meshes here, malformed ones as ../bad/ply_*.ply.

Run from anywhere; the files are committed, so this is needed only to change them. The good
files hold one mesh in three encodings (ascii, binary little and big endian) with different
property types, texture-coordinate names and element orders; tests/ply_test.cpp expects them
all to decode to the same PlyMesh.
"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
BAD = os.path.join(HERE, "..", "bad")

# Values exactly representable in float32, so that every encoding decodes identically.
P = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 1.5, 0.25), (-0.5, 0.5, -1.25)]
N = [(0, 0, 1), (0, 0, 1), (0, 1, 0), (0, 1, 0), (1, 0, 0), (-1, 0, 0)]
UV = [(0, 0), (1, 0), (1, 1), (0, 1), (0.5, 0.75), (0.25, 0.125)]
FACES = [(0, 1, 2, 3), (3, 2, 4), (0, 3, 5)]  # a quad, then two triangles
FACE_INDICES = [7, 8, 9]

STRUCT = {"char": "b", "uchar": "B", "short": "h", "ushort": "H", "int": "i", "uint": "I",
          "float": "f", "double": "d", "int8": "b", "uint8": "B", "int16": "h",
          "uint16": "H", "int32": "i", "uint32": "I", "float32": "f", "float64": "d"}


def write(path, data):
    with open(path, "wb") as f:
        f.write(data)


def header(fmt, elements, newline="\n", comments=()):
    lines = ["ply", f"format {fmt} 1.0", *comments]
    for name, count, props in elements:
        lines.append(f"element {name} {count}")
        lines += [f"property {p}" for p in props]
    lines.append("end_header")
    return newline.join(lines).encode() + newline.encode()


def ascii_mesh():
    elements = [("vertex", len(P), ["float x", "float y", "float z", "float nx", "float ny",
                                    "float nz", "float u", "float v", "uchar red"]),
                ("face", len(FACES), ["list uchar int vertex_indices", "int face_indices"]),
                ("edge", 2, ["int vertex1", "int vertex2"])]
    body = "".join(f"{p[0]} {p[1]} {p[2]} {n[0]} {n[1]} {n[2]} {uv[0]} {uv[1]} 255\n"
                   for p, n, uv in zip(P, N, UV))
    body += "".join(f"{len(f)} {' '.join(map(str, f))} {i}\n" for f, i in zip(FACES, FACE_INDICES))
    body += "0 1\n1 2\n"
    return header("ascii", elements, comments=["comment made by make_test_files.py",
                                                "obj_info test mesh"]) + body.encode()


def binary_le_mesh():
    # Windows line ends in the header, double positions, "s t" texture coordinates, a skipped
    # list property after the indices.
    elements = [("vertex", len(P), ["double x", "double y", "double z", "float nx", "float ny",
                                    "float nz", "float s", "float t"]),
                ("face", len(FACES), ["list uint int vertex_indices", "uint face_indices",
                                      "list uchar float weights"])]
    body = b"".join(struct.pack("<3d3f2f", *p, *n, *uv) for p, n, uv in zip(P, N, UV))
    for f, i in zip(FACES, FACE_INDICES):
        body += struct.pack(f"<I{len(f)}iIB2f", len(f), *f, i, 2, 0.5, 0.25)
    return header("binary_little_endian", elements, newline="\r\n") + body


def binary_be_mesh():
    # Faces before vertices, face_indices before vertex_indices, sized type names and
    # "texture_u texture_v".
    elements = [("face", len(FACES), ["int16 face_indices", "list uint8 uint32 vertex_indices"]),
                ("vertex", len(P), ["float32 x", "float32 y", "float32 z", "float32 nx",
                                    "float32 ny", "float32 nz", "float32 texture_u",
                                    "float32 texture_v"])]
    body = b"".join(struct.pack(f">hB{len(f)}I", i, len(f), *f) for f, i in zip(FACES, FACE_INDICES))
    body += b"".join(struct.pack(">8f", *p, *n, *uv) for p, n, uv in zip(P, N, UV))
    return header("binary_big_endian", elements) + body


TRIANGLE_HEADER = ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                   "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                   "end_header\n")
TRIANGLE_BODY = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"


def bad_files():
    tri, body = TRIANGLE_HEADER, TRIANGLE_BODY
    yield "bad_magic", "plx\n" + tri[4:] + body
    yield "unknown_format", tri.replace("ascii 1.0", "binary_middle_endian 1.0") + body
    yield "bad_version", tri.replace("ascii 1.0", "ascii 2.0") + body
    yield "unknown_type", tri.replace("float y", "int128 y") + body
    yield "missing_y", tri.replace("property float y\n", "") + "0 0\n1 0\n0 1\n3 0 1 2\n"
    yield "no_faces", tri.replace("element face 1\nproperty list uchar int vertex_indices\n", "") \
        + "0 0 0\n1 0 0\n0 1 0\n"
    yield "no_vertex_indices", tri.replace("list uchar int vertex_indices", "int material") \
        + "0 0 0\n1 0 0\n0 1 0\n5\n"
    yield "float_indices", tri.replace("list uchar int", "list uchar float") + body
    yield "float_count", tri.replace("list uchar int", "list float int") + body
    yield "missing_end_header", tri.replace("end_header\n", "")
    yield "missing_format", tri.replace("format ascii 1.0\n", "") + body
    yield "property_before_element", tri.replace("ply\n", "ply\nproperty float w\n", 1) + body
    yield "unknown_keyword", tri.replace("end_header", "edn_header") + body
    yield "bad_element_count", tri.replace("vertex 3", "vertex -3") + body
    yield "duplicate_element", tri.replace("element face", "element vertex") + body
    yield "duplicate_property", tri.replace("float z", "float x") + body
    yield "malformed_property", tri.replace("property float z", "property float") + body
    yield "list_position", tri.replace("property float z", "property list uchar float z") + body
    yield "truncated_ascii", tri + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n"
    yield "bad_value", tri + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n"
    yield "nonfinite", tri + "0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n"
    yield "uchar_overflow", tri + "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n"
    yield "index_out_of_range", tri + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"
    yield "negative_index", tri + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"
    yield "pentagon", tri + "0 0 0\n1 0 0\n0 1 0\n5 0 1 2 0 1\n"
    yield "trailing_data", tri + body + "7\n"
    le = TRIANGLE_HEADER.replace("ascii", "binary_little_endian").encode()
    verts = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    yield "truncated_binary", le + verts + struct.pack("<Bii", 3, 0, 1)
    yield "huge_count", le.replace(b"vertex 3", b"vertex 1000000000") + verts
    yield "binary_index_out_of_range", le + verts + struct.pack("<B3i", 3, 0, 1, 7)
    yield "binary_negative_count", (le.replace(b"uchar int", b"char int") + verts
                                    + struct.pack("<b3i", -3, 0, 1, 2))
    # The remaining error paths of the reader, one file each (docs/coverage.md).
    yield "duplicate_format", tri.replace("format ascii 1.0\n", "format ascii 1.0\n" * 2) + body
    yield "malformed_format", tri.replace("ascii 1.0", "ascii") + body
    yield "malformed_element", tri.replace("element vertex 3", "element vertex") + body
    yield "malformed_list", tri.replace("uchar int vertex_indices", "uchar vertex_indices") + body
    yield "word_element_count", tri.replace("vertex 3", "vertex three") + body
    yield "scalar_indices", tri.replace("list uchar int vertex_indices", "int vertex_indices") \
        + "0 0 0\n1 0 0\n0 1 0\n5\n"
    with_face_index = tri.replace("vertex_indices\n", "vertex_indices\nproperty {} face_indices\n")
    yield "list_face_indices", with_face_index.format("list uchar int") + body.replace(
        "0 1 2\n", "0 1 2 1 7\n")
    yield "float_face_indices", with_face_index.format("float") + body.replace("0 1 2\n", "0 1 2 7\n")
    yield "face_index_out_of_range", with_face_index.format("uint") + body.replace(
        "0 1 2\n", "0 1 2 4294967295\n")
    yield "no_vertex_element", tri.replace(
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n", "") + "3 0 1 2\n"
    yield "empty_vertex", tri.replace("vertex 3", "vertex 0") + "3 0 1 2\n"
    yield "empty_face", tri.replace("face 1", "face 0") + "0 0 0\n1 0 0\n0 1 0\n"
    yield "too_many_vertices", tri.replace("vertex 3", "vertex 2147483648") + body
    yield "empty", ""
    yield "header_only", tri.rstrip("\n")
    yield "uchar_negative", tri + "0 0 0\n1 0 0\n0 1 0\n-1 0 1 2\n"
    yield "fractional_index", tri + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n"
    yield "bare_property", tri.replace("property float z", "property") + body
    yield "binary_nonfinite", le + struct.pack("<9f", 0, 0, 0, 1, float("nan"), 0, 0, 1, 0) \
        + struct.pack("<B3i", 3, 0, 1, 2)
    # A skipped list whose items run past the end of the file.
    yield "binary_truncated_skip", (le.replace(b"vertex_indices\n",
                                               b"vertex_indices\nproperty list uchar float weights\n")
                                    + verts + struct.pack("<B3iBf", 3, 0, 1, 2, 5, 0.5))


def main():
    write(os.path.join(HERE, "mesh_ascii.ply"), ascii_mesh())
    write(os.path.join(HERE, "mesh_binary_le.ply"), binary_le_mesh())
    write(os.path.join(HERE, "mesh_binary_be.ply"), binary_be_mesh())
    write(os.path.join(HERE, "triangle.ply"), (TRIANGLE_HEADER + TRIANGLE_BODY).encode())
    for name, data in bad_files():
        write(os.path.join(BAD, f"ply_{name}.ply"), data.encode() if isinstance(data, str) else data)


if __name__ == "__main__":
    main()
