#!/usr/bin/python3
"""The noise-to-time study's plots and table, from benchmarks/convergence_bench's JSON output.

    build/release/benchmarks/convergence_bench --benchmark_out=build/bench/convergence.json
    /usr/bin/python3 scripts/plot_convergence.py build/bench/convergence.json [--out FOLDER]

Writes into FOLDER (default: the JSON's folder)
  convergence_relmse.png      relMSE against render time, log-log, one panel per scene, one line
                              per path strategy x fabric sampler, each its own colour and marker
                              (scripts/lib/plotstyle.py), the legend beside the panels;
  convergence_efficiency.png  efficiency ratios: each fabric sampler against uniform (under MIS),
                              MIS against BSDF-only and light-only (with the best sampler);
and prints Markdown tables: the spp each fabric sampler needs for the relMSE of "best", MIS's
efficiency relative to BSDF-only and light-only, and for the light samplers, the sample
generators and the integrators (LightSampler/, Sampler/ and Integrator/ benchmarks) relMSE per
spp and efficiency relative to "bvh", "independent" and "bdpt".

The model: an unbiased estimator with independent samples has relMSE = c / spp, so the spp for
equal error is proportional to c, and efficiency 1 / (relMSE * seconds) = 1 / (c * seconds per
spp). The reference (MIS, best, reference_spp samples, another seed) adds its own noise
c_ref / reference_spp to every measurement; the fit removes that floor.
"""
import argparse
import json
import os
from collections import defaultdict

import sys

import matplotlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from convergencefit import efficiency, fit_c, reference_floor  # noqa: E402
from plotstyle import label_short_log_axis, legend_beside, log_limits, series_styles  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend choice)

SAMPLERS = ["uniform", "cosine", "paper", "best"]
STRATEGIES = ["bsdf", "light", "mis"]
REFERENCE = ("best", "mis")  # what the reference is rendered with


def load(path):
    """{scene: {(sampler, strategy): [(spp, seconds, relMSE)]}} and {scene: reference spp}."""
    with open(path) as f:
        benchmarks = json.load(f)["benchmarks"]
    series = defaultdict(lambda: defaultdict(list))
    reference_spp = {}
    for b in benchmarks:
        if b.get("error_occurred") or b.get("run_type", "iteration") != "iteration":
            continue
        parts = b["name"].split("/")
        if parts[0] != "Convergence":
            continue
        scene, sampler, strategy = parts[1:4]
        series[scene][(sampler, strategy)].append((int(b["spp"]), b["seconds"], b["relMSE"]))
        reference_spp[scene] = int(b["reference_spp"])
    for by_key in series.values():
        for points in by_key.values():
            points.sort()
    return series, reference_spp


def fit(series, reference_spp):
    """{scene: {(sampler, strategy): (c, efficiency)}}"""
    fits = {}
    for scene, by_key in series.items():
        ref = by_key.get(REFERENCE)
        floor = reference_floor(ref, reference_spp[scene]) if ref else 0.0
        fits[scene] = {}
        for key, points in by_key.items():
            c = fit_c(points, floor)
            fits[scene][key] = (c, efficiency(c, points))
    return fits


def plot_relmse(series, path):
    scenes = sorted(series)
    cols = 2
    rows = (len(scenes) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(5.5 * cols, 4.2 * rows), squeeze=False)
    # (strategy, sampler): a line style per strategy, a hue and marker per sampler (plotstyle).
    keys = [(t, s) for t in STRATEGIES for s in SAMPLERS]
    keys += sorted({(t, s) for by_key in series.values() for s, t in by_key} - set(keys))
    styles = series_styles(keys)
    for ax, scene in zip(axes.flat, scenes):
        for (sampler, strategy), points in sorted(series[scene].items(),
                                                  key=lambda kv: (kv[0][1], kv[0][0])):
            style = styles[(strategy, sampler)]
            ax.loglog([p[1] for p in points], [p[2] for p in points], marker=style["marker"],
                      markersize=5, fillstyle="none", color=style["color"],
                      linestyle=style["linestyle"], label=f"{strategy} / {sampler}")
        ax.set_title(scene)
        ax.set_xlabel("render time [s]")
        ax.set_ylabel("relMSE")
        ax.grid(True, which="both", alpha=0.3)
    for ax in list(axes.flat)[len(scenes):]:
        ax.axis("off")
    legend_beside(fig, list(axes.flat))
    fig.tight_layout()
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)


C, EFFICIENCY = 0, 1  # the fields of a fit


def ratio(fits, scene, key, baseline, field):
    """NaN where a filtered run left out either series."""
    f = fits[scene]
    if key not in f or baseline not in f:
        return float("nan")
    return f[key][field] / f[baseline][field]


def cell(value, fmt):
    return "–" if value != value else format(value, fmt)


