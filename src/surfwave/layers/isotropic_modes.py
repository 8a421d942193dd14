"""Guided modes of isotropic stacks from the pole-free secular functions of :mod:`surfwave.layers.isotropic`.

Search. Per family (P-SV: labels R, S1, S2, ...; SH: L0, L1, ...) the secular function is scanned
on one speed grid shared by all rows (kh values, or frequencies with kh = omega H / c) for
brackets of every mode (:mod:`surfwave.layers.isotropic_scan`: the grid, what it guarantees, the
hunt for two roots in one cell, the rescan of rows with too few modes). All brackets are then
refined together by a safeguarded Newton iteration in
t = sqrt(1 - c^2 / c_lim^2) (c_lim the substrate's shear speed; the function is analytic in t up to
c_lim, in c it has a square-root branch point there) with the exact derivative of
:mod:`surfwave.layers.isotropic_deriv`, to a relative width :data:`C_TOL` in c.
With one film and ``modes`` given, the first step of the scan's hunt for two roots in one cell is
evaluated in the same call as Newton's first round (:func:`both_families`); where the hunt would
have gone on or found a pair, the brackets with the hunt run are refined instead (the same answers).

Group velocity: v_g = c + kh dc/dkh with dc/dkh = -F_kh / F_c, the exact derivatives of the
secular function at the root (those of the last Newton evaluation; the positive normalisations of
F drop out at a zero of F). Power flow is along x1 (angle 0).
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

from surfwave.layers.isotropic import IsoStack
from surfwave.layers.isotropic_deriv import secular_d, secular_d_pair
from surfwave.layers.isotropic_hunt import hunt_settles, hunt_start
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
    phase_curve,
    slowest_speed,
    speed_grid,
)

__all__ = ["CHUNK", "C_TOL", "Rows", "VG_CARRY", "both_families", "family_roots", "refine_brackets", "roots_table",
           "secular_at", "slowest_speed", "speed_grid"]

#: Relative width in c of a converged bracket.
C_TOL = 5e-14
#: Largest carried correction of v_g (relative) accepted without another evaluation.
VG_CARRY = 1e-8
#: Refinement iterations at most.
MAX_ITER = 60


def _at_d(st: IsoStack, prefix: str, rows_of: Rows, r: np.ndarray, t: np.ndarray, kh: np.ndarray
          ) -> tuple[np.ndarray, ...]:
    """:func:`secular_d` (with ``ratio``) of each point's family at (row r, t, kh) (m,).

    Prefix "RL": rows from ``rows_of.split`` on are SH; the points of P-SV rows come first (as
    :func:`both_families` orders its brackets), and both families are evaluated in one pass
    (:func:`secular_d_pair`).
    """
    if prefix != "RL":
        return secular_d(st, prefix, t, kh, ratio=True)
    sh = r >= rows_of.split
    k = int(np.count_nonzero(~sh))
    if not sh[:k].any():
        return secular_d_pair(st, t, kh, k)
    out = np.empty((4, t.size))                    # not in that order (not met): each family on its own
    for m, p in ((~sh, "R"), (sh, "L")):
        out[:, m] = secular_d(st, p, t[m], kh[m], ratio=True)
    return out[0], out[1], out[2], out[3]


def _refine(st: IsoStack, prefix: str, lo: np.ndarray, hi: np.ndarray, rows_of: Rows, r: np.ndarray,
            flo: np.ndarray, fhi: np.ndarray, c3: np.ndarray, f3: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Safeguarded Newton iteration in t on all brackets (c in (lo, hi), of rows r): speeds, group velocities (m,), m/s.

    Starts at the inverse quadratic interpolation through the bracket ends and the third grid point
    (``c3``, ``f3``; linear interpolation where that is NaN or lands outside the bracket); the
    first step is the inverse Hermite interpolation through that first evaluation (F and its
    derivative) and the bracket's ends (Newton's where it would leave the bracket), then Newton
    steps along the row (at fixed kh, or at fixed frequency kh = omega H / c) with the exact
    derivative (:func:`secular_d`); bisection where a step leaves the bracket or, every third
    step, where the bracket has not halved and the steps do not shrink tenfold.
    Converged: a Newton step below the tolerance (C_TOL relative in c; the stepped point is
    returned) or, once the steps shrink tenfold, one whose predicted remaining error |K| step^2
    (K = F'' / 2F' from the derivatives of the last two iterates) is below a tenth of it, and
    whose carried group velocity correction is below :data:`VG_CARRY`; a bracket narrower than
    the tolerance, or F = 0 exactly. The group velocity v_g = c + kh dc/dkh, dc/dkh = -F_kh / F_c,
    comes from the derivatives of the last evaluation (F_kh / F_t carried linearly to the root).
    """
    with np.errstate(all="ignore"):
        out = _newton(st, prefix, lo, hi, rows_of, r, flo, fhi, c3, f3)
    assert out is not None
    return out


