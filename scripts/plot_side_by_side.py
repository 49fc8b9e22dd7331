#!/usr/bin/python3
"""Renders side by side, each labelled (docs/img/port_pbrt_v4_side_by_side.png, port_pbrt_v3.png).

    /usr/bin/python3 scripts/plot_side_by_side.py OUT.png LABEL=IMAGE [LABEL=IMAGE ...]
                                                  [--title T]
    /usr/bin/python3 scripts/plot_side_by_side.py OUT.png --split IMAGE LABEL [LABEL ...]
                                                  [--title T]

The first form puts the images (EXR, shown clamped and sRGB-encoded as pbrt_ext writes a PNG, or
8-bit PNG) left to right under their labels; the second cuts one image already side by side into
as many equal columns as labels and labels each. "\\n" in a label starts a new line. The images keep
their pixel size. scripts/compare-pbrt-v4 --side-by-side FOLDER writes one per scene itself. Needs
Debian's python3-matplotlib, python3-numpy and python3-openimageio.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from sidebyside import compose, read_display, split  # noqa: E402  (after the path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out")
    parser.add_argument("panels", nargs="+", metavar="LABEL=IMAGE (or LABEL with --split)")
    parser.add_argument("--split", metavar="IMAGE",
                        help="one image to cut into the labelled columns")
    parser.add_argument("--title")
    args = parser.parse_args()
    labels = [p.split("=", 1)[0].replace("\\n", "\n") for p in args.panels]
    if args.split:
        images = split(read_display(args.split), len(labels))
    else:
        if any("=" not in p for p in args.panels):
            parser.error("each panel is LABEL=IMAGE (or give --split IMAGE and labels)")
        images = [read_display(p.split("=", 1)[1]) for p in args.panels]
    compose(list(zip(labels, images)), args.out, args.title)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
