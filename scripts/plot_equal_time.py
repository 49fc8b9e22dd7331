"""Equal-time crops side by side (the paper's Fig. 3 comparison): the same region of renders that
each took the same time with a different fabric sampler, each labelled with what rendered it and
the samples per pixel and seconds it reached.

Usage: /usr/bin/python3 scripts/plot_equal_time.py out.png x0 x1 y0 y1 label=image.exr [...]
                                                    [--title TITLE]
The crop is in pixels (x0 x1 y0 y1, half-open). The images are pbrt_ext's EXR output: their
samplesPerPixel and renderTimeSeconds (written by every render, e.g. one stopped by
--time-limit) label the panels, and the pixels are shown as pbrt_ext writes a PNG (clamped,
sRGB). The title defaults to the scene named in the first image. Needs Debian's
python3-matplotlib, python3-numpy and python3-openimageio.
"""
import argparse
import os
import sys

import numpy as np
import OpenImageIO as oiio

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_render(path):
    """(sRGB pixels in [0, 1], samples per pixel, seconds, scene) of one of pbrt_ext's EXRs."""
    image = oiio.ImageBuf(path)
    if image.has_error:
        sys.exit(f"cannot read {path}: {image.geterror()}")
    spec = image.spec()
    spp, seconds = spec.getattribute("samplesPerPixel"), spec.getattribute("renderTimeSeconds")
    if spp is None or seconds is None:
        sys.exit(f"{path}: no samplesPerPixel or renderTimeSeconds (render an EXR with pbrt_ext)")
    rgb = np.clip(np.nan_to_num(image.get_pixels(oiio.FLOAT)[:, :, :3]), 0, 1)
    srgb = np.where(rgb <= 0.0031308, 12.92 * rgb, 1.055 * rgb ** (1 / 2.4) - 0.055)
    return srgb, int(spp), float(seconds), spec.getattribute("scene")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out")
    parser.add_argument("crop", nargs=4, type=int, metavar="x0 x1 y0 y1")
    parser.add_argument("panels", nargs="+", metavar="label=image.exr")
    parser.add_argument("--title", help="(default: equal render time, and the scene's file)")
    args = parser.parse_args()
    x0, x1, y0, y1 = args.crop
    panels = []
    for arg in args.panels:
        if "=" not in arg:
            parser.error(f"{arg}: expected label=image.exr")
        label, path = arg.split("=", 1)
        panels.append((label, *read_render(path)))
    fig, axes = plt.subplots(1, len(panels), figsize=(3.2 * len(panels), 3.9), squeeze=False,
                             layout="constrained")
    for ax, (label, image, spp, seconds, _) in zip(axes.flat, panels):
        ax.imshow(image[y0:y1, x0:x1], interpolation="nearest")
        ax.set_title(f"{label}\n{spp} spp in {seconds:.2f} s", fontsize=10)
        ax.set_axis_off()
    scene = panels[0][4]
    title = args.title or ("equal render time" + (f": {os.path.basename(scene)}" if scene else ""))
    fig.suptitle(title, fontsize=11)
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
