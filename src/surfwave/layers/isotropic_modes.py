"""Guided modes of isotropic stacks from the pole-free secular functions of :mod:`surfwave.layers.isotropic`.

Search. Per family (P-SV: labels R, S1, S2, ...; SH: L0, L1, ...) the secular function is evaluated
on one speed grid shared by all rows (kh values, or frequencies with kh = omega H / c), in chunks of
:data:`CHUNK` speeds from the bottom up; a row stops once it holds ``modes`` sign changes. The
function has no poles, so every sign change is a mode and the n-th one from below is the n-th
mode. All brackets are then refined together by a safeguarded Newton iteration in
t = sqrt(1 - c^2 / c_lim^2) (c_lim the substrate's shear speed; the function is analytic in t up to
c_lim, in c it has a square-root branch point there) with the exact derivative of
:mod:`surfwave.layers.isotropic_deriv`, to a relative width :data:`C_TOL` in c.

Grid, and what it guarantees. The grid runs from ``c_floor`` = :data:`FLOOR` x the slowest shear
speed of any layer (the floor of the general path) to c_lim. Above ``c_lo`` = 0.95 x the slowest
Rayleigh speed of any layer it is dense; below, where every wave of every layer is evanescent and
the function varies slowly, it has :data:`N_LOW` points geometric in c (a dense film loads the
surface by its mass and takes the R mode below every layer's Rayleigh speed: 0.87 x the slowest
in a random sample of stacks) and ``c_lo`` itself. It is the union of that, of
(i) :data:`N_TOP` points geometric in t from 1e-7 to 0.02 (modes enter at c_lim with t ~ kh - kh_cutoff),
(ii) :data:`N_BASE` points uniform in t and as many uniform in c (less those within half their
spacing of a point of (iii)), and (iii) points where the total vertical phase
Phi(c) = kh_max(c) sum_l h_l/H (nu_a + nu_b) (nu = sqrt(c^2 / v^2 - 1) where real) advances by
:data:`PHASE_STEP`. Between consecutive modes of one family the field of some film turns by about
pi in depth, so a cell holds a fraction of a mode spacing. Every sign change on the grid is a mode
(the function has no poles). Two modes in one cell (modes localised in different films, weakly
coupled, can be arbitrarily close) leave no sign change: every local minimum of |F| on the grid is
hunted by parabolic steps (:func:`_hidden_pairs`), and a point of the opposite sign splits the
cell into two brackets; the pair is missed only if the dip between the two roots escapes that hunt.
As a last guard a row holding fewer modes than rows on both sides of it (modes enter only at c_lim,
so counts are monotone in kh and in frequency) is searched again on a grid :data:`RESCAN` times finer.
This is not a proof: :mod:`surfwave.layers.isotropic_guard` checks the rows of stacks with two
films or more against the exact mode count and re-solves those that fail.

Group velocity: v_g = c + kh dc/dkh with dc/dkh = -F_kh / F_c, the exact derivatives of the
secular function at the root (those of the last Newton evaluation; the positive normalisations of
F drop out at a zero of F). Power flow is along x1 (angle 0).
"""
from __future__ import annotations

import math

import numpy as np

from surfwave.layers.isotropic import IsoStack, psv_kernels, secular_psv, secular_sh
from surfwave.layers.isotropic_deriv import secular_d, secular_d_pair

__all__ = ["CHUNK", "C_TOL", "Rows", "VG_CARRY", "both_families", "family_roots", "refine_brackets", "roots_table",
           "secular_at", "slowest_speed", "speed_grid"]

#: Relative width in c of a converged bracket.
C_TOL = 5e-14
#: Largest carried correction of v_g (relative) accepted without another evaluation.
VG_CARRY = 1e-8
#: Refinement iterations at most.
MAX_ITER = 60
#: Speeds per chunk of the upward scan (about: the grid is cut into near-equal chunks).
CHUNK = 32
#: Points uniform in t and uniform in c.
N_BASE = 20
#: Lowest speed searched, in units of the slowest shear speed of any layer (the general path's floor).
FLOOR = 0.05
#: Points geometric in c from the floor to c_lo (mass loading by a dense film takes R below c_lo).
N_LOW = 10
#: Points geometric in t from 1e-7 to 0.02 (next to c_lim, where modes enter).
N_TOP = 12
#: Phase step of the grid, radians.
PHASE_STEP = math.pi / 4
#: Parabolic / golden steps hunting two roots hidden in one grid cell.
PAIR_STEPS = 10
#: Refinement factor of the rescan of rows with too few modes.
RESCAN = 4



