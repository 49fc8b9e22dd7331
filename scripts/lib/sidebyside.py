"""Renders side by side, each under its label (scripts/plot_side_by_side.py, scripts/compare-pbrt-v4
--side-by-side): the images at their own pixel size, so that noise reads as it is.
"""
import sys

import numpy as np


def srgb(linear):
    """Linear RGB as pbrt_ext writes a PNG: clamped to [0, 1], sRGB-encoded."""
    rgb = np.clip(np.nan_to_num(linear), 0, 1)
    return np.where(rgb <= 0.0031308, 12.92 * rgb, 1.055 * rgb ** (1 / 2.4) - 0.055)


def read_display(path):
    """An image to show: an EXR (or other float image) sRGB-encoded, an 8-bit PNG as it is."""
    import OpenImageIO as oiio
    image = oiio.ImageBuf(path)
    if image.has_error:
        sys.exit(f"cannot read {path}: {image.geterror()}")
    pixels = image.get_pixels(oiio.FLOAT)[:, :, :3]
    if image.spec().format.basetype in (oiio.FLOAT, oiio.HALF, oiio.DOUBLE):
        return srgb(pixels)
    return np.clip(pixels, 0, 1)


def split(image, count):
    """image cut into count equal columns, left to right."""
    width = image.shape[1] // count
    return [image[:, i * width:(i + 1) * width] for i in range(count)]


def compose(panels, out, title=None, dpi=100):
    """panels: [(label, HxWx3 in [0, 1])], shown left to right at one image pixel per output
    pixel, each titled with its label (newlines allowed), title above them all."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    height = max(image.shape[0] for _, image in panels)
    lines = max(label.count("\n") + 1 for label, _ in panels)
    top = 0.18 * lines + (0.25 if title else 0) + 0.06  # inches of text above the images
    gap = 0.08
    # Each panel as wide as its image or its longest label line (about 0.075 in a character at
    # 9 points), whichever is wider; the image centred in it.
    slots = [max(image.shape[1] / dpi, 0.075 * max(len(line) for line in label.split("\n")))
             for label, image in panels]
    fig_w = sum(slots) + gap * (len(panels) + 1)
    if title:
        fig_w = max(fig_w, 0.085 * len(title) + 2 * gap)
    fig_h = height / dpi + top + gap
    fig = plt.figure(figsize=(fig_w, fig_h), dpi=dpi)
    x = (fig_w - sum(slots) - gap * (len(panels) - 1)) / 2
    for (label, image), slot in zip(panels, slots):
        h, w = image.shape[0] / dpi, image.shape[1] / dpi
        ax = fig.add_axes(((x + (slot - w) / 2) / fig_w, gap / fig_h, w / fig_w, h / fig_h))
        ax.imshow(image, interpolation="nearest")
        ax.set_axis_off()
        ax.set_title(label, fontsize=9)
        x += slot + gap
    if title:
        fig.suptitle(title, fontsize=10, y=1 - 0.05 / fig_h, va="top")
    fig.savefig(out, dpi=dpi, pil_kwargs={"optimize": True})
    plt.close(fig)
