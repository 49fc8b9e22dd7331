#!/usr/bin/python3
"""Writes the seed inputs of the fuzz targets whose input format is the harness's own
(fuzz/fabric_target.cpp, fuzz/image_target.cpp): fuzz/seeds/<target>/*.seed. The parser and ply
targets are seeded from the scene and PLY files in tests/ and scenes/ instead (scripts/fuzz).

Run from anywhere: /usr/bin/python3 fuzz/seeds/make_seeds.py (needs oiiotool for the images).
"""
import pathlib
import struct
import subprocess
import tempfile

HERE = pathlib.Path(__file__).resolve().parent

# fuzz/fabric_target.cpp: sampler and normalization name indices, flag bits, then 18 floats.
SAMPLERS = ["uniform", "cosine", "paper", "truncatedsinphi", "best"]
NORMALIZATIONS = ["paper", "unitpeak"]
REGULARIZE, DIFFUSE, IMPORTANCE = 1, 2, 4
ALL_FLAGS = 3 << 3  # BxDFReflTransFlags::All

# fuzz/image_target.cpp: kExtensions, indexed by the first byte.
EXTENSIONS = ["exr", "png", "hdr", "pfm", "tga", "jpg", "ppm", "bmp", "tif"]


def fabric_seed(sampler, normalization="paper", flags=ALL_FLAGS, roughness=0.3, angle=30.0,
                elevation=0.0, color=(0.8, 0.6, 0.4), diffuse=(0.2, 0.3, 0.4),
                wo=(0.3, -0.2, 0.93), wi=(-0.4, 0.1, 0.91), u=(0.37, 0.61, 0.18)):
    head = bytes([SAMPLERS.index(sampler), NORMALIZATIONS.index(normalization), flags])
    values = [roughness, angle, elevation, *color, *diffuse, *wo, *wi, *u]
    return head + struct.pack("<18f", *values)


def fabric_seeds():
    seeds = {}
    for i, sampler in enumerate(SAMPLERS):
        for normalization in NORMALIZATIONS:
            seeds[f"{sampler}_{normalization}"] = fabric_seed(
                sampler, normalization, angle=30.0 * i, elevation=15.0 * i)
    seeds["best_regularized"] = fabric_seed("best", flags=ALL_FLAGS | REGULARIZE, roughness=0.05)
    seeds["best_diffuse_base"] = fabric_seed("best", flags=ALL_FLAGS | DIFFUSE)
    seeds["paper_importance"] = fabric_seed("paper", flags=ALL_FLAGS | IMPORTANCE)
    seeds["best_smooth_roughness0"] = fabric_seed("best", roughness=0.0)
    seeds["best_rough_roughness1"] = fabric_seed("best", roughness=1.0)
    seeds["truncated_grazing_wo"] = fabric_seed("truncatedsinphi", wo=(0.8, 0.6, 1e-6))
    seeds["paper_below_surface"] = fabric_seed("paper", wo=(0.3, -0.2, -0.93), wi=(0.1, 0.4, -0.9))
    seeds["best_wi_along_thread"] = fabric_seed("best", angle=0.0, elevation=40.0,
                                                wi=(0.766044, 0.0, 0.642788))
    seeds["unitpeak_thread_along_normal"] = fabric_seed("best", "unitpeak", elevation=90.0)
    seeds["best_reflection_only"] = fabric_seed("best", flags=1 << 3)
    return seeds


def pfm(width, height):
    """A color PFM: header, then little-endian floats (negative scale), bottom row first."""
    pixels = [v for y in range(height) for x in range(width)
              for v in (x / width, y / height, 0.5)]
    return f"PF\n{width} {height}\n-1.0\n".encode() + struct.pack(f"<{len(pixels)}f", *pixels)


def image_seeds():
    # Small but not trivial: a gradient, so that compressed formats hold real data.
    variants = {ext: ["-d", "uint8"] for ext in EXTENSIONS}
    variants.update({"exr": ["-d", "half"], "hdr": ["-d", "float"]})
    seeds = {}
    with tempfile.TemporaryDirectory() as tmp:
        def make(name, ext, channels, options):
            out = pathlib.Path(tmp) / f"{name}.{ext}"
            subprocess.run(["oiiotool", "--pattern", "fill:topleft=0,0.2,0.4:topright=1,0.5,0"
                            ":bottomleft=0.3,0.3,1:bottomright=0.9,0.9,0.9", "5x4", "3",
                            "--ch", channels, *options, "-o", str(out)], check=True)
            seeds[name] = bytes([EXTENSIONS.index(ext)]) + out.read_bytes()

        for ext in EXTENSIONS:
            if ext != "pfm":  # oiiotool does not write PFM
                make(f"{ext}_rgb", ext, "R,G,B", variants[ext])
        seeds["pfm_rgb"] = bytes([EXTENSIONS.index("pfm")]) + pfm(5, 4)
        make("png_gray", "png", "R", ["-d", "uint8"])
        make("png_rgba16", "png", "R,G,B,A=1.0", ["-d", "uint16"])
        make("exr_float", "exr", "R,G,B", ["-d", "float"])
        make("exr_tiled", "exr", "R,G,B", ["-d", "half", "--tile", "4", "4"])
        # Two subimages make a multi-part file, whose headers are read differently.
        make("exr_multipart", "exr", "R,G,B", ["-d", "half", "--dup", "--siappend"])
        make("tif_float", "tif", "R,G,B", ["-d", "float"])
    return seeds


# fuzz/guidingtree_target.cpp: a tree file after its magic number and bounds
# (pbrt_ext/integrators/sdtree.cpp's Write): spatial nodes (axis, two children, leaf), then per
# leaf a directional tree (record count, node count, per node four children and four energies)
# and its BSDF fraction.
def dtree(weight, nodes, bsdf_fraction=0.5):
    out = struct.pack("<dI", weight, len(nodes))
    for children, sums in nodes:
        out += struct.pack("<4I4d", *children, *sums)
    return out + struct.pack("<f", bsdf_fraction)


def guidingtree_seeds():
    one_leaf = struct.pack("<I4i", 1, 0, 0, 0, 0) + struct.pack("<I", 1)
    two_leaves = struct.pack("<I", 3) + struct.pack("<4i", 0, 1, 2, -1) + \
        struct.pack("<4i", 1, 0, 0, 0) + struct.pack("<4i", 1, 0, 0, 1) + struct.pack("<I", 2)
    uniform = dtree(0, [((0, 0, 0, 0), (0, 0, 0, 0))])
    deep = dtree(100, [((1, 0, 0, 0), (3, 1, 0, 0.5)), ((0, 0, 2, 0), (1, 0, 2, 0)),
                       ((0, 0, 0, 0), (0.25, 0.5, 1, 0.25))], 0.3)
    return {"uniform": one_leaf + uniform, "deep": one_leaf + deep, "two_leaves": two_leaves + deep + uniform}


def write(target, seeds):
    folder = HERE / target
    folder.mkdir(exist_ok=True)
    for old in folder.glob("*.seed"):
        old.unlink()
    for name, data in seeds.items():
        (folder / f"{name}.seed").write_bytes(data)
    print(f"{folder}: {len(seeds)} seeds")


if __name__ == "__main__":
    write("fabric", fabric_seeds())
    write("image", image_seeds())
    write("guidingtree", guidingtree_seeds())
