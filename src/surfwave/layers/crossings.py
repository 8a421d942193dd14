"""Where one dispersion branch meets given frequencies: brackets in kh and starting points, on a sampled curve.

A branch j of a family is sampled as omega H = c_j(kh) kh at points kh_0 < kh_1 < ... with its exact slope
d(omega H)/d(kh) = v_g (the group velocity). omega(kh) need not rise with kh: where v_g < 0 (a backward wave)
it falls, and one frequency may meet the branch two or three times. Here every crossing is bracketed:

* :func:`stray_samples` finds samples that belong to another branch (the search at that kh missed or added
  a slower mode, so "the j-th slowest" is a neighbour there): the caller drops them;
* :func:`turning_points` gives, in each cell between two samples, the points where the cubic Hermite model
  of the cell (the samples' values and slopes) has zero slope; the caller samples the true curve there too,
  so the samples then hold (nearly) every extremum of the curve;
* :func:`brackets` gives, for each target omega H, every cell of the samples across which omega H - target
  changes sign (one root at least inside: the sampled values are exact), and every sample equal to the
  target (a root there, a touch included), with a start for Newton's method in each.

What this guarantees: every sign change of omega H - target between consecutive samples gives one bracket,
hence one root; the roots of distinct brackets are distinct. What it does not: two roots that lie between
the same two samples (both on one side of a turning point the samples do not resolve, i.e. a frequency
within the Hermite model's error of the branch's extremum: the crossings are then closer than a fraction of a
cell) are not seen; they come and go in pairs, so the count of crossings found has the parity of the true
one per branch.
"""
from __future__ import annotations

import numpy as np

__all__ = ["brackets", "stray_samples", "turning_points"]

#: Relative misfit of a cell's rise to the trapezoid rule on its end slopes above which the cell is
#: taken as inconsistent (:func:`stray_samples`).
MISFIT = 0.5


def _misfit(kh0: np.ndarray, kh1: np.ndarray, w0: np.ndarray, w1: np.ndarray, v0: np.ndarray,
            v1: np.ndarray) -> np.ndarray:
    """|rise - trapezoid of the slopes| / (|rise| + |trapezoid|) of cells (all arrays (m,))."""
    rise, trap = w1 - w0, 0.5 * (kh1 - kh0) * (v0 + v1)
    with np.errstate(all="ignore"):
        return np.abs(rise - trap) / (np.abs(rise) + 0.5 * (kh1 - kh0) * (np.abs(v0) + np.abs(v1)))


def stray_samples(kh: np.ndarray, w: np.ndarray, slope: np.ndarray) -> np.ndarray:
    """True at samples that belong to another branch: both cells beside them disagree with their slopes.

    A branch sampled as "the j-th slowest mode" at each kh takes a neighbour's value where the search
    at that kh missed (or added) a slower mode. Such a sample makes both of its cells inconsistent,
    the rise of omega H across each far from the trapezoid rule on the end slopes (relative misfit
    above :data:`MISFIT`), while the cell across it, from its left to its right neighbour, agrees
    (misfit below MISFIT / 4); on a smooth branch a cell twice as wide fits no better than its halves.

    Parameters
    ----------
    kh, w, slope : ndarray, shape (m,)
        The samples (ascending kh), omega H (m/s) and its slope dw/dkh (m/s).

    Returns
    -------
    ndarray of bool, shape (m,)
        True at an interior sample to be dropped (no two neighbours both).
    """
    out = np.zeros(kh.size, dtype=bool)
    if kh.size < 3:
        return out
    cell = _misfit(kh[:-1], kh[1:], w[:-1], w[1:], slope[:-1], slope[1:])
    across = _misfit(kh[:-2], kh[2:], w[:-2], w[2:], slope[:-2], slope[2:])
    stray = (cell[:-1] > MISFIT) & (cell[1:] > MISFIT) & (across < 0.25 * MISFIT)
    stray[1:] &= ~stray[:-1]                                         # isolated samples only
    out[1:-1] = stray
    return out


