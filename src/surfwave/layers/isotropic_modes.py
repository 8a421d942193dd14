"""Guided modes of isotropic stacks from the pole-free secular functions of :mod:`surfwave.layers.isotropic`.

Search. Per family (P-SV: labels R, S1, S2, ...; SH: L0, L1, ...) the secular function is scanned
on one speed grid shared by all rows (kh values, or frequencies with kh = omega H / c) for
brackets of every mode (:mod:`surfwave.layers.isotropic_scan`: the grid, what it guarantees, the
hunt for two roots in one cell, the rescan of rows with too few modes). All brackets are then
refined together by a safeguarded Newton iteration in
t = sqrt(1 - c^2 / c_lim^2) (c_lim the substrate's shear speed; the function is analytic in t up to
c_lim, in c it has a square-root branch point there) with the exact derivative of
:mod:`surfwave.layers.isotropic_deriv`, to a relative width :data:`C_TOL` in c.

Group velocity: v_g = c + kh dc/dkh with dc/dkh = -F_kh / F_c, the exact derivatives of the
secular function at the root (those of the last Newton evaluation; the positive normalisations of
F drop out at a zero of F). Power flow is along x1 (angle 0).
"""
from __future__ import annotations

import numpy as np

from surfwave.layers.isotropic import IsoStack
from surfwave.layers.isotropic_deriv import secular_d
from surfwave.layers.isotropic_scan import (  # noqa: F401  (the grid's names, public here as before)
    CHUNK,
    FLOOR,
    N_BASE,
    N_LOW,
    N_TOP,
    PAIR_STEPS,
    PHASE_STEP,
    RESCAN,
    Rows,
    _at,
    _brackets,
    _brackets_both,
    slowest_speed,
    speed_grid,
)

__all__ = ["CHUNK", "C_TOL", "Rows", "both_families", "family_roots", "refine_brackets", "roots_table", "secular_at",
           "slowest_speed", "speed_grid"]

#: Relative width in c of a converged bracket.
C_TOL = 5e-14
#: Refinement iterations at most.
MAX_ITER = 60


def _at_d(st: IsoStack, prefix: str, rows_of: Rows, r: np.ndarray, t: np.ndarray, kh: np.ndarray, act: np.ndarray
          ) -> tuple[np.ndarray, ...]:
    """:func:`secular_d` (with ``ratio``) of each point's family at (row r, t, kh) (m,).

    Prefix "RL": rows from ``rows_of.split`` on are SH; a family without an active point (``act``)
    is not evaluated (its values are NaN).
    """
    if prefix != "RL":
        return secular_d(st, prefix, t, kh, ratio=True)
    sh = r >= rows_of.split
    out = np.full((4, t.size), np.nan)
    for m, p in ((~sh, "R"), (sh, "L")):
        if (act & m).any():
            out[:, m] = secular_d(st, p, t[m], kh[m], ratio=True)
    return out[0], out[1], out[2], out[3]


