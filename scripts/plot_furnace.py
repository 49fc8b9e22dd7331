"""Plots the fabric white-furnace table written by fabric_furnace (the paper's Fig. 2 as a graph).

Usage: /usr/bin/python3 scripts/plot_furnace.py furnace.csv furnace.png
Debian's python3 with python3-matplotlib (scripts/setup installs it).
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(csv_path, png_path):
    curves = defaultdict(list)  # (normalization, azimuth, polar) -> [(roughness, albedo)]
    with open(csv_path, newline="") as f:
        for row in csv.DictReader(f):
            key = (row["normalization"], row["azimuth"], float(row["polar_deg"]))
            curves[key].append((float(row["roughness"]), float(row["albedo"])))
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for ax, norm in zip(axes, ["paper", "unitpeak"]):
        for (n, azimuth, polar), points in sorted(curves.items()):
            if n != norm:
                continue
            if azimuth == "across" and polar > 0:
                continue  # across the thread the albedo does not depend on the polar angle
            points.sort()
            label = ("wo ⊥ thread (any polar angle)" if azimuth == "across"
                     else f"wo {polar:.0f}° from N, along thread")
            ax.plot(*zip(*points), "-" if azimuth == "across" else "--", marker="o",
                    markersize=3, label=label)
        ax.axhline(1.0, color="k", linewidth=0.8)
        ax.set_title(f"FabricBxDF white furnace: {norm} normalization")
        ax.set_xlabel("roughness (n = ceil(1 + 29 (1 - r)²))")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("directional albedo a(wo)")
    axes[1].legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)
    print(f"wrote {png_path}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
