"""All guided modes of a stack at many kh: bracketing on a speed grid, vectorised refinement, labels.

Per decoupled family (:func:`surfwave.layers.partial.families`) the real secular function
det Z(c, kh) (:func:`surfwave.layers.recursion.secular`) is evaluated on a grid of speeds for
all kh at once: the layers' eigen-solutions depend on c only, so they are computed once per grid
speed and shared by every kh. The grid is uniform in t = sqrt(1 - c^2 / c_lim^2) (dense near the
substrate's limiting speed c_lim, where modes appear at their cut-off with a square-root
behaviour), plus a geometric tail toward t = 0. Every sign change brackets either a mode or a
pole of Z (a mode of the stack with a clamped top); all brackets of all kh are refined together
by a safeguarded secant iteration (:func:`_refine`) to a relative width :data:`C_TOL`, and a
converged bracket is a mode when Z is (numerically) singular there and bounded, a pole otherwise
(the scan and the search next to poles: :mod:`surfwave.layers.scan`).

Trapped modes. A mode trapped in a slow layer buried under a stiff one has a tiny surface
amplitude: its zero of det Z sits next to a pole within a window far narrower than a grid cell,
and no function of Z sampled at the cell's ends shows the pair. Where such a burial exists
(:func:`surfwave.layers.counting.needed`), the modes of each stretch of the grid are checked
against the exact, pole-free Wittrick-Williams count of :mod:`surfwave.layers.counting`, which
finds the missing ones itself.

Labels. Within one family, the modes at fixed kh are ordered by speed and cannot cross as kh
changes (crossings of one family are non-generic, and each family's modes are counted from the
slowest); new modes enter at the top, through c_lim. The n-th slowest mode of a family therefore
keeps its label along kh: sagittal "R" (Rayleigh), "S1", "S2", ... (Sezawa); shear horizontal
"L0", "L1", ... (Love); coupled families "M0", "M1", ....
"""
from __future__ import annotations

import numpy as np

from surfwave.layers.counting import needed, recount
from surfwave.layers.partial import Blocks, Family
from surfwave.layers.recursion import boundary_eigenvalues, boundary_matrix, top_impedance
from surfwave.layers.scan import POLE_SPLIT as POLE_SPLIT  # noqa: F401  (re-exported)
from surfwave.layers.scan import impedance_eigvalsh, near_poles, scan_grid
from surfwave.solvers.boundary import Boundary, as_boundary
from surfwave.solvers.impedance import limiting_x as elastic_limiting_x

__all__ = ["C_TOL", "FAMILY_OF_LETTER", "family_modes", "label_family", "label", "lowest_speed"]

#: Relative width of a converged bracket in c.
C_TOL = 4e-15
#: Iterations of the bracket refinement at most.
MAX_ITER = 200
#: Points of the speed grid per unit of kh (on top of :data:`BASE_GRID`): thick films hold many modes.
GRID_PER_KH = 8
BASE_GRID = 60
#: Smallest t = sqrt(1 - c^2/c_lim^2) of the grid.
T_MIN = 1e-7
#: With ``lowest=True``: the speed grid is scanned from the bottom in these parts (fractions of its
#: points), stopping after the first part in which every kh has the bracket of a mode.
LOWEST_PARTS = (0.4, 0.55, 0.7, 1.0)


def label(prefix: str, j: int) -> str:
    """Label of the j-th slowest mode of a family with this prefix ("R" -> R, S1, S2, ...)."""
    if prefix == "R":
        return "R" if j == 0 else f"S{j}"
    return f"{prefix}{j}"


#: The family of each label's first letter: R (Rayleigh) and S (Sezawa) share the sagittal family "R".
FAMILY_OF_LETTER = {"R": "R", "S": "R", "L": "L", "M": "M"}


def label_family(text: str) -> str:
    """The family prefix ("R", "L", "M") of a mode label, leaky ("...~") or not: the inverse of
    :func:`label`'s prefix; "" for an unknown label."""
    return FAMILY_OF_LETTER.get(str(text)[:1], "")