class Rows:
    """The rows of a call: fixed kh (``base`` = kh) or fixed frequency (``base`` = omega H, kh = omega H / c).

    Parameters
    ----------
    base : ndarray, shape (n,)
        kh, or 2 pi f H (m/s).
    freq : bool
        True at fixed frequency.
    """

    def __init__(self, base: np.ndarray, freq: bool) -> None:
        self.base, self.freq = np.asarray(base, dtype=float), freq
        self.split: int | None = None          # set by both(): rows from here on are SH

    def both(self) -> Rows:
        """These rows twice: P-SV rows 0 ... n - 1, SH rows n ... 2n - 1 (prefix "RL" of the refinement)."""
        out = Rows(np.concatenate([self.base, self.base]), self.freq)
        out.split = self.base.size
        return out

    def grid(self, rows: np.ndarray, c: np.ndarray) -> np.ndarray:
        """kh (r, n) of rows (r,) at speeds c (n,)."""
        b = self.base[rows][:, None]
        return b / c[None, :] if self.freq else np.broadcast_to(b, (rows.size, c.size))

    def pairs(self, rows: np.ndarray, c: np.ndarray) -> np.ndarray:
        """kh (m,) of (row, speed) pairs (m,)."""
        return self.base[rows] / c if self.freq else self.base[rows]

    def kh_max(self, c: np.ndarray) -> np.ndarray:
        """An upper bound (n,) of every row's kh at speeds c (n,)."""
        top = float(self.base.max(initial=0.0))
        return top / c if self.freq else np.full(c.shape, top)


def _rayleigh_ratio(kappa: float) -> float:
    """c_R^2 / beta^2 of an isotropic half-space with beta^2 / alpha^2 = kappa (bisection, 1e-12)."""
    lo, hi = 1e-9, 1.0
    for _ in range(42):
        x = 0.5 * (lo + hi)
        if (2.0 - x) ** 2 - 4.0 * math.sqrt((1.0 - x) * (1.0 - kappa * x)) < 0.0:
            lo = x
        else:
            hi = x
    return lo


def slowest_speed(st: IsoStack) -> float:
    """The slowest Rayleigh speed of any layer as a half-space, m/s."""
    beta = st.shear
    kap = st.mu / (st.lam + 2 * st.mu)
    return float(min(b * math.sqrt(_rayleigh_ratio(float(k))) for b, k in zip(beta, kap)))


def speed_grid(st: IsoStack, rows_of: Rows, fine: int = 1) -> np.ndarray:
    """Ascending speeds (n,) in [c_floor, c_lim) (module docstring), for the rows' largest kh at each speed."""
    c_lim = st.c_lim
    c_lo = 0.95 * slowest_speed(st)
    t_hi = math.sqrt(1.0 - (c_lo / c_lim) ** 2)
    top = np.geomspace(1e-7, 0.02, N_TOP, endpoint=False)
    t = np.linspace(0.02, t_hi, N_BASE * fine)
    base = np.concatenate([c_lim * np.sqrt(1.0 - t * t), np.linspace(c_lo, c_lim, N_BASE * fine)])
    c_floor = FLOOR * float(st.shear.min())
    low = np.geomspace(c_floor, c_lo, N_LOW, endpoint=False) if c_floor < c_lo else np.zeros(0)
    parts = [c_lim * np.sqrt(1.0 - top * top), np.array([c_lo]), low]       # c_lo itself, always
    if st.frac.size:
        aux = np.linspace(c_lo, c_lim, 4000)
        nu = sum(st.frac[i] * (np.sqrt(np.maximum((aux / v[i]) ** 2 - 1.0, 0.0)))
                 for v in (st.shear, st.longitudinal) for i in range(st.frac.size))
        phase = rows_of.kh_max(aux) * nu
        levels = np.arange(PHASE_STEP / fine, float(phase[-1]), PHASE_STEP / fine)
        if levels.size:
            pts = np.interp(levels, phase, aux)
            parts.append(pts)
            # a base point within half the base spacing of a phase point adds nothing
            t_base = np.sqrt(np.maximum(1.0 - (base / c_lim) ** 2, 0.0))
            step_c = (c_lim - c_lo) / (N_BASE * fine)                       # of the c-uniform part
            dc = np.minimum(step_c, c_lim * c_lim * t_base * t_hi / (base * N_BASE * fine))   # and the t-uniform
            k = np.clip(np.searchsorted(pts, base), 1, pts.size - 1) if pts.size > 1 else np.zeros(base.size, int)
            near = np.minimum(np.abs(pts[k] - base), np.abs(pts[np.maximum(k - 1, 0)] - base))
            base = base[near > 0.5 * dc]
    g = np.unique(np.concatenate(parts + [base]))
    g = g[(g == c_lo) | (np.abs(g - c_lo) > 1e-12 * c_lo)]              # c_lo once (not also rounded from t_hi)
    return g[(g >= min(c_floor, c_lo)) & (g < c_lim)]


