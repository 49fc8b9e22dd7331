"""scripts/study report: a study's tables and plots, from its database alone.

Writes into the output folder
  report.md      per scene, one row per series (the configuration's choices, spp and seed
                 aside): relMSE at each spp (the mean over seeds), c of relMSE = floor + c / spp
                 (convergencefit), c and efficiency 1 / (relMSE x seconds) relative to the
                 baseline series, efficiency relative to the baseline at each spp (where
                 low-discrepancy samplers beat 1 / spp, no single c fits), the fabric samplers'
                 uniform : paper : best where they vary, the cost per task, and the failures;
  relmse.png     relMSE against render time, log-log, a panel per scene, a line per series
                 (its own colour and marker, scripts/lib/plotstyle.py; one legend beside the
                 panels);
  efficiency.png efficiency relative to the baseline series, a group of bars per scene;
  functions.png  with [functions]: each sampler's mean squared error against the sample count,
                 log-log, a panel per test function (report.md has their table),
and prints report.md.

replot (scripts/study replot REPORT.md) makes relmse.png and efficiency.png again from a
report.md's tables alone, for a study whose database is gone: relMSE then against spp, as the
report does not keep the seconds of each point.
"""
import math
import os
import re
import statistics
from collections import defaultdict

from convergencefit import efficiency, fit_c, reference_floor
from studydb import Database
from studyfile import DIMENSIONS

CHOICES = [f for f, _ in DIMENSIONS.values()]
# What the reference is rendered with (studyfile.Study.reference_args); None: the scene's.
REFERENCE_CHOICES = {"strategy": ("mis", None), "fabric_sampler": ("best", None)}


def varying(study):
    """The choices with more than one value: they name the series."""
    return [f for f in CHOICES if len(study.choices[f]) > 1]


def label(key):
    return " / ".join(str(v) for v in key) if key else "the scene's"


def series_of(rows, dims):
    """{scene: {series key: [(spp, seconds, relMSE)]}}: seeds averaged per spp."""
    by_point = defaultdict(list)
    for r in rows:
        by_point[(r["scene"], tuple(r[d] for d in dims), r["spp"])].append(r)
    series = defaultdict(lambda: defaultdict(list))
    for (scene, key, spp), rs in sorted(by_point.items(), key=lambda kv: str(kv[0])):
        series[scene][key].append((spp, statistics.mean(r["seconds"] for r in rs),
                                   statistics.mean(r["relmse"] for r in rs)))
    for by_key in series.values():
        for points in by_key.values():
            points.sort()
    return series


def is_reference_like(study, scene, key, dims):
    """Whether the series is rendered as the reference is (studyfile.Study.reference_args):
    MIS, the best fabric sampler, the reference's integrator, the scene's other choices."""
    allowed = {**REFERENCE_CHOICES, "integrator": (study.reference_integrator.get(scene), None)}
    for choice in CHOICES:
        value = key[dims.index(choice)] if choice in dims else study.choices[choice][0]
        if value not in allowed.get(choice, (None,)):
            return False
    return True


def fits_of(study, series, dims):
    """{scene: {key: c}}, after the floor of the reference's noise, estimated from the series
    rendered as the reference is where the study has one (otherwise no floor)."""
    fits = {}
    for scene, by_key in series.items():
        like = [pts for key, pts in by_key.items() if is_reference_like(study, scene, key, dims)]
        floor = reference_floor(like[0], study.reference_spp) if like else 0.0
        fits[scene] = {key: fit_c(points, floor) for key, points in by_key.items()}
    return fits


def baseline_key(study, dims, keys):
    wanted = tuple(study.baseline.get(d) for d in dims)
    return wanted if wanted in keys else sorted(keys, key=str)[0]


def fmt(value, spec):
    return "–" if value is None or value != value else format(value, spec)