def _refine(st: IsoStack, prefix: str, lo: np.ndarray, hi: np.ndarray, rows_of: Rows, r: np.ndarray,
            flo: np.ndarray, fhi: np.ndarray, c3: np.ndarray, f3: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Safeguarded Newton iteration in t on all brackets (c in (lo, hi), of rows r): speeds, group velocities (m,), m/s.

    Starts at the inverse quadratic interpolation through the bracket ends and the third grid point
    (``c3``, ``f3``; linear interpolation where that is NaN or lands outside the bracket); Newton
    steps along the row (at fixed kh, or at fixed frequency kh = omega H / c) with the exact
    derivative (:func:`secular_d`); bisection where a step leaves the bracket or, every third
    step, where the bracket has not halved and the steps do not shrink tenfold.
    Converged: a Newton step below the tolerance (C_TOL relative in c; the stepped point is
    returned) or, after two Newton steps, one whose predicted remaining error (quadratic
    convergence: step^3 / previous step^2) is below a tenth of it; a bracket narrower than the
    tolerance, or F = 0 exactly. The group velocity
    v_g = c + kh dc/dkh, dc/dkh = -F_kh / F_c, comes from the derivatives of the last evaluation.
    """
    with np.errstate(all="ignore"):
        return _newton(st, prefix, lo, hi, rows_of, r, flo, fhi, c3, f3)


def _newton(st: IsoStack, prefix: str, lo: np.ndarray, hi: np.ndarray, rows_of: Rows, r: np.ndarray,
            flo: np.ndarray, fhi: np.ndarray, c3: np.ndarray, f3: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The loop of :func:`_refine` (floating-point warnings off: converged points ride along unused).

    Every point is evaluated at every iteration (one vectorised call costs the same for a few
    hundred points as for a few); a converged point's answer is frozen when it converges.
    """
    c_lim = st.c_lim
    a = np.sqrt(1.0 - (hi / c_lim) ** 2)            # bracket ends in t (a: the fast end)
    z = np.sqrt(1.0 - (lo / c_lim) ** 2)
    fa, fz = fhi.astype(float), flo.astype(float)
    y = np.sqrt(1.0 - (c3 / c_lim) ** 2)
    x = (a * fz * f3 / ((fa - fz) * (fa - f3)) + z * fa * f3 / ((fz - fa) * (fz - f3))
         + y * fa * fz / ((f3 - fa) * (f3 - fz)))
    left, right = np.minimum(a, z), np.maximum(a, z)
    x = np.where((x > left) & (x < right), x, a - fa * (z - a) / (fz - fa))     # NaN compares False
    x = np.where((x > left) & (x < right), x, 0.5 * (a + z))
    width = right - left
    out, ratio = 0.5 * (a + z), np.full(lo.size, np.nan)            # t of the roots, F_kh / F_t there
    act = np.ones(lo.size, dtype=bool)
    newt, prev = np.zeros(lo.size, dtype=bool), np.full(lo.size, np.inf)   # last move a Newton step; its size
    xp, rp = np.full(lo.size, np.nan), np.full(lo.size, np.nan)            # the previous iterate and F_kh / F_t
    for it in range(MAX_ITER):
        c = c_lim * np.sqrt(1.0 - x * x)
        kh = rows_of.pairs(r, c)
        fx, ft, fk, rk = _at_d(st, prefix, rows_of, r, x, kh, act)
        # along the row: at fixed frequency kh = omega H / c, dkh/dt = kh t / (1 - t^2)
        step = fx / (ft + fk * kh * x / (1.0 - x * x)) if rows_of.freq else fx / ft
        side_a = (fx > 0) == (fa > 0)
        a, fa = np.where(side_a, x, a), np.where(side_a, fx, fa)
        z, fz = np.where(side_a, z, x), np.where(side_a, fz, fx)
        left, right = np.minimum(a, z), np.maximum(a, z)
        xn = x - step
        # (C_TOL relative in c; not below 4 ulps of t, which rounding cannot resolve)
        tol = np.maximum(np.minimum(C_TOL * (1.0 - x * x) / x, 1e-8 * x), 8.9e-16 * x)
        # quadratic convergence: after a Newton step that follows a Newton step, the error left is
        # about step^3 / previous_step^2; below a tenth of the tolerance the stepped point is the root.
        # F_kh / F_t is carried from x to it linearly (slope from the previous iterate, a Newton step
        # away): v_g to ~ the step times the previous step.
        ast = np.abs(step)
        conv = newt & (ast <= 0.1 * np.abs(prev))
        fin = np.where((xn >= left) & (xn <= right) & (fx != 0), xn, x)
        carried = rk + (rk - rp) / (x - xp) * (fin - x)
        # the carried correction of v_g = c + kh (F_kh / F_t) c_lim^2 t / c itself below 1e-7 c: its error,
        # a small fraction of it (the ratio is smooth: :func:`secular_d`), cannot matter
        small = kh * np.abs(carried - rk) * c_lim * c_lim * x <= 1e-7 * c * c
        done = act & (((ast <= tol) | (conv & (ast ** 3 <= 0.1 * tol * prev * prev) & (ast <= 1e-7 * x) & small))
                      | (right - left <= tol) | (fx == 0))
        out = np.where(done, fin, out)
        ratio = np.where(done, np.where(conv & np.isfinite(carried), carried, rk), ratio)
        act &= ~done
        if not act.any():
            break
        slow = (it % 3 == 2) & (right - left > 0.5 * width) & ~conv
        bis = ~((xn > left) & (xn < right)) | slow
        newt, prev, xp, rp = ~bis, step, x, rk
        x = np.where(bis, 0.5 * (left + right), xn)
        if it % 3 == 2:
            width = right - left
    else:                                          # not converged in MAX_ITER (not seen): the last iterate
        c = c_lim * np.sqrt(1.0 - x * x)
        rk = _at_d(st, prefix, rows_of, r, x, rows_of.pairs(r, c), act)[3]
        out, ratio = np.where(act, x, out), np.where(act, rk, ratio)
    c = c_lim * np.sqrt(1.0 - out * out)
    kh = rows_of.pairs(r, c)
    return c, c + kh * ratio * c_lim * c_lim * out / c     # dc/dkh = -F_kh / (F_t dt/dc), dt/dc = -c / (c_lim^2 t)


def family_roots(st: IsoStack, prefix: str, rows_of: Rows, modes: int | None, grid: np.ndarray | None = None
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Speeds and group velocities (n_rows, n_modes) of one family's guided modes, ascending, NaN-padded.

    Parameters
    ----------
    st : IsoStack
    prefix : {"R", "L"}
        P-SV or SH.
    rows_of : Rows
        The rows (kh or frequencies; the row-count guard compares neighbours in ascending order).
    modes : int or None
        At most this many modes per row (the slowest); None: all.
    grid : ndarray, optional
        ``speed_grid(st, rows_of)`` when already computed (both families share it).
    """
    n_rows = rows_of.base.size
    r, lo, hi, flo, fhi, c3, f3 = _brackets(st, prefix, rows_of, modes, grid)
    if r.size == 0:
        return np.full((n_rows, 0), np.nan), np.full((n_rows, 0), np.nan)
    roots, vg = _refine(st, prefix, lo, hi, rows_of, r, flo, fhi, c3, f3)
    return _table(n_rows, r, roots, vg)


def both_families(st: IsoStack, rows_of: Rows, modes: int | None, grid: np.ndarray | None = None
                  ) -> list[tuple[np.ndarray, np.ndarray]]:
    """:func:`family_roots` of P-SV and SH (in that order), the brackets of both refined in one Newton loop."""
    n = rows_of.base.size
    grid = speed_grid(st, rows_of) if grid is None else grid
    bR, bL = _brackets_both(st, rows_of, modes, grid)
    r, lo, hi, flo, fhi, c3, f3 = (np.concatenate([u, v + n if k == 0 else v]) for k, (u, v) in enumerate(zip(bR, bL)))
    roots, vg = _refine(st, "RL", lo, hi, rows_of.both(), r, flo, fhi, c3, f3)
    sh = r >= n
    return [_table(n, r[~sh], roots[~sh], vg[~sh]), _table(n, r[sh] - n, roots[sh], vg[sh])]


def _table(n_rows: int, r: np.ndarray, roots: np.ndarray, vg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Speeds and group velocities of roots (m,) of rows r as (n_rows, width) tables, ascending, NaN-padded."""
    counts = np.bincount(r, minlength=n_rows)
    width = int(counts.max(initial=0))
    c_out, v_out = np.full((n_rows, width), np.nan), np.full((n_rows, width), np.nan)
    if r.size == 0:
        return c_out, v_out
    srt = np.lexsort((roots, r))
    r, roots, vg = r[srt], roots[srt], vg[srt]
    col = np.arange(r.size) - (np.cumsum(counts) - counts)[r]         # rank within the row
    c_out[r, col], v_out[r, col] = roots, vg
    return c_out, v_out


#: Public names of the pieces :mod:`surfwave.layers.isotropic_guard` reuses: the secular function at
#: (row, speed) pairs, the Newton refinement of brackets, and the (rows, width) table of roots.
secular_at = _at
refine_brackets = _refine
roots_table = _table