def turning_points(kh: np.ndarray, w: np.ndarray, slope: np.ndarray, target: np.ndarray | None = None
                   ) -> np.ndarray:
    """kh where the cubic Hermite model of w(kh) has zero slope, strictly inside a cell.

    Parameters
    ----------
    kh : ndarray, shape (m,)
        Ascending sample points.
    w : ndarray, shape (m,)
        omega H = c kh at them, m/s.
    slope : ndarray, shape (m,)
        dw/dkh at them (the group velocity), m/s.
    target : ndarray, shape (n,), optional
        Only the cells where the model meets some target more often than the ends' signs show (the
        crossings the samples alone would miss); None: every cell.

    Returns
    -------
    ndarray, shape (p,)
        Ascending kh of the model's interior extrema (at most two per cell).
    """
    if kh.size < 2:
        return np.zeros(0)
    h = np.diff(kh)
    w0, w1 = w[:-1], w[1:]
    m0, m1 = h * slope[:-1], h * slope[1:]
    # d/ds of the cubic on s in [0, 1]: a s^2 + b s + m0
    a = 6.0 * (w0 - w1) + 3.0 * (m0 + m1)
    b = 6.0 * (w1 - w0) - 4.0 * m0 - 2.0 * m1
    with np.errstate(all="ignore"):
        disc = b * b - 4.0 * a * m0
        sq = np.sqrt(np.where(disc >= 0, disc, np.nan))
        q = -0.5 * (b + np.copysign(sq, b))
        s1, s2 = q / a, m0 / q
        flat = np.abs(a) <= 1e-12 * (np.abs(b) + np.abs(m0))      # the derivative is linear in s
        s1 = np.where(flat, -m0 / b, s1)
        s2 = np.where(flat, np.nan, s2)
    s = np.sort(np.stack([s1, s2], axis=1), axis=1)                # NaN last
    ok = np.isfinite(s) & (s > 0) & (s < 1)
    if target is not None and ok.any():
        cell = np.flatnonzero(ok.any(axis=1))
        se = np.where(ok[cell], s[cell], np.nan)
        h00, h10, h01, h11 = 2 * se**3 - 3 * se**2 + 1, se**3 - 2 * se**2 + se, -2 * se**3 + 3 * se**2, se**3 - se**2
        pe = (h00 * w0[cell, None] + h10 * m0[cell, None] + h01 * w1[cell, None] + h11 * m1[cell, None])
        # the model's values along the cell in order: w0, its extrema, w1 (a missing extremum repeats w0)
        seq = np.concatenate([w0[cell, None], np.where(np.isfinite(pe), pe, w0[cell, None]), w1[cell, None]], axis=1)
        d = np.sign(seq[None, :, :] - target[:, None, None])          # (n, cells, 4)
        changes = (d[..., 1:] * d[..., :-1] < 0).sum(axis=-1) + (d[..., 1:-1] == 0).sum(axis=-1)
        ends = (d[..., 0] * d[..., -1] < 0)
        more = (changes > ends).any(axis=0)
        ok[cell[~more]] = False
    return np.unique((kh[:-1, None] + s * h[:, None])[ok])


def brackets(kh: np.ndarray, w: np.ndarray, slope: np.ndarray, target: np.ndarray
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Every crossing of the sampled curve w(kh) with each target: its row, bracket, sign and start.

    Parameters
    ----------
    kh, w, slope : ndarray, shape (m,)
        The samples (ascending kh), omega H at them (m/s) and its slope dw/dkh (m/s).
    target : ndarray, shape (n,)
        omega H of each row, m/s.

    Returns
    -------
    row : ndarray of int, shape (r,)
        The target of each crossing (several per row where the curve is not monotone).
    lo, hi : ndarray, shape (r,)
        The bracket in kh (lo == hi: the sample itself is a root).
    sign_lo : ndarray, shape (r,)
        Sign of w - target at ``lo`` (+1 or -1; the other end has the other sign).
    start : ndarray, shape (r,)
        Newton's start: the inverse cubic Hermite interpolation of the cell (kh as a function of w,
        as for a monotone curve) where both end slopes have the sign of the cell's rise; the linear
        interpolation elsewhere or where the former leaves the cell.
    """
    g = w[None, :] - target[:, None]                                  # (n, m)
    r0, i0 = np.nonzero(g == 0)
    with np.errstate(invalid="ignore"):
        r1, i1 = np.nonzero(g[:, :-1] * g[:, 1:] < 0)
    kl, kr, wl, wr, vl, vr = kh[i1], kh[i1 + 1], w[i1], w[i1 + 1], slope[i1], slope[i1 + 1]
    t = target[r1]
    dw = wr - wl
    s = (t - wl) / dw
    lin = kl + s * (kr - kl)
    with np.errstate(all="ignore"):
        d0, d1 = dw / vl, dw / vr
        h00, h10, h01, h11 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2, s**3 - s**2
        herm = h00 * kl + h10 * d0 + h01 * kr + h11 * d1
    good = (vl * dw > 0) & (vr * dw > 0) & (herm > kl) & (herm < kr)
    start = np.where(good, herm, lin)
    row = np.concatenate([r0, r1])
    lo = np.concatenate([kh[i0], kl])
    hi = np.concatenate([kh[i0], kr])
    sign_lo = np.concatenate([np.ones(r0.size), np.sign(g[r1, i1])])
    start = np.concatenate([kh[i0], start])
    return row, lo, hi, sign_lo, start