def scene_table(study, dims, scene, by_key, c_of):
    counts = sorted({spp for pts in by_key.values() for spp, _, _ in pts})
    base = baseline_key(study, dims, by_key)
    base_pts = {spp: (sec, rel) for spp, sec, rel in by_key[base]}
    eff_of = {key: efficiency(c_of[key], pts) for key, pts in by_key.items()}
    lines = [f"### {scene} (baseline: {label(base)})", "",
             "| series | " + " | ".join(f"relMSE {n}" for n in counts)
             + " | c | c / baseline | efficiency / baseline | "
             + " | ".join(f"eff. {n} / baseline" for n in counts) + " |",
             "|---|" + "---|" * (2 * len(counts) + 3)]
    for key, pts in sorted(by_key.items(), key=lambda kv: str(kv[0])):
        at = {spp: (sec, rel) for spp, sec, rel in pts}
        rel = [fmt(at[n][1] if n in at else None, ".3g") for n in counts]
        eff = [fmt(base_pts[n][0] * base_pts[n][1] / (at[n][0] * at[n][1])
                   if n in at and n in base_pts else None, ".2f") for n in counts]
        lines.append(f"| {label(key)} | " + " | ".join(rel)
                     + f" | {c_of[key]:.3g} | {c_of[key] / c_of[base]:.3g} | "
                     + f"{eff_of[key] / eff_of[base]:.3g} | " + " | ".join(eff) + " |")
    return lines


def fabric_sampler_lines(dims, fits):
    """uniform : paper : best (c relative to best) per scene and other choices, where the fabric
    sampler varies; the paper claims uniform needs 6-8x the samples of its own sampler."""
    if "fabric_sampler" not in dims:
        return []
    i = dims.index("fabric_sampler")
    lines = ["## Fabric samplers: spp for equal error, uniform : paper : best", "",
             "| scene | other choices | uniform : paper : best | uniform / paper (paper: 6-8) |",
             "|---|---|---|---|"]
    for scene, c_of in sorted(fits.items()):
        others = sorted({key[:i] + key[i + 1:] for key in c_of}, key=str)
        for rest in others:
            c = {s: c_of.get(rest[:i] + (s,) + rest[i:]) for s in ("uniform", "paper", "best")}
            if None in c.values():
                continue
            lines.append(f"| {scene} | {label(rest)} | {c['uniform'] / c['best']:.2f} : "
                         f"{c['paper'] / c['best']:.2f} : 1 | {c['uniform'] / c['paper']:.2f} |")
    return lines + [""]


def cost_lines(rows):
    """Per task: the render's own seconds against the whole task's (process start, scene
    loading, reading the reference, relMSE)."""
    ok = [r for r in rows if r["status"] == "ok" and r["wall_seconds"] is not None]
    if not ok:
        return []
    overhead = [r["wall_seconds"] - r["seconds"] for r in ok]
    render = [r["seconds"] for r in ok]
    return ["## Cost per task", "",
            f"{len(ok)} tasks: render {statistics.median(render):.3f} s median "
            f"({sum(render):.1f} s in all); the rest of the task {statistics.median(overhead):.3f} s "
            f"median, {max(overhead):.3f} s at most ({sum(overhead):.1f} s in all).", ""]


def failure_lines(rows):
    failed = [r for r in rows if r["status"] == "failed"]
    if not failed:
        return ["No configuration failed.", ""]
    lines = [f"## Failures ({len(failed)})", "", "| scene | configuration | message |", "|---|---|---|"]
    for r in failed:
        config = ", ".join(f"{f} {r[f]}" for f in [*CHOICES, "spp", "seed"] if r[f] is not None)
        message = (r["message"] or "").replace("\n", " ").replace("|", "\\|")
        lines.append(f"| {r['scene']} | {config} | {message} |")
    return lines + [""]


def efficiency_ratios(series, dims, fits, study):
    """{scene: {key: efficiency / the baseline's}} and {scene: the baseline's key}."""
    ratios, baselines = {}, {}
    for scene, by_key in series.items():
        c_of = fits[scene]
        base = baselines[scene] = baseline_key(study, dims, by_key)
        ratios[scene] = {key: efficiency(c_of[key], pts) / efficiency(c_of[base], by_key[base])
                         for key, pts in by_key.items()}
    return ratios, baselines