def _secular(st: IsoStack, prefix: str, c: np.ndarray, kh: np.ndarray) -> np.ndarray:
    """The family's secular function at speeds c (n,) and kh (r, n)."""
    if prefix == "L":
        return secular_sh(st, c, kh)
    return secular_psv(st, c, kh)


def _at(st: IsoStack, prefix: str, rows_of: Rows, r: np.ndarray, c: np.ndarray) -> np.ndarray:
    """The secular function at (row, speed) pairs r, c (m,)."""
    return _secular(st, prefix, c, rows_of.pairs(r, c)[None, :])[0]


def _hidden_pairs(st: IsoStack, prefix: str, rows_of: Rows, r: np.ndarray, cs: np.ndarray, Fs: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Split points of two roots hidden between grid speeds: (found (m,), x (m,), F at x (m,)).

    ``cs``, ``Fs`` (m, 3): three consecutive grid speeds around a local minimum of |F| without a sign
    change. The minimum of s F (s its sign) is hunted by parabolic steps (golden-section fallback)
    for :data:`PAIR_STEPS` steps; where s F < 0 at some point x, (c_left, x) and (x, c_right) each
    hold one root. From the second step on, a candidate whose parabola puts the minimum above 0.7 x
    the lowest value seen is dropped (a near miss).
    """
    s = np.sign(Fs[:, 1])
    (cl, cm, ch), (gl, gm, gh) = cs.T.copy(), (Fs * s[:, None]).T.copy()
    found = np.zeros(r.size, dtype=bool)
    x_out = np.full(r.size, np.nan)
    f_out = np.full(r.size, np.nan)
    idx = np.arange(r.size)
    for step in range(PAIR_STEPS):
        if idx.size == 0:
            break
        with np.errstate(all="ignore"):
            a, b = cm - cl, cm - ch
            den = a * (gm - gh) - b * (gm - gl)
            x = cm - 0.5 * (a * a * (gm - gh) - b * b * (gm - gl)) / den
            curv = ((gl - gm) / a - (gh - gm) / b) / (a - b)
            g_min = gm - curv * (cm - x) ** 2                            # the parabola's minimum
        if step > 0:
            # after one step the parabola models the dip: a minimum it puts well above zero is a
            # near miss, not two roots
            clear = np.isfinite(g_min) & (curv > 0) & (g_min > 0.7 * gm)
            keep = ~clear
            idx, cl, cm, ch, gl, gm, gh, a, b, x = (v[keep] for v in (idx, cl, cm, ch, gl, gm, gh, a, b, x))
            if idx.size == 0:
                break
        wide_left = a > -b
        gold = np.where(wide_left, cm - 0.382 * a, cm - 0.382 * b)
        bad = ~np.isfinite(x) | (x <= cl) | (x >= ch) | (np.abs(x - cm) < 1e-3 * (ch - cl))
        x = np.where(bad, gold, x)
        gx = _at(st, prefix, rows_of, r[idx], x) * s[idx]
        hit = gx < 0
        found[idx[hit]], x_out[idx[hit]], f_out[idx[hit]] = True, x[hit], gx[hit] * s[idx[hit]]
        better, left = gx < gm, x < cm
        cl, ch = (np.where(better, np.where(left, cl, cm), np.where(left, x, cl)),
                  np.where(better, np.where(left, cm, ch), np.where(left, ch, x)))
        gl, gh = (np.where(better, np.where(left, gl, gm), np.where(left, gx, gl)),
                  np.where(better, np.where(left, gm, gh), np.where(left, gh, gx)))
        cm, gm = np.where(better, x, cm), np.where(better, gx, gm)
        keep = ~hit & (ch - cl > 1e-9 * cm)
        idx, cl, cm, ch, gl, gm, gh = (v[keep] for v in (idx, cl, cm, ch, gl, gm, gh))
    return found, x_out, f_out


def _scan(st: IsoStack, prefix: str, grid: np.ndarray, rows_of: Rows, rows: np.ndarray, need: float
          ) -> tuple[np.ndarray, ...]:
    """Brackets (row, lower speed, upper speed, F at both, a third grid speed next to them or NaN, F there).

    The grid is evaluated chunk by chunk until each row holds ``need`` sign changes; a root is a sign
    change between grid speeds, or one of two roots hidden in a grid cell next to a local minimum of
    |F| (:func:`_hidden_pairs`, all candidates of all chunks at once). Per row the brackets are
    sorted and the first ``need`` kept.
    """
    found = np.zeros(rows.size, dtype=int)
    act = np.arange(rows.size)
    c_old, F_old = grid[:0], np.zeros((rows.size, 0))                 # the last two columns seen
    rr: list[np.ndarray] = []
    lo: list[np.ndarray] = []
    hi: list[np.ndarray] = []
    flo: list[np.ndarray] = []
    fhi: list[np.ndarray] = []
    c3: list[np.ndarray] = []                                          # a third grid point next to the bracket
    f3: list[np.ndarray] = []
    cands: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
    cuts = np.linspace(0, grid.size, max(round(grid.size / CHUNK), 1) + 1).astype(int)   # near-equal chunks
    for start, stop in zip(cuts[:-1], cuts[1:]):
        if act.size == 0:
            break
        cn = grid[start:stop]
        kernels = None
        if prefix == "R" and st.frac.size > 1:
            X = st.rho * (cn[:, None] ** 2) / st.s
            kernels = [X[:0, 0]] + [psv_kernels(st.lam[i], st.mu[i], X[:, i]) for i in range(1, st.frac.size)]
        kh = rows_of.grid(rows[act], cn)
        Fn = secular_sh(st, cn, kh) if prefix == "L" else secular_psv(st, cn, kh, kernels)
        c, F = np.concatenate([c_old, cn]), np.concatenate([F_old, Fn], axis=1)
        n0 = c_old.size
        pos = F > 0
        sc_all = pos[:, 1:] != pos[:, :-1]
        sc = sc_all.copy()
        sc[:, :max(n0 - 1, 0)] = False                                    # counted with the last chunk
        r1, j1 = np.nonzero(sc)
        rr.append(rows[act[r1]])
        lo.append(c[j1])
        hi.append(c[j1 + 1])
        flo.append(F[r1, j1])
        fhi.append(F[r1, j1 + 1])
        j3 = np.where(j1 > 0, j1 - 1, np.minimum(j1 + 2, c.size - 1))
        c3.append(np.where(j3 == j1 + 1, np.nan, c[j3]))
        f3.append(F[r1, j3])
        if c.size >= 3:
            # a local minimum of |F| between cells without a sign change: two roots may hide there
            aF = np.abs(F)
            cand = (aF[:, 1:-1] < aF[:, :-2]) & (aF[:, 1:-1] <= aF[:, 2:]) & ~sc_all[:, :-1] & ~sc_all[:, 1:]
            cand[:, :max(n0 - 2, 0)] = False
            r2, j2 = np.nonzero(cand)
            cols = j2[:, None] + np.arange(3)
            cands.append((rows[act[r2]], c[cols], F[r2[:, None], cols]))
        found[act] += sc.sum(axis=1)
        live = found[act] < need
        act, c_old, F_old = act[live], c[-2:], F[live][:, -2:]
    if cands:
        r2, c3_, F3 = (np.concatenate([x[k] for x in cands]) for k in range(3))
        if r2.size:
            ok, x, fx = _hidden_pairs(st, prefix, rows_of, r2, c3_, F3)
            rr += [r2[ok], r2[ok]]
            lo += [c3_[ok, 0], x[ok]]
            hi += [x[ok], c3_[ok, 2]]
            flo += [F3[ok, 0], fx[ok]]
            fhi += [fx[ok], F3[ok, 2]]
            c3 += [c3_[ok, 2], c3_[ok, 0]]
            f3 += [F3[ok, 2], F3[ok, 0]]
    if not rr:
        return np.zeros(0, dtype=int), *(np.zeros(0) for _ in range(6))
    R, LO, HI, FLO, FHI, C3, F3_ = (np.concatenate(v) for v in (rr, lo, hi, flo, fhi, c3, f3))
    srt = np.lexsort((LO, R))
    keep = np.arange(R.size) - np.searchsorted(R[srt], R[srt]) < need        # rank within the row
    return tuple(v[srt][keep] for v in (R, LO, HI, FLO, FHI, C3, F3_))


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
        return _newton(st, prefix, lo, hi, rows_of, r, flo, fhi, c3, f3)


def _newton(st: IsoStack, prefix: str, lo: np.ndarray, hi: np.ndarray, rows_of: Rows, r: np.ndarray,
            flo: np.ndarray, fhi: np.ndarray, c3: np.ndarray, f3: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The loop of :func:`_refine` (floating-point warnings off).

    Only the brackets not yet converged are evaluated (the state of the loop is carried for those
    only); a converged point's answer is written out when it converges.
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
        if k_psv is None:
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
    grid = speed_grid(st, rows_of) if grid is None else grid
    bR, bL = (_brackets(st, p, rows_of, modes, grid) for p in ("R", "L"))
    r, lo, hi, flo, fhi, c3, f3 = (np.concatenate([u, v + n if k == 0 else v]) for k, (u, v) in enumerate(zip(bR, bL)))
    roots, vg = _refine(st, "RL", lo, hi, rows_of.both(), r, flo, fhi, c3, f3)
    sh = r >= n
    return [_table(n, r[~sh], roots[~sh], vg[~sh]), _table(n, r[sh] - n, roots[sh], vg[sh])]


def _table(n_rows: int, r: np.ndarray, roots: np.ndarray, vg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Speeds and group velocities of roots (m,) of rows r as (n_rows, width) tables, ascending, NaN-padded."""
    width = int(np.bincount(r, minlength=n_rows).max(initial=0))
    c_out, v_out = np.full((n_rows, width), np.nan), np.full((n_rows, width), np.nan)
    if r.size == 0:
        return c_out, v_out
    srt = np.lexsort((roots, r))
    r, roots, vg = r[srt], roots[srt], vg[srt]
    start = np.concatenate([[0], np.cumsum(np.bincount(r, minlength=n_rows))[:-1]])
    col = np.arange(r.size) - start[r]
    c_out[r, col], v_out[r, col] = roots, vg
    return c_out, v_out


def _family_grid(st: IsoStack, prefix: str, grid: np.ndarray) -> np.ndarray:
    """The grid a family scans: SH modes are faster than the slowest shear speed v of any layer
    (omega^2 int rho v^2 = int mu (v'^2 + k^2 v^2) >= k^2 min(mu / rho) int rho v^2), so SH starts just
    below v; P-SV scans all of it."""
    if prefix != "L":
        return grid
    v = float(st.shear.min())
    return np.concatenate([[v * (1.0 - 1e-9)], grid[grid > v]])


def _brackets(st: IsoStack, prefix: str, rows_of: Rows, modes: int | None, grid: np.ndarray | None
              ) -> tuple[np.ndarray, ...]:
    """The scan of :func:`family_roots` with its rescan of rows with too few modes: :func:`_scan`'s brackets."""
    n_rows = rows_of.base.size
    need = np.inf if modes is None else modes
    rows = np.arange(n_rows)
    grid = speed_grid(st, rows_of) if grid is None else grid
    r, lo, hi, flo, fhi, c3, f3 = _scan(st, prefix, _family_grid(st, prefix, grid), rows_of, rows, need)
    counts = np.bincount(r, minlength=n_rows)
    order = np.argsort(rows_of.base, kind="stable")
    cs = counts[order]
    dip = order[cs < np.minimum(np.maximum.accumulate(cs), np.maximum.accumulate(cs[::-1])[::-1])]
    if dip.size:
        more = _scan(st, prefix, _family_grid(st, prefix, speed_grid(st, rows_of, RESCAN)), rows_of, dip, need)
        better = np.bincount(more[0], minlength=n_rows) > counts
        keep, keep2 = ~better[r], better[more[0]]
        r, lo, hi, flo, fhi, c3, f3 = (np.concatenate([u[keep], v[keep2]])
                                       for u, v in zip((r, lo, hi, flo, fhi, c3, f3), more))
    return r, lo, hi, flo, fhi, c3, f3


#: Public names of the pieces :mod:`surfwave.layers.isotropic_guard` reuses: the secular function at
#: (row, speed) pairs, the Newton refinement of brackets, and the (rows, width) table of roots.
secular_at = _at
refine_brackets = _refine
roots_table = _table
