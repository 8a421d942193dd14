"""All guided modes of a stack at many kh: bracketing on a speed grid, vectorised refinement, labels.

Per decoupled family (:func:`surfwave.layers.partial.families`) the real secular function
det Z(c, kh) (:func:`surfwave.layers.recursion.secular`) is evaluated on a grid of speeds for
all kh at once: the layers' eigen-solutions depend on c only, so they are computed once per grid
speed and shared by every kh. The grid is uniform in t = sqrt(1 - c^2 / c_lim^2) (dense near the
substrate's limiting speed c_lim, where modes appear at their cut-off with a square-root
behaviour), plus a geometric tail toward t = 0. Every sign change brackets either a mode or a
pole of Z (a mode of the stack with a clamped top); all brackets of all kh are refined together
by the Illinois variant of regula falsi to a relative width :data:`C_TOL`, and a converged
bracket is a mode when Z is (numerically) singular there and bounded, a pole otherwise.

Labels. Within one family, the modes at fixed kh are ordered by speed and cannot cross as kh
changes (crossings of one family are non-generic, and each family's modes are counted from the
slowest); new modes enter at the top, through c_lim. The n-th slowest mode of a family therefore
keeps its label along kh: sagittal "R" (Rayleigh), "S1", "S2", ... (Sezawa); shear horizontal
"L0", "L1", ... (Love); coupled families "M0", "M1", ....
"""
from __future__ import annotations

import numpy as np

from surfwave.layers.partial import Blocks, Family
from surfwave.layers.recursion import boundary_matrix, secular, top_impedance
from surfwave.solvers.impedance import limiting_x as elastic_limiting_x

__all__ = ["C_TOL", "family_modes", "label", "lowest_speed"]

#: Relative width of a converged bracket in c.
C_TOL = 4e-15
#: Iterations of the bracket refinement at most.
MAX_ITER = 200
#: Points of the speed grid per unit of kh (on top of :data:`BASE_GRID`): thick films hold many modes.
GRID_PER_KH = 12
BASE_GRID = 120
#: Smallest t = sqrt(1 - c^2/c_lim^2) of the grid.
T_MIN = 1e-7


def label(prefix: str, j: int) -> str:
    """Label of the j-th slowest mode of a family with this prefix ("R" -> R, S1, S2, ...)."""
    if prefix == "R":
        return "R" if j == 0 else f"S{j}"
    return f"{prefix}{j}"


def lowest_speed(b: Blocks) -> float:
    """A speed below every guided mode: 0.2 x the lowest limiting speed of any layer as a half-space, m/s."""
    Q, R, T = b.Q[:, :3, :3], b.R[:, :3, :3], b.T[:, :3, :3]
    XL = elastic_limiting_x(Q, R, T)[0]
    return float(0.2 * np.sqrt(np.min(XL * b.sA / b.rho)))


def film_bulk_speeds(b: Blocks) -> np.ndarray:
    """Trace-speed minima along x1 of the three bulk sheets of every film, m/s, shape (3 L,).

    Above such a speed a partial wave of the film is real (propagates across the film), and at
    large kh the film's modes crowd just above it (spacing ~ pi / kh in the vertical wavenumber).
    """
    L = len(b.frac)
    if L == 0:
        return np.zeros(0)
    phi = np.linspace(-0.5 * np.pi, 0.5 * np.pi, 181)[1:-1]
    cs, sn = np.cos(phi)[:, None, None], np.sin(phi)[:, None, None]
    out = []
    for layer in range(L):
        Q, R, T = b.Q[layer, :3, :3], b.R[layer, :3, :3], b.T[layer, :3, :3]
        G = cs * cs * Q + sn * cs * (R + R.T) + sn * sn * T
        w = np.linalg.eigvalsh(G) / (cs[:, :, 0] ** 2)
        out.append(np.sqrt(np.clip(w.min(axis=0), 0, None) * b.sA / b.rho[layer]))
    return np.concatenate(out)


def speed_grid(c_lim: float, c_lo: float, n: int, bulk=(), kh_max: float = 0.0) -> np.ndarray:
    """Ascending speeds in (c_lo, c_lim): uniform in t = sqrt(1 - c^2/c_lim^2), a geometric tail toward
    c_lim, and above each film bulk speed v in ``bulk`` the points v sqrt(1 + q^2) with q spaced by
    pi / (6 kh_max) (modes crowd there at large kh)."""
    t_hi = np.sqrt(1.0 - (c_lo / c_lim) ** 2)
    t = np.concatenate([np.geomspace(T_MIN, 0.02, 24, endpoint=False), np.linspace(0.02, t_hi, n)])
    parts = [c_lim * np.sqrt(1.0 - t * t)]
    if kh_max > 1.0:
        for v in bulk:
            if c_lo < v < c_lim:
                q_max = np.sqrt((c_lim / v) ** 2 - 1.0)
                q = np.arange(1e-9, q_max, np.pi / (6.0 * kh_max))[:4000]
                parts.append(v * np.sqrt(1.0 + q * q))
    g = np.unique(np.concatenate(parts))
    return g[(g > c_lo) & (g < c_lim)]