def plot(series, dims, fits, study, out):
    ratios, baselines = efficiency_ratios(series, dims, fits, study)
    plot_relmse(series, os.path.join(out, "relmse.png"), study.name)
    plot_efficiency(ratios, baselines, os.path.join(out, "efficiency.png"), study.name)


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def plot_relmse(series, path, title=None):
    """relMSE against render time (against spp where the points have no seconds, as those read
    back from a report.md have not), log-log, a panel per scene, a line per series with its own
    colour and marker (plotstyle; hollow markers, so that series drawn on each other both show),
    one legend beside the panels."""
    plt = _pyplot()
    from plotstyle import label_short_log_axis, legend_beside, log_limits, series_styles
    scenes = sorted(series)
    keys = sorted({k for by_key in series.values() for k in by_key}, key=str)
    styles = series_styles(keys)
    timed = all(sec is not None for by_key in series.values() for pts in by_key.values()
                for _, sec, _ in pts)
    cols = min(3 if len(scenes) > 4 else 2, len(scenes))
    rows = (len(scenes) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.6 * cols, 3.9 * rows), squeeze=False)
    for ax, scene in zip(axes.flat, scenes):
        for key, pts in sorted(series[scene].items(), key=lambda kv: str(kv[0])):
            style = styles[key]
            ax.loglog([p[1] if timed else p[0] for p in pts], [p[2] for p in pts],
                      marker=style["marker"], markersize=5, fillstyle="none", linewidth=1.2,
                      color=style["color"], linestyle=style["linestyle"], label=label(key))
        ylim = log_limits([p[2] for pts in series[scene].values() for p in pts], pad=1.4)
        if ylim:
            ax.set_ylim(*ylim)
            label_short_log_axis(ax.yaxis)
        ax.set(title=scene, xlabel="render time [s]" if timed else "samples per pixel",
               ylabel="relMSE (mean over seeds)")
        if not timed:
            counts = sorted({p[0] for pts in series[scene].values() for p in pts})
            ax.set_xticks(counts, [str(n) for n in counts])
            ax.minorticks_off()
        ax.grid(True, which="both", alpha=0.3)
    for ax in list(axes.flat)[len(scenes):]:
        ax.axis("off")
    legend_beside(fig, list(axes.flat))
    if title:
        fig.suptitle(f"{title}: relMSE against {'render time' if timed else 'spp'}")
    fig.tight_layout()
    fig.savefig(path, dpi=100, bbox_inches="tight")
    plt.close(fig)


def plot_efficiency(ratios, baselines, path, title=None):
    """Efficiency relative to the baseline series, a group of bars per scene, log scale with
    limits that hold every bar (and 1, the baseline), the legend beside the axes."""
    plt = _pyplot()
    from plotstyle import label_short_log_axis, log_limits, series_styles
    scenes = sorted(ratios)
    keys = sorted({k for by_key in ratios.values() for k in by_key}, key=str)
    styles = series_styles(keys)
    fig, ax = plt.subplots(figsize=(max(6.0, 0.16 * len(keys) * len(scenes) + 2), 4.2))
    width = 0.84 / max(1, len(keys))
    values = []
    for i, key in enumerate(keys):
        heights = [ratios[scene].get(key, float("nan")) for scene in scenes]
        values += heights
        style = styles[key]
        ax.bar([j + (i - (len(keys) - 1) / 2) * width for j in range(len(scenes))], heights, width,
               label=label(key), color=style["color"], hatch=style["hatch"],
               edgecolor="white", linewidth=0.4)
    ax.axhline(1, color="black", linewidth=0.8)
    ax.set_yscale("log")
    low, high = log_limits(values + [1.0], pad=2.0)
    ax.set_ylim(low, high)
    label_short_log_axis(ax.yaxis)
    ax.set_xticks(range(len(scenes)), scenes, rotation=15)
    ax.set_xlim(-0.5, len(scenes) - 0.5)
    bases = sorted({label(b) for b in baselines.values()})
    ax.set_ylabel(f"efficiency / {', '.join(bases)}'s\n(efficiency: 1 / (relMSE x seconds))")
    ax.set_title(f"{title + ': ' if title else ''}efficiency relative to the baseline")
    ax.grid(True, axis="y", which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False)
    fig.tight_layout()
    fig.savefig(path, dpi=100, bbox_inches="tight")
    plt.close(fig)


