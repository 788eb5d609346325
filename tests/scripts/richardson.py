"""Richardson extrapolation of three values on meshes halved in turn,
shared by the checks (run_and_check.py) and the documentation's studies
(doc/scripts)."""
import math


def richardson(coarse, middle, fine):
    """The observed order p = log2(d1 / d2), d1 = middle - coarse and
    d2 = fine - middle, and the extrapolated limit fine + d2 / (2^p - 1).
    Both are nan when the three values are not monotone (d1 d2 <= 0); the
    limit is nan when p <= 0, where the values do not converge."""
    d1, d2 = middle - coarse, fine - middle
    if d1 * d2 <= 0:
        return math.nan, math.nan
    order = math.log2(d1 / d2)
    return order, (fine + d2 / (2 ** order - 1) if order > 0 else math.nan)