def _refine(b: Blocks, fam: Family, lo, hi, flo, fhi, kh, electrical: str) -> np.ndarray:
    """Illinois regula falsi on all brackets at once; returns the converged speeds (m,)."""
    a, fa, c_, fc = lo.copy(), flo.copy(), hi.copy(), fhi.copy()      # c_ = the latest point
    idx = np.arange(a.size)
    out = 0.5 * (a + c_)
    for _ in range(MAX_ITER):
        if idx.size == 0:
            break
        with np.errstate(all="ignore"):
            x = c_ - fc * (c_ - a) / (fc - fa)
        left, right = np.minimum(a, c_), np.maximum(a, c_)
        bad = ~np.isfinite(x) | (x <= left) | (x >= right)
        x = np.where(bad, 0.5 * (a + c_), x)
        fx = secular(b, fam, x, kh[idx, None], electrical)[:, 0]
        same = np.sign(fx) == np.sign(fc)
        # Illinois: keep the old end a, halve its value when the new point falls on c_'s side
        fa = np.where(same, 0.5 * fa, fc)
        a = np.where(same, a, c_)
        c_, fc = x, fx
        done = (np.abs(c_ - a) <= C_TOL * np.abs(c_)) | (fx == 0) | ~np.isfinite(fx)
        out[idx[done]] = c_[done]
        keep = ~done
        idx, a, fa, c_, fc = idx[keep], a[keep], fa[keep], c_[keep], fc[keep]
    out[idx] = c_
    return out


def _is_mode(b: Blocks, fam: Family, c, kh, electrical: str) -> np.ndarray:
    """True where Z(c, kh) is singular and bounded (a mode), False at a pole."""
    M = top_impedance(b, fam, c, kh[:, None])["M"][:, 0]
    Z, _ = boundary_matrix(b, fam, M, electrical)
    w = np.abs(np.linalg.eigvalsh(Z))
    return np.isfinite(w).all(axis=-1) & (w.min(axis=-1) <= 1e-7 * np.maximum(w.max(axis=-1), 1e-3)) \
        & (w.max(axis=-1) < 1e6)


def family_modes(b: Blocks, fam: Family, kh, *, electrical: str = "free", n_grid: int | None = None) -> np.ndarray:
    """Speeds of every guided mode of one family below its limiting speed, for each kh.

    Parameters
    ----------
    b : Blocks
    fam : Family
    kh : array_like, shape (k,)
        Wavenumber times total film thickness (>= 0).
    electrical : {"free", "metallized"}
    n_grid : int, optional
        Speed grid points (default :data:`BASE_GRID` + :data:`GRID_PER_KH` max kh).

    Returns
    -------
    ndarray, shape (k, n_modes)
        Ascending speeds (m/s) per kh, NaN-padded; column j is the family's j-th slowest mode.
    """
    kh = np.atleast_1d(np.asarray(kh, dtype=float))
    c_lim = float(np.sqrt(fam.X_limit * b.sA / b.rho[-1]))
    n = n_grid or int(BASE_GRID + GRID_PER_KH * min(float(np.max(kh, initial=0.0)), 100.0))
    kh_max = float(np.max(kh, initial=0.0))
    grid = speed_grid(c_lim, min(lowest_speed(b), 0.5 * c_lim), n, film_bulk_speeds(b), kh_max)
    D = secular(b, fam, grid, np.broadcast_to(kh, (grid.size, kh.size)), electrical)   # (n_c, k)
    s = np.sign(D)
    change = (s[:-1] * s[1:] < 0) & np.isfinite(D[:-1]) & np.isfinite(D[1:])
    ic, ik = np.nonzero(change)
    if ic.size == 0:
        return np.full((kh.size, 0), np.nan)
    roots = _refine(b, fam, grid[ic], grid[ic + 1], D[ic, ik], D[ic + 1, ik], kh[ik], electrical)
    ok = _is_mode(b, fam, roots, kh[ik], electrical)
    ik, roots = ik[ok], roots[ok]
    counts = np.bincount(ik, minlength=kh.size)
    out = np.full((kh.size, max(int(counts.max(initial=0)), 0)), np.nan)
    order = np.lexsort((roots, ik))
    ik, roots = ik[order], roots[order]
    start = np.concatenate([[0], np.cumsum(counts)[:-1]])
    col = np.arange(ik.size) - start[ik]
    out[ik, col] = roots
    return out