#: Points evaluated with Newton's first round (:func:`_newton`): t and kh of P-SV points (m1,), of SH
#: points (m2,), and a test of F there (m1,), (m2,): False stops the refinement (it returns None).
Extra = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, Callable[[np.ndarray, np.ndarray], bool]]


def _newton(st: IsoStack, prefix: str, lo: np.ndarray, hi: np.ndarray, rows_of: Rows, r: np.ndarray,
            flo: np.ndarray, fhi: np.ndarray, c3: np.ndarray, f3: np.ndarray, extra: Extra | None = None,
            first: tuple[np.ndarray, np.ndarray] | list | None = None) -> tuple[np.ndarray, np.ndarray] | None:
    """The loop of :func:`_refine` (floating-point warnings off).

    Only the brackets not yet converged are evaluated (the state of the loop is carried for those
    only); a converged point's answer is written out when it converges. ``extra`` (prefix "RL" only):
    points evaluated in the same call as the first round (:data:`Extra`); None if their test fails
    (or the brackets are not P-SV first). Each point's values do not depend on the others evaluated
    with it (:func:`secular_d_pair`), so the answer is the one without ``extra``. ``first``: with
    ``extra``, a list receiving the first round's values (4, m) when the test fails; else (j (m,),
    values (4, m')): the first round's values of the brackets with j >= 0 are values[:, j] (those of
    the same bracket in an earlier call: the same point), the others are evaluated.
    """
    c_lim = st.c_lim
    freq = rows_of.freq
    a, z, y = np.sqrt(1.0 - (np.array([hi, lo, c3]) / c_lim) ** 2)    # bracket ends in t (a: the fast end), c3
    fa, fz = fhi.astype(float), flo.astype(float)
    daz, da3, dz3 = fa - fz, fa - f3, fz - f3
    x = a * fz * f3 / (daz * da3) - z * fa * f3 / (daz * dz3) + y * fa * fz / (da3 * dz3)
    left, right = np.minimum(a, z), np.maximum(a, z)
    x = np.where((x > left) & (x < right), x, a + fa * (z - a) / daz)          # NaN compares False
    mid = 0.5 * (a + z)
    x = np.where((x > left) & (x < right), x, mid)
    n = lo.size
    out, ratio = mid, np.full(n, np.nan)                             # t of the roots, F_kh / F_t there
    idx, b = np.arange(n), rows_of.base[r]                           # the brackets still iterated; their rows
    k_psv = None                                                     # prefix "RL": P-SV points first, this many
    if prefix == "RL":
        sh = r >= rows_of.split
        k = int(np.count_nonzero(~sh))
        k_psv = None if sh[:k].any() else k
    sl, width = np.where(a == left, fa > 0, fz > 0), right - left    # F > 0 at left; the bracket's width
    newt, aprev = np.zeros(n, dtype=bool), np.full(n, np.inf)       # last move a Newton step; its size
    xp = dp = rp = np.full(n, np.nan)                                # previous iterate: t, F', F_kh / F_t
    for it in range(MAX_ITER):
        w = 1.0 - x * x
        c = c_lim * np.sqrt(w)
        kh = b / c if freq else b
        if it == 0 and extra is not None:
            if k_psv is None:
                return None
            tR, kR, tL, kL, test = extra
            nR, m = tR.size, x.size
            kh_ = np.broadcast_to(kh, x.shape)
            res = secular_d_pair(st, np.concatenate([x[:k_psv], tR, x[k_psv:], tL]),
                                 np.concatenate([kh_[:k_psv], kR, kh_[k_psv:], kL]), k_psv + nR)
            sel = np.r_[0:k_psv, k_psv + nR:m + nR]
            if not test(res[0][k_psv:k_psv + nR], res[0][m + nR:]):
                if isinstance(first, list):
                    first.append(np.array([v[sel] for v in res]))
                return None
            fx, ft, fk, rk = (v[sel] for v in res)
        elif it == 0 and isinstance(first, tuple):
            j, vals = first
            have = j >= 0
            got = vals[:, np.where(have, j, 0)]
            miss = np.flatnonzero(~have)
            if miss.size:
                km = None if k_psv is None else int(np.count_nonzero(miss < k_psv))
                kh_ = np.broadcast_to(kh, x.shape)
                got[:, miss] = (_at_d(st, prefix, rows_of, r[miss], x[miss], kh_[miss]) if km is None
                                else secular_d_pair(st, x[miss], kh_[miss], km))
            fx, ft, fk, rk = got
        elif k_psv is None:
            fx, ft, fk, rk = _at_d(st, prefix, rows_of, r[idx], x, kh)
        else:
            fx, ft, fk, rk = secular_d_pair(st, x, kh, k_psv)
        xw = x / w
        # along the row: at fixed frequency kh = omega H / c, dkh/dt = kh t / (1 - t^2)
        d = ft + fk * kh * xw if freq else ft
        step = fx / d
        if it == 0:
            # first step: t(F) by Hermite interpolation through (F, t, dt/dF) here and the bracket's ends
            q1 = ((a - x) / (fa - fx) - 1.0 / d) / (fa - fx)
            q2 = (((z - a) / (fz - fa) - (a - x) / (fa - fx)) / (fz - fx) - q1) / (fz - fx)
            step = fx * (1.0 / d - fx * (q1 - fa * q2))
        at_left = (fx > 0) == sl                   # x replaces the end where F has its sign
        left, right = np.where(at_left, x, left), np.where(at_left, right, x)
        xn = x - step
        inside = (xn > left) & (xn < right)
        if it == 0:                                # Newton's step where that one is unusable
            off = ~inside
            step = np.where(off, fx / d, step)
            xn = np.where(off, x - step, xn)
            inside = (xn > left) & (xn < right)
            # no convergence test at the start (one within the tolerance stops at the next step)
            newt, aprev, xp, dp, rp = inside, np.abs(step), x, d, rk
            x = np.where(inside, xn, 0.5 * (left + right))
            continue
        ast = np.abs(step)
        # (C_TOL relative in c; not below 4 ulps of t, which rounding cannot resolve)
        tol = np.maximum(np.minimum(C_TOL * w / x, 1e-8 * x), 8.9e-16 * x)
        fin = np.where((xn >= left) & (xn <= right) & (fx != 0), xn, x)
        done = (ast <= tol) | (right - left <= tol) | (fx == 0)
        conv = newt & (ast <= 0.1 * aprev)
        dx = x - xp
        delta = (rk - rp) / dx * (fin - x)         # F_kh / F_t carried to fin
        carried = rk + delta
        # the carried correction of v_g = c + kh (F_kh / F_t) c_lim^2 t / c itself, relative
        carry = kh * np.abs(delta) * xw
        # error left after the Newton step: K step^2, K = F'' / (2 F') from the last two derivatives
        K = (d - dp) / (2.0 * d * dx)
        done |= conv & (np.abs(K) * ast * ast <= 0.1 * tol) & (ast <= 1e-7 * x) & (carry <= VG_CARRY)
        anyd = bool(done.any())
        if anyd:
            j = idx[done]
            out[j] = fin[done]
            ratio[j] = np.where(conv & np.isfinite(carried), carried, rk)[done]
            if done.all():
                break
        bis = ~inside
        if it % 3 == 2:                            # every third step: bisect where the bracket did not halve
            bis |= (right - left > 0.5 * width) & ~conv
            width = right - left
        nxt = np.where(bis, 0.5 * (left + right), xn)
        newt, aprev, xp, dp, rp = ~bis, ast, x, d, rk
        if anyd:                                   # carry the state of the others only
            keep = np.flatnonzero(~done)
            if k_psv is not None:
                k_psv = int(np.searchsorted(keep, k_psv))
            nxt, newt, aprev, xp, dp, rp = nxt[keep], newt[keep], aprev[keep], xp[keep], dp[keep], rp[keep]
            left, right, sl, width, idx, b = left[keep], right[keep], sl[keep], width[keep], idx[keep], b[keep]
        x = nxt
    else:                                          # not converged in MAX_ITER (not seen): the last iterate
        c = c_lim * np.sqrt(1.0 - x * x)
        rk = _at_d(st, prefix, rows_of, r[idx], x, rows_of.pairs(r[idx], c))[3]
        out[idx], ratio[idx] = x, rk
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
    curve = None
    if grid is None:
        curve = phase_curve(st) if st.frac.size == 1 else None
        grid = speed_grid(st, rows_of, 1, curve)
    # with one film and ``modes`` given, the first scan's hunt for hidden pairs (isotropic_scan._hidden_pairs)
    # is evaluated with Newton's first round: if it finds nothing (no point of F's other sign, every
    # minimum dropped as a near miss after that step) the brackets are those of the scan as it is; else
    # the brackets with the hunt run (from the same evaluated grid) are refined, the first round's values
    # of the brackets they share reused. (Every mode: many minima, and at large kh hunts that go on
    # made this slower, 5.7 -> 7.3 ms at 200 kh up to 30: not folded.)
    pend: tuple[list, list, list] | None = ([], [], []) if st.frac.size == 1 and modes is not None else None
    bR, bL = _brackets_both(st, rows_of, modes, grid, curve, pending=pend)
    extra = _hunt_points(st, rows_of, pend) if pend is not None and (pend[0] or pend[1]) else None
    res = None
    first: tuple[np.ndarray, np.ndarray] | list = []
    for _ in range(2):
        r, lo, hi, flo, fhi, c3, f3 = (np.concatenate([u, v + n if k == 0 else v])
                                       for k, (u, v) in enumerate(zip(bR, bL)))
        with np.errstate(all="ignore"):
            res = _newton(st, "RL", lo, hi, rows_of.both(), r, flo, fhi, c3, f3, extra, first)
        if res is not None:
            break
        assert pend is not None and isinstance(first, list) and first
        key = (r, lo, hi, np.nan_to_num(c3, nan=-1.0))
        bR, bL = pend[2][0]()
        extra = None
        new = (np.concatenate([bR[0], bL[0] + n]), np.concatenate([bR[1], bL[1]]), np.concatenate([bR[2], bL[2]]),
               np.nan_to_num(np.concatenate([bR[5], bL[5]]), nan=-1.0))
        first = (_same(key, new), first[0])
    assert res is not None
    roots, vg = res
    sh = r >= n
    return [_table(n, r[~sh], roots[~sh], vg[~sh]), _table(n, r[sh] - n, roots[sh], vg[sh])]