def read_report(path):
    """The scene tables of a report.md this module wrote: ({scene: {key: [(spp, None, relMSE)]}},
    {scene: {key: efficiency / baseline}}, {scene: baseline key}). The seconds per point are not
    in the report, so plots made from it have spp on their x axis."""
    series, ratios, baselines = {}, {}, {}
    scene = header = None
    with open(path) as f:
        for line in f:
            line = line.rstrip("\n")
            heading = re.match(r"^### (\S+) \(baseline: (.*)\)$", line)
            if heading:
                scene, header = heading.group(1), None
                baselines[scene] = unlabel(heading.group(2))
                continue
            if line.startswith("#"):
                scene = header = None
                continue
            if scene is None or not line.startswith("|") or line.startswith("|---"):
                continue
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if header is None:
                header = cells
                continue
            row = dict(zip(header, cells))
            key = unlabel(row["series"])
            points = [(int(name.split()[1]), None, float(value)) for name, value in row.items()
                      if re.fullmatch(r"relMSE \d+", name) and value != "–"]
            series.setdefault(scene, {})[key] = sorted(points)
            if row.get("efficiency / baseline", "–") != "–":
                ratios.setdefault(scene, {})[key] = float(row["efficiency / baseline"])
    return series, ratios, baselines


def unlabel(text):
    """label's inverse."""
    return () if text == "the scene's" else tuple(text.split(" / "))


def replot(report_path, out):
    """relmse.png (against spp) and efficiency.png from a report.md's tables, for a study whose
    database is gone."""
    series, ratios, baselines = read_report(report_path)
    if not series:
        print(f"{report_path}: no scene tables")
        return 1
    os.makedirs(out, exist_ok=True)
    name = os.path.splitext(os.path.basename(report_path))[0]
    plot_relmse(series, os.path.join(out, "relmse.png"), name)
    if ratios:
        plot_efficiency(ratios, baselines, os.path.join(out, "efficiency.png"), name)
    print(f"wrote {os.path.join(out, 'relmse.png')}"
          + (f" and {os.path.join(out, 'efficiency.png')}" if ratios else ""))
    return 0


MARKERS = "osD^v<>Ph*"


def mean_table(tables):
    """The rows (n, MSE) common to every seed's table, MSE averaged over the seeds."""
    common = set.intersection(*({n for n, _ in t} for t in tables))
    return sorted((n, statistics.fmean(dict(t)[n] for t in tables)) for n in common)


def plotted_rows(rows):
    """The rows a sampler is compared at: its rows, or for a sampler that writes every count the
    powers of two; those with an error above 0 (log axes)."""
    dense = len(rows) == rows[-1][0]
    return [(n, mse) for n, mse in rows if mse > 0 and (not dense or n & (n - 1) == 0)]


def convergence_order(rows):
    """The least-squares slope of log MSE against log n over the rows from n = 4 on: -1 for
    independent samples, steeper for point sets that stratify the function's features. Where a
    sampler writes a row at every count, over the powers of two only, as the others' rows are
    (pmj02bn's pixel samples are a random subset of its set between them); None where fewer than
    two rows have an error above 0."""
    pts = [(math.log(n), math.log(mse)) for n, mse in plotted_rows(rows) if n >= 4]
    if len(pts) < 2:
        return None
    mx, my = statistics.fmean(p[0] for p in pts), statistics.fmean(p[1] for p in pts)
    return (sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts))


def function_tables(study, results):
    """function -> sampler -> the mean table over the seeds, from the stored ok results."""
    tables = defaultdict(lambda: defaultdict(list))
    for r in results:
        if r["status"] == "ok" and r["rows"]:
            tables[r["function"]][r["sampler"]].append(r["rows"])
    return {f: {s: mean_table(ts) for s, ts in by.items()} for f, by in tables.items()}


