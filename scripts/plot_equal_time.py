"""Equal-time crops side by side (the paper's Fig. 3 comparison): the same region of renders that
each took the same time with a different fabric sampler.

Usage: /usr/bin/python3 scripts/plot_equal_time.py out.png x0 x1 y0 y1 label=image.png [label=image.png ...]
The crop is in pixels (x0 x1 y0 y1, half-open); images are the renderer's PNG output.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def main(argv):
    if len(argv) < 7:
        sys.exit(__doc__)
    out = argv[1]
    x0, x1, y0, y1 = (int(v) for v in argv[2:6])
    panels = [arg.split("=", 1) for arg in argv[6:]]
    fig, axes = plt.subplots(1, len(panels), figsize=(3.2 * len(panels), 3.4))
    for ax, (label, path) in zip(axes, panels):
        image = mpimg.imread(path)
        ax.imshow(image[y0:y1, x0:x1], interpolation="nearest")
        ax.set_title(label, fontsize=10)
        ax.set_axis_off()
    fig.suptitle("equal render time, fabric cylinder (roughness 0.1)", fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv)
