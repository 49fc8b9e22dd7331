#!/usr/bin/env python3
"""Writes the binary inputs of tests/resource_limits_test.cpp: files whose headers claim far more
than they hold, so that a reader that trusts the header before checking it allocates without bound.

Run from anywhere; the files are committed, so this is needed only to change them.
"""
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)


def png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def huge_png():
    # A valid header (with its CRC) for 60000 x 60000 8-bit gray pixels: 3.6 GB in the file's
    # own format, below OpenImageIO's 32 GB sanity limit, so that our guard is the one that fires;
    # the pixel data is a compressed empty stream.
    ihdr = struct.pack(">IIBBBBB", 60000, 60000, 8, 0, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) +
            png_chunk(b"IDAT", zlib.compress(b"")) + png_chunk(b"IEND", b""))


def huge_face_count_ply():
    # 2^31 faces declared, three vertices and one face present.
    header = "\n".join(["ply", "format binary_little_endian 1.0",
                        "comment the header declares 2^31 faces; the body holds one",
                        "element vertex 3", "property float x", "property float y",
                        "property float z", "element face 2147483648",
                        "property list uchar int vertex_indices", "end_header"]) + "\n"
    vertices = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    face = struct.pack("<B3i", 3, 0, 1, 2)
    return header.encode() + vertices + face


def volume_dds():
    # A 2 x 2 x 2 volume texture (DDSCAPS2_VOLUME) of 32-bit RGB: a reader that sizes its buffer
    # for one slice must refuse it.
    width, height, depth = 2, 2, 2
    caps, height_flag, width_flag, pixel_format, depth_flag = 0x1, 0x2, 0x4, 0x1000, 0x800000
    rgb = 0x40
    pixel = struct.pack("<8I", 32, rgb, 0, 32, 0xFF0000, 0xFF00, 0xFF, 0)
    texture, complex_surface, volume = 0x1000, 0x8, 0x200000
    header = (struct.pack("<7I", 124, caps | height_flag | width_flag | pixel_format | depth_flag,
                          height, width, width * 4, depth, 1) + bytes(11 * 4) + pixel +
              struct.pack("<5I", texture | complex_surface, volume, 0, 0, 0))
    return b"DDS " + header + bytes(width * height * depth * 4)


write("limit_image_huge.png", huge_png())
write("limit_image_volume.dds", volume_dds())
write("limit_ply_faces.ply", huge_face_count_ply())