def plot_efficiency(fits, path):
    scenes = sorted(fits)
    panels = [
        ("fabric sampler vs uniform (MIS)",
         [(s, (s, "mis"), ("uniform", "mis")) for s in SAMPLERS[1:]]),
        ("MIS vs one strategy (best sampler)",
         [(f"mis / {s}", ("best", "mis"), ("best", s)) for s in STRATEGIES[:2]]),
    ]
    fig, axes = plt.subplots(1, len(panels), figsize=(6 * len(panels), 4.5))
    for ax, (title, bars) in zip(axes, panels):
        width = 0.8 / len(bars)
        values = []
        for i, (label, key, baseline) in enumerate(bars):
            ratios = [ratio(fits, scene, key, baseline, EFFICIENCY) for scene in scenes]
            ax.bar([j + (i - (len(bars) - 1) / 2) * width for j in range(len(scenes))], ratios,
                   width, label=label)
            values += ratios
        ax.axhline(1, color="black", linewidth=0.8)
        ax.set_yscale("log")
        ax.set_ylim(*log_limits(values + [1.0], pad=2.0))
        label_short_log_axis(ax.yaxis)
        ax.set_xticks(range(len(scenes)), scenes, rotation=15)
        ax.set_ylabel("efficiency ratio")
        ax.set_title(title)
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.22), ncol=len(bars),
                  frameon=False)
    fig.tight_layout()
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)


def print_tables(fits):
    scenes = sorted(fits)
    print("spp for the relMSE of `best` (c_sampler / c_best), uniform : cosine : paper : best\n")
    print("| scene | strategy | " + " | ".join(SAMPLERS) + " |")
    print("|---|---|" + "---|" * len(SAMPLERS))
    for scene in scenes:
        for strategy in STRATEGIES:
            ratios = [ratio(fits, scene, (s, strategy), ("best", strategy), C) for s in SAMPLERS]
            print(f"| {scene} | {strategy} | " + " | ".join(cell(r, ".2f") for r in ratios) + " |")
    print("\nMIS efficiency relative to BSDF-only and light-only (1 / (relMSE x seconds))\n")
    print("| scene | fabric sampler | mis / bsdf | mis / light |")
    print("|---|---|---|---|")
    for scene in scenes:
        for s in SAMPLERS:
            ratios = [ratio(fits, scene, (s, "mis"), (s, t), EFFICIENCY) for t in STRATEGIES[:2]]
            print(f"| {scene} | {s} | " + " | ".join(cell(r, ".3g") for r in ratios) + " |")


CHOICE_BASELINES = {"LightSampler": "bvh", "Sampler": "independent", "Integrator": "bdpt"}


def load_choices(path):
    """{study: {scene: {choice: [(spp, seconds, relMSE)]}}} for the studies of CHOICE_BASELINES."""
    with open(path) as f:
        benchmarks = json.load(f)["benchmarks"]
    studies = defaultdict(lambda: defaultdict(lambda: defaultdict(list)))
    for b in benchmarks:
        parts = b["name"].split("/")
        if b.get("error_occurred") or parts[0] not in CHOICE_BASELINES:
            continue
        studies[parts[0]][parts[1]][parts[2]].append((int(b["spp"]), b["seconds"], b["relMSE"]))
    return studies


def print_choice_tables(studies):
    """relMSE at each sweep count, and efficiency (1 / (relMSE x seconds)) over the baseline's at
    the same count: low-discrepancy samplers converge faster than 1 / spp, so no single c fits."""
    for study, scenes in studies.items():
        baseline = CHOICE_BASELINES[study]
        counts = sorted({spp for by_choice in scenes.values() for pts in by_choice.values()
                         for spp, _, _ in pts})
        print(f"\n{study}: relMSE per spp, and efficiency relative to {baseline} at that spp\n")
        print("| scene | choice | " + " | ".join(f"relMSE {n}" for n in counts) + " | "
              + " | ".join(f"eff. {n}" for n in counts) + " |")
        print("|---|---|" + "---|" * (2 * len(counts)))
        for scene, by_choice in sorted(scenes.items()):
            base = {spp: 1 / (rel * sec) for spp, sec, rel in by_choice.get(baseline, [])}
            for choice, pts in by_choice.items():
                pts = dict((spp, (sec, rel)) for spp, sec, rel in pts)
                rel = [cell(pts[n][1] if n in pts else float("nan"), ".3g") for n in counts]
                eff = [cell(1 / (pts[n][1] * pts[n][0]) / base[n] if n in pts and n in base
                            else float("nan"), ".2f") for n in counts]
                print(f"| {scene} | {choice} | " + " | ".join(rel) + " | " + " | ".join(eff) + " |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("json", help="convergence_bench's --benchmark_out file")
    parser.add_argument("--out", help="folder for the plots (default: the JSON's folder)")
    args = parser.parse_args()
    out = args.out or os.path.dirname(os.path.abspath(args.json))
    series, reference_spp = load(args.json)
    studies = load_choices(args.json)
    if not series and not studies:
        parser.error(f"{args.json}: no convergence benchmarks without errors")
    if series:
        fits = fit(series, reference_spp)
        plot_relmse(series, os.path.join(out, "convergence_relmse.png"))
        plot_efficiency(fits, os.path.join(out, "convergence_efficiency.png"))
        print_tables(fits)
    print_choice_tables(studies)


if __name__ == "__main__":
    main()
