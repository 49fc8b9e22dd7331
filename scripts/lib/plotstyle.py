"""Styles shared by the project's plots (scripts/lib/studyreport.py, scripts/plot_*.py): every
series its own colour and marker however many there are, legends beside the axes rather than on
the data, and log-axis limits that hold every value.

A series key is a tuple of choices (strategy, fabric sampler, ...) or a plain string. With
tuples of two or more choices the last choice picks the hue (tab10) and the marker, the first the
line style, the hatch and the lightness (darker, as is, lighter), so "light / paper" reads as
paper's hue and marker drawn dashed, and the series of one first choice, drawn near each other,
differ in hue; otherwise the colours are tab10 (tab20 past 10 series) and the markers cycle.
"""
import math

MARKERS = ["o", "s", "D", "^", "v", "<", ">", "P", "X", "*", "h", "p"]
LINESTYLES = ["-", "--", ":", "-."]
HATCHES = ["", "//", "..", "xx", "\\\\", "oo"]
# The lightness of the first choice's values: < 0 mixes the hue with black, > 0 with white.
SHADES = {1: [0.0], 2: [-0.3, 0.3], 3: [-0.35, 0.0, 0.3], 4: [-0.4, -0.15, 0.15, 0.35]}


def _distinct(values):
    return list(dict.fromkeys(values))


def _flat_colours(count):
    import matplotlib
    if count <= 10:
        cmap = matplotlib.colormaps["tab10"]
        return [cmap(i) for i in range(count)]
    if count <= 20:
        cmap = matplotlib.colormaps["tab20"]
        # tab20's pairs: both shades of a hue before the next hue.
        return [cmap(i) for i in range(count)]
    cmap = matplotlib.colormaps["turbo"]
    return [cmap(0.05 + 0.9 * i / (count - 1)) for i in range(count)]


def _shade(rgba, amount):
    """rgba mixed with black (amount < 0) or white (amount > 0) by |amount|."""
    target = 0.0 if amount < 0 else 1.0
    return tuple(c + abs(amount) * (target - c) for c in rgba[:3]) + (1.0,)


def series_styles(keys):
    """{key: {"color", "marker", "linestyle", "hatch"}}, a distinct colour and a distinct
    (colour, marker) pair for every key."""
    import matplotlib
    keys = _distinct(keys)
    grouped = all(isinstance(k, tuple) and len(k) >= 2 for k in keys) and keys
    styles = {}
    if grouped:
        firsts = _distinct(k[0] for k in keys)
        lasts = _distinct(k[-1] for k in keys)
        if len(firsts) in SHADES and len(lasts) <= 10:
            tab10 = matplotlib.colormaps["tab10"]
            for k in keys:
                f, s = firsts.index(k[0]), lasts.index(k[-1])
                styles[k] = {"color": _shade(tab10(s), SHADES[len(firsts)][f]),
                             "marker": MARKERS[s],
                             "linestyle": LINESTYLES[f % len(LINESTYLES)],
                             "hatch": HATCHES[f % len(HATCHES)]}
            # Keys equal in first and last choice but differing between (three choices or
            # more) would share a style: fall back to flat colours then.
            if len({(v["color"], v["marker"]) for v in styles.values()}) == len(keys):
                return styles
    colours = _flat_colours(len(keys))
    for i, k in enumerate(keys):
        styles[k] = {"color": colours[i], "marker": MARKERS[i % len(MARKERS)], "linestyle": "-",
                     "hatch": ""}
    return styles


def log_limits(values, pad=1.6):
    """(low, high) for a log axis holding every positive finite value with a margin of pad x on
    each side; None where there is none."""
    values = [v for v in values if v is not None and v > 0 and math.isfinite(v)]
    if not values:
        return None
    return min(values) / pad, max(values) * pad


def label_short_log_axis(axis):
    """Labels the minor ticks (2, 3, 5 x 10^k) of a log axis that spans two decades or less,
    where the decades alone leave one label or none."""
    from matplotlib.ticker import FuncFormatter, LogLocator
    low, high = axis.get_view_interval()
    if low > 0 and high / low <= 100:
        axis.set_minor_locator(LogLocator(subs=(2, 3, 5)))
        axis.set_minor_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))


def legend_beside(fig, axes_list, handles=None, labels=None, title=None, fontsize=8):
    """One legend for the figure, off the data: in the first unused panel of the grid when there
    is one (axes_list has hidden axes), otherwise to the right of the figure (saved with
    bbox_inches="tight", which widens the image to hold it)."""
    if handles is None:
        handles, labels = [], []
        for ax in axes_list:
            for h, l in zip(*ax.get_legend_handles_labels()):
                if l not in labels:
                    handles.append(h)
                    labels.append(l)
    spare = [ax for ax in axes_list if not ax.axison and not ax.has_data()]
    ncol = 1 if len(labels) <= 16 else 2
    if spare:
        return spare[0].legend(handles, labels, loc="center", fontsize=fontsize, title=title,
                               ncol=ncol, frameon=False)
    return fig.legend(handles, labels, loc="center left", bbox_to_anchor=(1.0, 0.5),
                      fontsize=fontsize, title=title, ncol=ncol, frameon=False)