def function_lines(study, tables, failed):
    if not tables and not failed:
        return []
    x, y = study.function_resolution
    lines = ["## The samplers on the function integrator's test functions", "",
             f"pbrt-v4's function integrator, {x} x {y} pixels each estimating a test function's "
             f"integral (1) from its sampler's first two dimensions, {study.function_spp} samples "
             f"per pixel, mean over seeds {study.seeds}: the mean squared error at the last count "
             "each sampler writes a row at, MSE x n (equal for every n where samples are "
             "independent), and the convergence order, the slope of log MSE against log n "
             "(-1 for independent samples) over the counts from 4 on that each sampler writes rows "
             "at, the powers of two for those that write every count; – where the error is 0 "
             "throughout."
             + (" sobol is left out: its pixel samples are one sequence over the image, which the "
                "function integrator refuses (paddedsobol is the per-pixel one)."
                if "sobol" in study.choices["sampler"] else ""), ""]
    for function in study.functions:
        by_sampler = tables.get(function, {})
        lines += [f"### {function}", "", "| sampler | n | MSE | MSE x n | order |", "|---|---|---|---|---|"]
        for sampler in study.function_samplers():
            rows = by_sampler.get(sampler)
            if rows:
                n, mse = rows[-1]
                order = convergence_order(rows)
                lines.append(f"| {sampler} | {n} | {mse:.3g} | {mse * n:.3g} | "
                             f"{'–' if order is None else f'{order:.2f}'} |")
        lines.append("")
    for r in failed:
        lines.append(f"- {r['function']} with {r['sampler']}, seed {r['seed']}: failed: {r['message']}")
    return lines + ([""] if failed else [])


def plot_functions(study, tables, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    functions = [f for f in study.functions if f in tables]
    fig, axes = plt.subplots(1, len(functions), figsize=(4.5 * len(functions), 4.2), squeeze=False)
    samplers = study.function_samplers()
    for ax, function in zip(axes.flat, functions):
        for i, sampler in enumerate(samplers):
            rows = plotted_rows(tables[function].get(sampler) or [])
            if rows:
                ax.loglog([n for n, _ in rows], [m for _, m in rows], marker=MARKERS[i % len(MARKERS)],
                          markersize=3, color=f"C{i % 10}", label=sampler)
        ax.set(title=f"{function} (up to {study.function_spp} spp)", xlabel="samples per pixel",
               ylabel="mean squared error (0: not drawn)")
        ax.grid(True, which="both", alpha=0.3)
    handles, names = axes.flat[0].get_legend_handles_labels()
    fig.legend(handles, names, loc="lower center", ncol=min(len(names), 7), fontsize=8)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    fig.savefig(os.path.join(out, "functions.png"), dpi=110)
    plt.close(fig)


def report(study, out):
    database = Database(study.database)
    rows = database.results()
    references = database.references()
    function_results = database.function_results()
    tables = function_tables(study, function_results)
    failed_tables = [r for r in function_results if r["status"] != "ok"]
    database.close()
    if not rows and not tables:
        print(f"{study.database}: no results yet (scripts/study run {study.path})")
        return 1
    dims = varying(study)
    ok = [r for r in rows if r["status"] == "ok"]
    series = series_of(ok, dims)
    fits = fits_of(study, series, dims)
    lines = [f"# Study {study.name}", "",
             f"{len(rows)} results ({len(ok)} ok) from {os.path.relpath(study.database)}; references at "
             f"{study.reference_spp} spp, seed {study.reference_seed} "
             f"({sum(r['seconds'] or 0 for r in references):.1f} s of rendering). relMSE is the "
             f"mean over seeds {study.seeds}; efficiency is 1 / (relMSE x seconds).", ""]
    for scene in sorted(series):
        lines += scene_table(study, dims, scene, series[scene], fits[scene]) + [""]
    lines += function_lines(study, tables, failed_tables)
    lines += fabric_sampler_lines(dims, fits) + cost_lines(rows) + failure_lines(rows)
    os.makedirs(out, exist_ok=True)
    if series:
        plot(series, dims, fits, study, out)
    if tables:
        plot_functions(study, tables, out)
    text = "\n".join(lines)
    with open(os.path.join(out, "report.md"), "w") as f:
        f.write(text)
    print(text)
    return 0