def _same(old: tuple[np.ndarray, ...], new: tuple[np.ndarray, ...]) -> np.ndarray:
    """Per bracket of ``new`` (columns (m,)) the index of the bracket of ``old`` (columns (m',)) with equal
    columns, or -1 (the keys of each are distinct)."""
    m0 = old[0].size
    cols = [np.concatenate([a, b]) for a, b in zip(old, new)]
    order = np.lexsort(cols[::-1])                                     # stable: old before new where equal
    eq = np.ones(max(order.size - 1, 0), dtype=bool)
    for c in cols:
        eq &= c[order[1:]] == c[order[:-1]]
    eq &= (order[:-1] < m0) & (order[1:] >= m0)
    out = np.full(new[0].size, -1, dtype=np.intp)
    out[order[1:][eq] - m0] = order[:-1][eq]
    return out


def _hunt_points(st: IsoStack, rows_of: Rows, pend: tuple[list, list, list]) -> Extra:
    """The first points of the hunts ``pend`` (P-SV, SH: lists of (rows, speeds, F) of
    :func:`surfwave.layers.isotropic_scan._assemble`) as :data:`Extra`, with the test that they stop there."""
    pts = []
    for p in pend[:2]:
        if p:
            rr, cs, Fs = p[0]
            x = hunt_start(cs, Fs)
            pts.append((np.sqrt(1.0 - (x / st.c_lim) ** 2), rows_of.pairs(rr, x), cs, Fs, x))
        else:
            e = np.zeros(0)
            pts.append((e, e, np.zeros((0, 3)), np.zeros((0, 3)), e))
    (tR, kR, cR, FR, xR), (tL, kL, cL, FL, xL) = pts

    def test(fR: np.ndarray, fL: np.ndarray) -> bool:
        return hunt_settles(cR, FR, xR, fR) and hunt_settles(cL, FL, xL, fL)

    return tR, kR, tL, kL, test


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
