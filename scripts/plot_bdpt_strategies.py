#!/usr/bin/python3
"""bdpt's strategy images in one figure: docs/img/bdpt_strategies.png.

    /usr/bin/python3 scripts/plot_bdpt_strategies.py [--pbrt-ext build/release/pbrt_ext/cmd/pbrt_ext]
        [--scene scenes/caustic-fabric.pbrt] [--spp 64] [--out docs/img/bdpt_strategies.png]

Renders the scene by bdpt at maxdepth 3 with "visualizeweights" (a copy of the scene file,
written beside it so that its includes resolve, and removed after), then lays out the weighted
image of every (s, t) strategy of depths 1 to 3 (s light vertices, t camera vertices), a row per
depth, each tone-mapped alike (scaled by the full image's 99th percentile, sRGB gamma),
labelled, with the full image first. Needs Debian's python3-matplotlib, python3-numpy and python3-openimageio.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend choice)


MAX_DEPTH = 3


def read_rgb(path):
    image = oiio.ImageBuf(path)
    if image.has_error:
        sys.exit(f"cannot read {path}: {image.geterror()}")
    return image.get_pixels(oiio.FLOAT)[:, :, :3]


def render(pbrt_ext, scene, spp, folder):
    """Renders scene with bdpt's weighted strategy images into folder; returns the image's path."""
    text = open(scene).read()
    integrator = f'Integrator "bdpt" "integer maxdepth" {MAX_DEPTH} "bool visualizeweights" true\n'
    text, count = re.subn(r'^Integrator[^\n]*\n', integrator, text, count=1, flags=re.M)
    if count != 1:
        sys.exit(f"{scene}: no Integrator line to replace")
    copy = os.path.join(os.path.dirname(os.path.abspath(scene)), ".bdpt-strategies.pbrt")
    image = os.path.join(folder, "image.exr")
    try:
        with open(copy, "w") as f:
            f.write(text)
        subprocess.run([pbrt_ext, "--quiet", "--spp", str(spp), "--outfile", image, copy],
                       check=True, cwd=folder)
    finally:
        os.remove(copy)
    return image


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--pbrt-ext", default="build/release/pbrt_ext/cmd/pbrt_ext")
    parser.add_argument("--scene", default="scenes/caustic-fabric.pbrt")
    parser.add_argument("--spp", type=int, default=64)
    parser.add_argument("--out", default="docs/img/bdpt_strategies.png")
    args = parser.parse_args()
    pbrt_ext = os.path.abspath(args.pbrt_ext)
    with tempfile.TemporaryDirectory() as folder:
        full = read_rgb(render(pbrt_ext, args.scene, args.spp, folder))
        # The strategy images go beside the film's file, which --outfile put in folder.
        rows = [[(f"the image (depths 0-{MAX_DEPTH})", full)]]
        for depth in range(1, MAX_DEPTH + 1):
            row = rows[-1] if depth == 1 else []
            for s in range(depth + 3):
                t = depth + 2 - s
                if t == 0 or (s == 1 and t == 1):
                    continue
                name = os.path.join(folder, f"bdpt_d{depth:02d}_s{s:02d}_t{t:02d}.exr")
                row.append((f"depth {depth}: s = {s}, t = {t}", read_rgb(name)))
            if depth > 1:
                rows.append(row)
    scale = 1 / max(np.percentile(full, 99), 1e-6)
    columns = max(len(row) for row in rows)
    height, width = full.shape[:2]
    panel = 2.6
    fig, axes = plt.subplots(len(rows), columns,
                             figsize=(columns * panel, len(rows) * (panel * height / width + 0.25)))
    for ax in axes.flat:
        ax.axis("off")
    for r, row in enumerate(rows):
        for c, (title, image) in enumerate(row):
            axes[r, c].imshow(np.clip(image * scale, 0, 1) ** (1 / 2.2))
            axes[r, c].set_title(title, fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=80)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
