"""The grid scan of the boundary matrix's eigenvalues, and the modes hidden next to a pole in one cell.

Helpers of :mod:`surfwave.layers.modes`: :func:`scan_grid` evaluates the sorted eigenvalues of the
Hermitian boundary matrix Z (closed forms for up to 3 x 3) on a speed grid for all kh at once and
bisects cells whose negative count jumps oddly; :func:`near_poles` finds a mode whose count change
is cancelled by a pole of Z in the same cell, when the pole shows at the cell's ends (a sorted
eigenvalue grows: Foster). Modes whose pair with a pole is too narrow to show there (trapped under
a stiff film) are the business of :mod:`surfwave.layers.counting`.
"""
from __future__ import annotations

import numpy as np

from surfwave.layers.partial import Blocks, Family
from surfwave.layers.recursion import boundary_eigenvalues, boundary_matrix, top_impedance
from surfwave.solvers.boundary import Boundary

__all__ = ["POLE_SPLIT", "hermitian_eigenvalues", "impedance_eigvalsh", "near_poles", "scan_grid"]

#: Bisections of a cell holding a pole and, by its count, a mode (toward the pole).
POLE_SPLIT = 8


def impedance_eigvalsh(Z: np.ndarray) -> np.ndarray:
    """Ascending eigenvalues of Hermitian matrices (..., na, na); NaN rows where Z is not finite."""
    with np.errstate(all="ignore"):
        bad = ~np.isfinite(Z).all(axis=(-1, -2))
        w = np.linalg.eigvalsh(np.where(bad[..., None, None], 0.0, Z))
    w[bad] = np.nan
    return w


def hermitian_eigenvalues(Z: np.ndarray) -> np.ndarray:
    """Ascending eigenvalues of Hermitian matrices Z (..., n, n): closed forms for n <= 3, else LAPACK.

    n = 3: the trigonometric solution of the (real) characteristic cubic of the shifted matrix
    Z - tr(Z)/3; where two eigenvalues nearly coincide (|cos 3 phi| > 1 - 1e-6, where the arccos
    loses digits) and where Z is not finite, LAPACK's eigvalsh. Absolute error ~ 1e-13 |Z| (what
    the grid scan needs: signs, products, the Foster test at 1e-9); NaN rows where Z is not finite.
    """
    n = Z.shape[-1]
    if n > 3 or n == 0:
        return impedance_eigvalsh(Z)
    a = Z[..., 0, 0].real
    if n == 1:
        return a[..., None].copy()
    b = Z[..., 1, 1].real
    if n == 2:
        m, h = 0.5 * (a + b), np.hypot(0.5 * (a - b), np.abs(Z[..., 0, 1]))
        return np.stack([m - h, m + h], axis=-1)
    c = Z[..., 2, 2].real
    d, e, f = Z[..., 0, 1], Z[..., 1, 2], Z[..., 0, 2]
    m = (a + b + c) / 3.0
    a1, b1, c1 = a - m, b - m, c - m
    d2, e2, f2 = d.real ** 2 + d.imag ** 2, e.real ** 2 + e.imag ** 2, f.real ** 2 + f.imag ** 2
    p = (a1 * a1 + b1 * b1 + c1 * c1 + 2.0 * (d2 + e2 + f2)) / 6.0
    q = 0.5 * (a1 * b1 * c1 - a1 * e2 - b1 * f2 - c1 * d2 + 2.0 * (d * e * np.conj(f)).real)
    with np.errstate(all="ignore"):
        sp = np.sqrt(p)
        r = np.where(p > 0, q / (p * sp), 0.0)
        phi = np.arccos(np.clip(r, -1.0, 1.0)) / 3.0
        hi = m + 2.0 * sp * np.cos(phi)
        lo = m + 2.0 * sp * np.cos(phi + 2.0 * np.pi / 3.0)
        w = np.stack([lo, 3.0 * m - hi - lo, hi], axis=-1)
    hard = ~(np.abs(r) <= 1.0 - 1e-6) & (p > 0) | ~np.isfinite(w).all(axis=-1)
    if hard.any():
        w[hard] = impedance_eigvalsh(Z[hard])
    return w


def _grid_eigenvalues(b: Blocks, fam: Family, c, kh, electrical: str | Boundary) -> np.ndarray:
    """:func:`surfwave.layers.recursion.boundary_eigenvalues` for the grid scan (closed-form eigenvalues)."""
    M = top_impedance(b, fam, c, kh)["M"]
    Z, _ = boundary_matrix(b, fam, M, electrical)
    return hermitian_eigenvalues(Z)


