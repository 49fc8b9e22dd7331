"""Plots the fabric white-furnace table written by fabric_furnace (the paper's Fig. 2 as a graph).

Usage: /usr/bin/python3 scripts/plot_furnace.py furnace.csv furnace.png
Debian's python3 with python3-matplotlib (scripts/setup installs it).
"""
import csv
import os
import sys
from collections import defaultdict

import matplotlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from plotstyle import series_styles  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(csv_path, png_path):
    curves = defaultdict(list)  # (normalization, azimuth, polar) -> [(roughness, albedo)]
    with open(csv_path, newline="") as f:
        for row in csv.DictReader(f):
            key = (row["normalization"], row["azimuth"], float(row["polar_deg"]))
            curves[key].append((float(row["roughness"]), float(row["albedo"])))
    def label(azimuth, polar):
        return ("wo ⊥ thread (any polar angle)" if azimuth == "across"
                else f"wo {polar:.0f}° from N, along thread")

    shown = sorted({(a, p) for _, a, p in curves if a != "across" or p == 0},
                   key=lambda ap: (ap[0] != "across", ap[1]))
    # A colour and marker per direction, the same in both panels; hollow markers, so that
    # curves on each other (across the thread and 0° along it are the same direction) both show.
    styles = series_styles([label(*ap) for ap in shown])
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for ax, norm in zip(axes, ["paper", "unitpeak"]):
        for azimuth, polar in shown:
            points = sorted(curves.get((norm, azimuth, polar), []))
            if not points:
                continue
            name = label(azimuth, polar)
            ax.plot(*zip(*points), "-" if azimuth == "across" else "--",
                    marker=styles[name]["marker"], markersize=6 if azimuth == "across" else 4,
                    fillstyle="none", color=styles[name]["color"], label=name)
        ax.axhline(1.0, color="k", linewidth=0.8)
        ax.set_title(f"FabricBxDF white furnace: {norm} normalization")
        ax.set_xlabel("roughness (n = ceil(1 + 29 (1 - r)²))")
        ax.set_ylabel("directional albedo a(wo)")
        ax.set_ylim(-0.05, 1.1)
        ax.grid(alpha=0.3)
    axes[1].yaxis.set_tick_params(labelleft=True)
    handles, names = axes[0].get_legend_handles_labels()
    fig.legend(handles, names, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=3,
               fontsize=8, frameon=False)
    fig.tight_layout()
    fig.savefig(png_path, dpi=110, bbox_inches="tight")
    print(f"wrote {png_path}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