def lowest_speed(b: Blocks) -> float:
    """The floor of the search: 0.05 x the lowest limiting speed of any layer as a half-space, m/s.

    Guided modes lie above it unless a compressed layer is close to surface buckling (its Rayleigh
    speed falls to zero there); a mode below the floor counts as buckled (:func:`floor_unstable`).
    """
    Q, R, T = b.Q[:, :3, :3], b.R[:, :3, :3], b.T[:, :3, :3]
    XL = elastic_limiting_x(Q, R, T)[0]
    return float(0.05 * np.sqrt(np.min(XL * b.sA / b.rho)))


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


def film_x1_speeds(b: Blocks) -> np.ndarray:
    """Bulk speeds along x1 of every film (sqrt of the eigenvalues of Q / rho), m/s, shape (3 L,)."""
    L = len(b.frac)
    if L == 0:
        return np.zeros(0)
    w = np.linalg.eigvalsh(b.Q[:L, :3, :3])
    return np.sqrt(np.clip(w, 0, None) * b.sA / b.rho[:L, None]).ravel()


def speed_grid(c_lim: float, c_lo: float, n: int, bulk=(), kh_max: float = 0.0) -> np.ndarray:
    """Ascending speeds in (c_lo, c_lim).

    Uniform in t = sqrt(1 - c^2/c_lim^2) (dense near c_lim), uniform in c (n / 2 points: slow
    films), a geometric tail toward c_lim, the floor c_lo (1 + 1e-9) itself (the scan counts the
    negative eigenvalues there: the floor's count), and above each film bulk speed v in ``bulk`` the
    points v sqrt(1 + q^2), q in (0, q_max = sqrt(c_lim^2 / v^2 - 1)), with q spaced by
    pi / (16 kh_max) (16 points per mode: the sheet's modes lie ~pi / kh apart in q, with poles
    between them), at every kh_max > 0: the sheet holds ~kh_max q_max / pi modes, so the phase, not
    kh alone, sets how many (a film much slower than its substrate holds many already at small kh,
    far below the uniform parts' resolution); at most 4000 points per sheet.
    """
    t_hi = np.sqrt(1.0 - (c_lo / c_lim) ** 2)
    t = np.concatenate([np.geomspace(T_MIN, 0.02, 24, endpoint=False), np.linspace(0.02, t_hi, n)])
    parts = [c_lim * np.sqrt(1.0 - t * t), np.linspace(c_lo, c_lim, n // 2 + 2)[1:-1], np.array([c_lo * (1 + 1e-9)])]
    for v in bulk if kh_max > 0.0 else ():
        if c_lo < v < c_lim:
            q_max = np.sqrt((c_lim / v) ** 2 - 1.0)
            q = np.arange(1e-4, q_max, np.pi / (16.0 * kh_max))[:4000]
            parts.append(v * np.sqrt(1.0 + q * q))
    g = np.unique(np.concatenate(parts))
    return g[(g > c_lo) & (g < c_lim)]


def _refine(b: Blocks, fam: Family, lo, hi, flo, fhi, kh, electrical: str | Boundary,
            c_lim: float, lam_lo: np.ndarray | None = None,
            lam_hi: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Safeguarded secant iteration on all brackets at once; converged speeds (m,) and Z's eigenvalues there.

    Each step takes the secant through the two latest points (order 1.6); a step that leaves
    the current bracket (sign change of det Z), or a stalled iteration (four steps that neither
    halve the bracket nor make a small secant step), falls back to bisection. The iteration runs
    in t = sqrt(1 - c^2 / c_lim^2), in which det Z is smooth up to the limit (in c it has a
    square-root branch point there); the first step, where ``lam_lo`` and ``lam_hi`` (the eigenvalue
    of Z that crosses zero, at lo and hi) are given and finite, interpolates that eigenvalue instead.
    Stopping: a secant step from the latest evaluated point below the tolerance (or, once the
    steps shrink superlinearly, a predicted next step below tol / 1000) ends the iteration at the
    step's end without evaluating det Z there, provided Z at the latest point is already that of
    a mode (:func:`_mode_margin`); a sub-tolerance step that leaves the bracket (rounding) ends it
    at the latest point. Each evaluation costs the layers' Stroh eigen-solutions at a new speed,
    the bulk of the search's time.

    Returns
    -------
    c : ndarray, shape (m,)
        Converged speeds, m/s.
    w : ndarray, shape (m, na)
        Ascending eigenvalues of the boundary matrix Z at each speed's latest evaluated point (the
        speed itself, or a secant step from it that was not evaluated).
    """
    def to_t(c):
        return np.sqrt(np.maximum(1.0 - (c / c_lim) ** 2, 0.0))

    def to_c(t):
        return c_lim * np.sqrt(1.0 - t * t)

    def tol_at(x):
        return C_TOL * (1.0 - x * x) / np.maximum(x, 1e-300)              # |dc/c| = t |dt| / (1 - t^2)

    def evaluate(x, rows):
        M = top_impedance(b, fam, to_c(x), kh[rows, None])["M"]
        Z, _ = boundary_matrix(b, fam, M, electrical)
        Z = Z[:, 0]
        with np.errstate(all="ignore"):
            return np.linalg.det(Z).real, Z          # as :func:`secular`

    a, fa, z, fz = to_t(lo), flo.copy(), to_t(hi), fhi.copy()           # bracket ends (a, z)
    x0, f0, x1, f1 = a.copy(), fa.copy(), z.copy(), fz.copy()            # the two latest points
    Z1: np.ndarray | None = None                                         # Z at x1 (once evaluated)
    s1, s0 = np.full(a.size, np.inf), np.full(a.size, np.inf)            # the secant steps to x1 and x0
    width = np.abs(z - a)
    idx = np.arange(a.size)
    out = 0.5 * (lo + hi)
    got: list[tuple[np.ndarray, np.ndarray]] = []                        # (bracket indices, eig Z there)
    for it in range(MAX_ITER):
        if idx.size == 0:
            break
        left, right = np.minimum(a, z), np.maximum(a, z)
        with np.errstate(all="ignore"):
            x = x1 - f1 * (x1 - x0) / (f1 - f0)
            if it == 0 and lam_lo is not None and lam_hi is not None:
                # first step: the zero of the crossing eigenvalue's chord (closer than det Z's,
                # which carries the other eigenvalues' variation too)
                xg = x1 - lam_hi * (x1 - x0) / (lam_hi - lam_lo)
                x = np.where(np.isfinite(xg), xg, x)
        if Z1 is not None:
            # converged at x1 (the latest evaluated point, always a bracket end): the secant step from it
            # is below the tolerance but leaves the bracket (rounding, |det Z| at the level of its
            # noise); without this a bisection would follow, and a tail of steps halving the bracket
            edge = np.flatnonzero(np.isfinite(x) & (np.abs(x - x1) <= tol_at(x1)) & ((x <= left) | (x >= right)))
            out[idx[edge]] = to_c(x1[edge])
            got.append((idx[edge], impedance_eigvalsh(Z1[edge])))
            keep = np.ones(idx.size, dtype=bool)
            keep[edge] = False
            idx, a, fa, z, fz, x0, f0, x1, f1, width, x, left, right, Z1, s1, s0 = (
                v[keep] for v in (idx, a, fa, z, fz, x0, f0, x1, f1, width, x, left, right, Z1, s1, s0))
            if idx.size == 0:
                break
        # bisection where the secant leaves the bracket or, every fourth step, where the last
        # four steps did not shrink it by half and the secant step is not small (stalled iteration)
        slow = (it % 4 == 3) & (right - left > 0.5 * width) & (np.abs(x - x1) > 1e-3 * (right - left))
        bis = ~np.isfinite(x) | (x <= left) | (x >= right) | slow
        x = np.where(bis, 0.5 * (left + right), x)
        if it % 4 == 3:
            width = right - left
        tol = tol_at(x)
        if Z1 is not None:
            # converged: the secant step from the latest evaluated point x1 is below the tolerance
            # (or, once the secant converges superlinearly, steps s < s1 < s0, where the next step
            # predicted from them, C s s1 with C ~ s / (s1 s0), is below tol / 1000). x is then taken
            # without evaluating det Z there when Z at x1 is already that of a mode with a 10x margin
            # (the smallest |eigenvalue| only falls from x1 to the root); a pole, or a doubtful
            # case, is evaluated at x as any other point
            s = np.abs(x - x1)
            with np.errstate(all="ignore"):
                fast = (s < s1) & (s1 < s0) & (1e3 * s * s <= tol * s0) & np.isfinite(s0)
            pre = np.flatnonzero(((s <= tol) | fast) & ~bis)
            w1 = impedance_eigvalsh(Z1[pre])
            clear = _mode_margin(w1) > 0
            pre, w1 = pre[clear], w1[clear]
            out[idx[pre]] = to_c(x[pre])
            got.append((idx[pre], w1))
            keep = np.ones(idx.size, dtype=bool)
            keep[pre] = False
            idx, a, fa, z, fz, x0, f0, x1, f1, width, x, tol, bis, Z1, s1, s0 = (
                v[keep] for v in (idx, a, fa, z, fz, x0, f0, x1, f1, width, x, tol, bis, Z1, s1, s0))
            if idx.size == 0:
                break
        fx, Zx = evaluate(x, idx)
        side_a = np.sign(fx) == np.sign(fa)
        a, fa = np.where(side_a, x, a), np.where(side_a, fx, fa)
        z, fz = np.where(side_a, z, x), np.where(side_a, fz, fx)
        done = (np.abs(x - x1) <= tol) & ~bis | (np.abs(z - a) <= tol) | (fx == 0) | ~np.isfinite(fx)
        s0, s1 = s1, np.where(bis, np.inf, np.abs(x - x1))
        x0, f0, x1, f1, Z1 = x1, f1, x, fx, Zx
        out[idx[done]] = to_c(x[done])
        got.append((idx[done], impedance_eigvalsh(Zx[done])))
        keep = ~done
        idx, a, fa, z, fz, x0, f0, x1, f1, width, Z1, s1, s0 = (
            v[keep] for v in (idx, a, fa, z, fz, x0, f0, x1, f1, width, Z1, s1, s0))
    out[idx] = to_c(x1)
    if Z1 is not None:
        got.append((idx, impedance_eigvalsh(Z1)))
    if not got:
        return out, np.zeros((out.size, 0))
    w = np.concatenate([g[1] for g in got])
    w_out = np.empty((out.size, w.shape[-1]))
    w_out[np.concatenate([g[0] for g in got])] = w
    return out, w_out


def _mode_eigenvalues_ok(w: np.ndarray) -> np.ndarray:
    """True where eigenvalues w (..., na) of Z say singular and bounded (a mode), False at a pole."""
    return _mode_margin(w, 1.0) > 0


def _mode_margin(w: np.ndarray, margin: float = 10.0) -> np.ndarray:
    """+1 where eigenvalues w (..., na) of Z are those of a mode, -1 of a pole, with this margin; else 0.

    A mode: Z singular (smallest |w| <= 1e-7 x the largest, or 1e-10) and bounded (largest |w| < 1e6).
    With ``margin`` m > 1 the decision must hold with every threshold moved by the factor m against
    it (the refinement's shortcut, :func:`_refine`); ``margin`` 1 is the plain test.
    """
    w = np.abs(w)
    fin = np.isfinite(w).all(axis=-1)
    with np.errstate(invalid="ignore"):
        lo, hi = w.min(axis=-1, initial=np.inf), w.max(axis=-1, initial=0.0)
        small = 1e-7 * np.maximum(hi, 1e-3)
        mode = fin & (lo * margin <= small) & (hi * margin < 1e6)
        pole = ~fin | (lo > small * margin) | (hi >= 1e6 * margin)
    return np.where(mode, 1, np.where(pole, -1, 0))


def floor_unstable(b: Blocks, fam: Family, kh, electrical: str | Boundary = "free") -> np.ndarray:
    """True per kh (k,) where the boundary matrix has a negative eigenvalue at the floor speed of the search.

    The impedance of a stable stack is positive definite at low speed (but for the potential's
    negative block on a free piezoelectric top, :func:`_electric`); another negative eigenvalue there
    means a mode with omega^2 < 0 (e.g. the surface buckling of a strongly compressed film, which
    sets in before its bulk instability) or, in principle, a mode slower than the floor
    (:func:`lowest_speed`). :func:`family_modes` reports no mode in such rows.
    """
    kh = np.atleast_1d(np.asarray(kh, dtype=float))
    c_lim = float(np.sqrt(fam.X_limit * b.sA / b.rho[-1]))
    c0 = min(lowest_speed(b), 0.5 * c_lim)
    w = boundary_eigenvalues(b, fam, np.array([c0]), kh[None, :], electrical)[0]
    return (w < 0).sum(axis=-1) > _electric(fam, electrical)


def _electric(fam: Family, electrical: str | Boundary) -> int:
    """Negative eigenvalues of a stable stack's boundary matrix at low speed: the potential's (its block
    of the generalised impedance is negative definite, E_3j3l = -eps), when it is kept (free top)."""
    return int(fam.phi is not None and as_boundary(electrical).keeps_potential)


def family_modes(b: Blocks, fam: Family, kh, *, electrical: str | Boundary = "free",
                 n_grid: int | None = None, lowest: bool = False, grid_kh: float | None = None) -> np.ndarray:
    """Speeds of every guided mode of one family below its limiting speed, for each kh.

    Parameters
    ----------
    b : Blocks
    fam : Family
    kh : array_like, shape (k,)
        Wavenumber times total film thickness (>= 0).
    electrical : str or Boundary
        The top's electrical condition (:func:`surfwave.solvers.boundary.as_boundary`).
    n_grid : int, optional
        Speed grid points (default :data:`BASE_GRID` + :data:`GRID_PER_KH` max kh).
    lowest : bool
        Only the family's slowest mode (column 0): the grid is scanned from the bottom and the
        scan stops once every kh has the bracket of a mode (:data:`LOWEST_PARTS`). The grid
        cells scanned are those of the full scan, so the slowest mode comes out the same: below
        the slowest mode Z has no pole (each eigenvalue, positive at the floor and decreasing
        between poles, must cross zero, a mode, before it can reach a pole), so no mode hides
        next to a pole there. (Where the full scan finds a kh short of a higher mode and rescans
        it on a finer grid, its slowest mode there comes from another bracket: the same root to
        round-off.)
    grid_kh : float, optional
        Scan the speed grid of a call whose largest kh is ``grid_kh`` (default: the largest kh
        given), e.g. to solve a few kh on the grid of an earlier call over a wider range.

    Returns
    -------
    ndarray, shape (k, n_modes)
        Ascending speeds (m/s) per kh, NaN-padded; column j is the family's j-th slowest mode
        (``lowest``: shape (k, 1) or (k, 0)).
    """
    kh = np.atleast_1d(np.asarray(kh, dtype=float))
    if not np.all(np.isfinite(kh)):
        raise ValueError("family_modes needs finite kh")
    top = float(np.max(kh, initial=0.0)) if grid_kh is None else float(grid_kh)
    out = _family_scan(b, fam, kh, electrical, n_grid, lowest, top)
    if lowest:
        out = out[:, :1]
    # a mode and a pole of Z in one grid cell cancel in the count: where a kh holds fewer modes
    # than kh on both sides of it (modes are continuous in kh and enter only at the top), rescan it
    # on a grid four times finer
    n = np.isfinite(out).sum(axis=1)
    order = np.argsort(kh, kind="stable")
    ns = n[order]
    left = np.maximum.accumulate(ns)
    right = np.maximum.accumulate(ns[::-1])[::-1]
    dip = order[(ns < np.minimum(left, right))]
    if dip.size:
        n0 = n_grid or int(BASE_GRID + GRID_PER_KH * min(top, 100.0))
        fine = _family_scan(b, fam, kh[dip], electrical, 4 * n0, grid_kh=None if grid_kh is None else top)
        if lowest:
            fine = fine[:, :1]
        if fine.shape[1] > out.shape[1]:
            out = np.pad(out, ((0, 0), (0, fine.shape[1] - out.shape[1])), constant_values=np.nan)
        better = np.isfinite(fine).sum(axis=1) > n[dip]
        out[dip[better]] = np.nan
        out[dip[better], :fine.shape[1]] = fine[better]
    return out


def _family_scan(b: Blocks, fam: Family, kh: np.ndarray, electrical: str | Boundary, n_grid: int | None,
                 lowest: bool = False, grid_kh: float | None = None) -> np.ndarray:
    """:func:`family_modes` by one scan of the speed grid (n_grid points, default from kh, or from
    ``grid_kh`` if given); with ``lowest`` the scan may stop early (:func:`_scan_from_bottom`) and
    higher columns may be missing."""
    c_lim = float(np.sqrt(fam.X_limit * b.sA / b.rho[-1]))
    kh_max = float(np.max(kh, initial=0.0)) if grid_kh is None else float(grid_kh)
    n = n_grid or int(BASE_GRID + GRID_PER_KH * min(kh_max, 100.0))
    bulk = film_bulk_speeds(b)
    grid = speed_grid(c_lim, min(lowest_speed(b), 0.5 * c_lim), n, bulk, kh_max)
    # at a film's bulk speed along x1 its Stroh roots p = 0 coalesce (a Jordan block): det Z is
    # analytic there but its evaluation is not, and may jump. Fence each such speed with grid
    # points 1e-9 apart and ignore that one cell.
    v_x1 = film_x1_speeds(b)
    v_x1 = v_x1[(v_x1 > grid[0]) & (v_x1 < grid[-1])]
    near = (np.abs(grid[:, None] / v_x1[None, :] - 1.0) <= 2e-9).any(axis=1)
    grid = np.unique(np.concatenate([grid[~near], v_x1 * (1 - 1e-9), v_x1 * (1 + 1e-9)]))
    if lowest:
        grid, D, neg, W = _scan_from_bottom(b, fam, grid, kh, electrical, v_x1)
    else:
        grid, D, neg, W = scan_grid(b, fam, grid, kh, electrical)
    # a negative eigenvalue already at the floor speed: a mode with c^2 < 0 (surface buckling of a
    # compressed stack) or below the floor; no mode of that row is reported (see floor_unstable)
    D[:, neg[0] > _electric(fam, electrical)] = np.nan
    # a mode: the count of negative eigenvalues rises by one (a pole: it falls); two modes in one
    # cell (near-degenerate) are split by bisecting the cell until each holds one
    step = neg[1:] - neg[:-1]
    fenced = ((grid[:-1, None] < v_x1[None, :]) & (grid[1:, None] > v_x1[None, :])).any(axis=1)
    with np.errstate(invalid="ignore"):
        ic, ik = np.nonzero((step == 1) & (D[:-1] * D[1:] < 0) & ~fenced[:, None])
    plo, phi_, pfl, pfh, pik = near_poles(b, fam, grid, D, neg, W, kh, electrical, fenced)
    unstable_rows = neg[0] > _electric(fam, electrical)
    keep_p = ~unstable_rows[pik]
    lo = np.concatenate([grid[ic], plo[keep_p]])
    hi = np.concatenate([grid[ic + 1], phi_[keep_p]])
    flo = np.concatenate([D[ic, ik], pfl[keep_p]])
    fhi = np.concatenate([D[ic + 1, ik], pfh[keep_p]])
    ik = np.concatenate([ik, pik[keep_p]])
    roots = np.zeros(0)
    if ik.size:
        # the eigenvalue that crosses zero in a grid bracket: the (neg)-th smallest at its low end
        nb = ic.size
        j = np.clip(neg[ic, ik[:nb]], 0, W.shape[-1] - 1)
        lam_lo, lam_hi = np.full(ik.size, np.nan), np.full(ik.size, np.nan)
        lam_lo[:nb], lam_hi[:nb] = W[ic, ik[:nb], j], W[ic + 1, ik[:nb], j]
        roots, w_root = _refine(b, fam, lo, hi, flo, fhi, kh[ik], electrical, c_lim, lam_lo, lam_hi)
        ok = _mode_eigenvalues_ok(w_root)
        ik, roots = ik[ok], roots[ok]
    if needed(b, bulk):
        # a mode trapped under a stiff film hides next to a pole of Z: checked by the exact count
        ik, roots = recount(b, fam, grid, kh, ik, roots, electrical, unstable_rows, v_x1)
    if ik.size == 0:
        return np.full((kh.size, 0), np.nan)
    counts = np.bincount(ik, minlength=kh.size)
    out = np.full((kh.size, max(int(counts.max(initial=0)), 0)), np.nan)
    order = np.lexsort((roots, ik))
    ik, roots = ik[order], roots[order]
    start = np.concatenate([[0], np.cumsum(counts)[:-1]])
    col = np.arange(ik.size) - start[ik]
    out[ik, col] = roots
    return out


def _scan_from_bottom(b: Blocks, fam: Family, grid: np.ndarray, kh: np.ndarray, electrical: str | Boundary,
                      v_x1: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`scan_grid` of the grid's parts (:data:`LOWEST_PARTS`) from the bottom, until every kh has a bracket.

    Each part is scanned with the last point of the one below it (its cell, and that cell's
    bisections, belong to the new part); the parts joined are the full scan's arrays up to the
    last part scanned, cell for cell. A kh has a bracket where the count of negative eigenvalues
    rises by one with a sign change of det Z in a cell not fenced off at a film's x1 bulk speed;
    rows unstable at the floor need none (they report no mode).
    """
    ends = sorted({max(2, min(grid.size, int(round(f * grid.size)))) for f in LOWEST_PARTS} | {grid.size})
    parts: list[tuple[np.ndarray, ...]] = []
    start = 0
    for end in ends:
        if end <= start:
            continue
        lo = max(start - 1, 0)
        g, D, neg, W = scan_grid(b, fam, grid[lo:end], kh, electrical)
        if start > 0:  # the shared point is the previous part's last one
            g, D, neg, W = g[1:], D[1:], neg[1:], W[1:]
        parts.append((g, D, neg, W))
        start = end
        if end == grid.size:
            break
        g = np.concatenate([p[0] for p in parts])
        D = np.concatenate([p[1] for p in parts])
        neg = np.concatenate([p[2] for p in parts])
        step = neg[1:] - neg[:-1]
        fenced = np.asarray(((g[:-1, None] < v_x1[None, :]) & (g[1:, None] > v_x1[None, :])).any(axis=1))
        with np.errstate(invalid="ignore"):
            found = ((step == 1) & (D[:-1] * D[1:] < 0) & ~fenced[:, None]).any(axis=0)
        if np.all(found | (neg[0] > _electric(fam, electrical))):
            break
    return tuple(np.concatenate([p[i] for p in parts]) for i in range(4))  # type: ignore[return-value]