def scan_grid(b: Blocks, fam: Family, grid: np.ndarray, kh: np.ndarray, electrical: str | Boundary, rounds: int = 6):
    """det Z, the number of negative eigenvalues and the sorted eigenvalues W (n_c, k, na) on the grid;
    cells whose count rises by more than one, or by one with det of the wrong sign pattern, are
    bisected (``rounds`` times)."""
    w = _grid_eigenvalues(b, fam, grid, np.broadcast_to(kh, (grid.size, kh.size)), electrical)
    D, neg = np.prod(w, axis=-1), (w < 0).sum(axis=-1)
    D[~np.isfinite(w).all(axis=-1)] = np.nan
    for _ in range(rounds):
        step = neg[1:] - neg[:-1]
        odd = (np.abs(step) > 1) | ((np.abs(step) == 1) & ~(D[:-1] * D[1:] < 0)) | \
            ((step == 0) & (D[:-1] * D[1:] < 0))
        cells = np.flatnonzero(odd.any(axis=1))
        if cells.size == 0:
            break
        mid = 0.5 * (grid[cells] + grid[cells + 1])
        wm = _grid_eigenvalues(b, fam, mid, np.broadcast_to(kh, (mid.size, kh.size)), electrical)
        Dm, nm = np.prod(wm, axis=-1), (wm < 0).sum(axis=-1)
        Dm[~np.isfinite(wm).all(axis=-1)] = np.nan
        w = np.insert(w, cells + 1, wm, axis=0)
        grid = np.insert(grid, cells + 1, mid)
        D = np.insert(D, cells + 1, Dm, axis=0)
        neg = np.insert(neg, cells + 1, nm, axis=0)
    return grid, D, neg, w


def _pole_inside(wl: np.ndarray, wr: np.ndarray) -> np.ndarray:
    """True where a cell holds a pole of Z: some sorted eigenvalue is larger at the cell's right end.

    Between poles every eigenvalue of the reactance Z decreases with c (Foster), so the k-th smallest
    does too; only a branch passing a pole (from -inf to +inf) can make a sorted eigenvalue grow.
    """
    tol = 1e-9 * (1.0 + np.abs(wl))
    with np.errstate(invalid="ignore"):
        return (wr > wl + tol).any(axis=-1)


def near_poles(b: Blocks, fam: Family, grid, D, neg, W, kh, electrical: str | Boundary, skip) -> tuple:
    """Brackets of modes hidden next to a pole in one grid cell (their count changes cancel).

    A cell whose count does not change but which holds a pole (:func:`_pole_inside`) holds a mode
    too (or several); per (cell, kh) pair it is bisected :data:`POLE_SPLIT` times, always keeping the
    half with the pole; a half whose count rises by one with a sign change of det Z is a bracket.

    Returns
    -------
    lo, hi, flo, fhi : ndarray, shape (r,)
        Bracket ends (m/s) and det Z there.
    ik : ndarray of int, shape (r,)
        The kh index of each bracket.
    """
    step = neg[1:] - neg[:-1]
    near = (step == 0) & _pole_inside(W[:-1], W[1:]) & ~skip[:, None]
    ic, ik = np.nonzero(near)
    lo, hi = grid[ic], grid[ic + 1]
    Dl, Dh, nl, nh = D[ic, ik], D[ic + 1, ik], neg[ic, ik], neg[ic + 1, ik]
    wl, wh = W[ic, ik], W[ic + 1, ik]
    found: list[tuple] = []
    for _ in range(POLE_SPLIT):
        if ik.size == 0:
            break
        mid = 0.5 * (lo + hi)
        wm = boundary_eigenvalues(b, fam, mid, kh[ik, None], electrical)[:, 0]
        Dm, nm = np.prod(wm, axis=-1), (wm < 0).sum(axis=-1)
        with np.errstate(invalid="ignore"):
            left = (nm - nl == 1) & (Dl * Dm < 0)
            right = (nh - nm == 1) & (Dm * Dh < 0)
        found.append((np.r_[lo[left], mid[right]], np.r_[mid[left], hi[right]], np.r_[Dl[left], Dm[right]],
                      np.r_[Dm[left], Dh[right]], np.r_[ik[left], ik[right]]))
        go_left = _pole_inside(wl, wm)                                       # the pole's half
        keep = ~(left | right) & np.isfinite(Dm)
        lo, hi = np.where(go_left, lo, mid), np.where(go_left, mid, hi)
        Dl, Dh = np.where(go_left, Dl, Dm), np.where(go_left, Dm, Dh)
        nl, nh = np.where(go_left, nl, nm), np.where(go_left, nm, nh)
        wl, wh = np.where(go_left[:, None], wl, wm), np.where(go_left[:, None], wm, wh)
        lo, hi, Dl, Dh, nl, nh, wl, wh, ik = (v[keep] for v in (lo, hi, Dl, Dh, nl, nh, wl, wh, ik))
    if not found:
        empty = np.zeros(0)
        return empty, empty, empty, empty, np.zeros(0, dtype=int)
    return tuple(np.concatenate([f[i] for f in found]) for i in range(5))
