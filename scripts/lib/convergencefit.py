"""The noise-to-time model shared by scripts/plot_convergence.py (convergence_bench's JSON) and
scripts/study report (a study's database).

An unbiased estimator with independent samples has relMSE = c / spp, so the spp for equal error
is proportional to c, and efficiency 1 / (relMSE * seconds) = 1 / (c * seconds per spp). The
reference (reference_spp samples, another seed) adds its own noise c_ref / reference_spp to every
measurement; the fit removes that floor. Points are (spp, seconds, relMSE).
"""


def reference_floor(points, n_ref):
    """The reference's own relMSE, c_ref / n_ref, from the series rendered like the reference:
    there relMSE = c_ref * (1 / spp + 1 / n_ref)."""
    c_ref = [rel / (1 / spp + 1 / n_ref) for spp, _, rel in points]
    return sorted(c_ref)[len(c_ref) // 2] / n_ref


def fit_c(points, floor):
    """c of relMSE = floor + c / spp, least squares in relative error so every spp counts alike."""
    num = sum((rel - floor) / spp / rel**2 for spp, _, rel in points)
    den = sum(1 / spp**2 / rel**2 for spp, _, rel in points)
    return max(num / den, 1e-12)


def seconds_per_spp(points):
    """From the largest spp, where fixed costs (tiles, threads) matter least."""
    spp, seconds, _ = max(points)
    return seconds / spp


def efficiency(c, points):
    """1 / (relMSE x seconds) of the fit: 1 / (c x seconds per spp)."""
    return 1 / (c * seconds_per_spp(points))
