#!/usr/bin/python3
"""A render with its rows and columns named: text above given pixel columns and left of given
pixel rows, and a title (docs/img/fabric_furnace_scene.png: roughness per column, normalization
per row). The render keeps its pixel size.

    /usr/bin/python3 scripts/label_render.py IMAGE OUT.png [--columns X=LABEL ...]
                                             [--rows Y=LABEL ...] [--title T]

IMAGE is pbrt_ext's EXR (shown clamped and sRGB-encoded, as it writes a PNG) or an 8-bit PNG; X
and Y are pixel coordinates in it. Needs Debian's python3-matplotlib, python3-numpy and
python3-openimageio.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from sidebyside import read_display  # noqa: E402  (after the path)


def positions(entries, parser):
    out = []
    for entry in entries:
        where, sep, text = entry.partition("=")
        try:
            out.append((float(where), text.replace("\\n", "\n")))
        except ValueError:
            sep = ""
        if not sep:
            parser.error(f"{entry}: expected PIXEL=LABEL")
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("image")
    parser.add_argument("out")
    parser.add_argument("--columns", nargs="*", default=[], metavar="X=LABEL")
    parser.add_argument("--rows", nargs="*", default=[], metavar="Y=LABEL")
    parser.add_argument("--title")
    args = parser.parse_args()
    columns, rows = positions(args.columns, parser), positions(args.rows, parser)
    image = read_display(args.image)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    dpi = 100
    height, width = image.shape[:2]
    left = 0.12 + 0.07 * max((len(t) for _, t in rows), default=0)  # inches of row labels
    top = (0.28 if columns else 0.05) + (0.3 if args.title else 0)
    fig_w, fig_h = width / dpi + left + 0.1, height / dpi + top + 0.1
    if args.title:  # about 0.085 in a character at 10 points
        left += max(0.0, 0.085 * len(args.title) - fig_w) / 2
        fig_w = max(fig_w, 0.085 * len(args.title))
    fig = plt.figure(figsize=(fig_w, fig_h), dpi=dpi)
    # The axes one pixel wider than the render on every side, for a thin frame (a render may be
    # white to its edges) that covers none of its pixels.
    ax = fig.add_axes(((left - 1 / dpi) / fig_w, (0.1 - 1 / dpi) / fig_h,
                       (width + 2) / dpi / fig_w, (height + 2) / dpi / fig_h))
    ax.imshow(image, interpolation="nearest")
    ax.set_xlim(-1.5, width + 0.5)
    ax.set_ylim(height + 0.5, -1.5)
    for spine in ax.spines.values():
        spine.set(color="0.75", linewidth=0.5)
    ax.set_xticks([x for x, _ in columns], [t for _, t in columns], fontsize=9)
    ax.set_yticks([y for y, _ in rows], [t for _, t in rows], fontsize=9)
    ax.xaxis.tick_top()
    ax.tick_params(length=0)
    if args.title:
        fig.suptitle(args.title, fontsize=10, y=1 - 0.05 / fig_h, va="top")
    fig.savefig(args.out, dpi=dpi, pil_kwargs={"optimize": True})
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
