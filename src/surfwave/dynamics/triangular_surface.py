"""Numerical surface lattice dynamics of the triangular lattice (independent of Eqs. 6a-16).

The semi-infinite crystal is solved with the row equations of :mod:`surfwave.dynamics.triangular`
(bulk rows: omega^2 U_I = A0 U_I + A1 U_{I+1} + A1^H U_{I-1}; surface row with A0_surface)
by renormalisation-group decimation (Lopez Sancho et al., J. Phys. F 15, 851 (1985)): each
step eliminates every second row, so after K steps the surface row is coupled exactly to a
crystal 2^K rows deep and the neglected coupling decays like exp(-2^K Re q). The effective
surface matrix E_s(omega^2) then gives the surface-mode condition

    f(omega^2) = det(omega^2 - E_s(omega^2)) = 0,   0 < omega^2 < omega_bulk_min^2,

searched below the bottom of the bulk continuum at the same theta (bound, i.e. localised,
states only: every root there is a surface mode; plate modes and slab buckling cannot occur).
No formula of :mod:`surfwave.dynamics.dispersion` is used. In the basis (U, V) with u = U, v = iV the
row matrices are real, so f is real and the roots are bracketed by sign changes.

Units: m = K = d0 = 1; omega in (K/m)^(1/2), omega^2 in K/m.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from surfwave.dynamics.surface_green import det2, inv2, null_vector2
from surfwave.dynamics.triangular import long_wave, row_matrices
from surfwave.errors import InputError
from surfwave.model_crystals.potentials import PairPotential, get_potential
from surfwave.validate import as_1d

REASON_ROUNDING = ("theta too close to 0 or pi: the bulk band bottom omega^2 (~theta^2) is within "
                   "rounding of 0, stability undecidable in double precision")
REASON_UNRESOLVED = ("theta too close to 0 or pi: the error estimate of omega_lattice exceeds omega "
                     "(rounding of the row matrices swamps omega^2 ~ theta^2)")

_D = np.diag([1.0, -1j])  # U' = D U: (u, v) -> (U, V) with v = i V


def _real_basis(M: np.ndarray) -> np.ndarray:
    """D M D^-1: the row matrices in the (U, V) basis, where they are real."""
    return (_D @ M @ np.conj(_D)).real


def bulk_band_bottom(A0: np.ndarray, A1: np.ndarray, n_grid: int = 129, n_golden: int = 60) -> np.ndarray:
    """Lowest bulk omega^2 at fixed theta: min over kappa of eig(A0 + A1 e^ik + A1^H e^-ik).

    Parameters
    ----------
    A0, A1 : ndarray, shape (..., 2, 2), complex, K/m

    Returns
    -------
    ndarray, shape (...), K/m (negative where the bulk is unstable along this line).
    """
    def lowest(kap):
        M = A0[..., None, :, :] + A1[..., None, :, :] * np.exp(1j * kap)[..., None, None] \
            + np.conj(np.swapaxes(A1, -1, -2))[..., None, :, :] * np.exp(-1j * kap)[..., None, None]
        h11, h22, h12 = M[..., 0, 0].real, M[..., 1, 1].real, M[..., 0, 1]
        return 0.5 * (h11 + h22) - np.sqrt(0.25 * (h11 - h22) ** 2 + np.abs(h12) ** 2)

    grid = np.linspace(0.0, np.pi, n_grid)
    vals = lowest(np.broadcast_to(grid, A0.shape[:-2] + (n_grid,)))
    i = np.argmin(vals, axis=-1)
    step = grid[1]
    lo, hi = np.maximum(grid[i] - step, 0.0), np.minimum(grid[i] + step, np.pi)
    g = 0.5 * (np.sqrt(5.0) - 1.0)
    for _ in range(n_golden):  # golden section on the bracketing cell
        x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
        f1, f2 = lowest(x1[..., None])[..., 0], lowest(x2[..., None])[..., 0]
        hi, lo = np.where(f1 < f2, x2, hi), np.where(f1 < f2, lo, x1)
    best = lowest(0.5 * (lo + hi)[..., None])[..., 0]
    return np.minimum(best, vals.min(axis=-1))


def surface_matrix(E: np.ndarray, A0r: np.ndarray, A0sr: np.ndarray, A1r: np.ndarray, tol: float = 1e-10,
                   n_steps: int | None = None, max_steps: int = 64,
                   active: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray, int, np.ndarray]:
    """Effective surface matrix E_s(E) of the semi-infinite crystal by decimation.

    Parameters
    ----------
    E : ndarray, shape (...), omega^2 (K/m), below the bulk continuum.
    A0r, A0sr, A1r : ndarray, shape (..., 2, 2), real (U, V) basis.
    tol : float
        Stop when |alpha_K| <= tol |A1| everywhere (the neglected coupling to row 2^K).
    n_steps : int, optional
        Fixed number of decimation steps instead (benchmark knob).
    active : ndarray of bool, shape (...), optional
        Points that must converge (others, e.g. invalid stand-ins, are ignored).

    Returns
    -------
    Es, Es_prev, Es_prev2 : ndarray, shape (..., 2, 2)
        After the last step, one and two steps before it (for the error estimate).
    steps : int
    contraction : ndarray, shape (...)
        |alpha_K| / |alpha_{K-1}| ~ exp(-2^(K-1) Re q): the ratio by which the next step's
        correction shrinks (>= 0.5 means the decimation has not started to converge).
    """
    eye = np.eye(2)
    Ee = E[..., None, None] * eye
    alpha, beta = A1r.copy(), np.swapaxes(A1r, -1, -2).copy()
    eps, eps_s = A0r.copy(), A0sr.copy()
    scale = np.abs(A1r).max(axis=(-1, -2)) + 1e-300
    prev = prev2 = eps_s
    a_now = a_prev = np.abs(alpha).max(axis=(-1, -2))
    steps = 0
    limit = max_steps if n_steps is None else n_steps
    while steps < limit:
        small = np.abs(alpha).max(axis=(-1, -2)) <= tol * scale
        if n_steps is None and np.all(small | (False if active is None else ~active)):
            break
        g = inv2(Ee - eps)
        ag, bg = alpha @ g, beta @ g
        prev2, prev = prev, eps_s
        eps_s = eps_s + ag @ beta
        eps = eps + ag @ beta + bg @ alpha
        alpha, beta = ag @ alpha, bg @ beta
        a_prev, a_now = a_now, np.abs(alpha).max(axis=(-1, -2))
        steps += 1
    with np.errstate(all="ignore"):
        contraction = np.where(a_now == 0, 0.0, a_now / a_prev)
    return eps_s, prev, prev2, steps, contraction


def surface_mode(potential: str | PairPotential, d_over_d0: ArrayLike, theta: ArrayLike, tol: float = 1e-10,
                 n_steps: int | None = None, n_scan: int = 24, rtol_root: float = 1e-15) -> dict:
    """Surface-wave frequency of the triangular lattice by a numerical semi-infinite solve.

    Parameters
    ----------
    potential : str or PairPotential
        Any registered pair potential.
    d_over_d0 : array_like, shape (n,)
        2 d_x / d0 in (0, 2).
    theta : array_like, shape (m,)
        k d_x, radians; NaN with a reason outside (0, pi).
    tol : float
        Decimation tolerance on the neglected coupling (relative to |A1|).
    n_steps : int, optional
        Fixed number of decimation steps (depth 2^n_steps rows) instead of ``tol``.
    n_scan : int
        Points of the sign scan of f below the bulk continuum (counts the bound modes).
    rtol_root : float
        Relative width at which the bisection/regula-falsi bracket on omega^2 stops.

    Returns
    -------
    dict
        ``omega_lattice``, ``omega_lattice_error``, ``omega_bulk_min``, ``omega_sine_law``,
        ``sine_law_deviation``, ``polarisation`` (n, m) float; ``depth``,
        ``n_surface_modes`` (n, m) int (-1 where no scan ran); ``depth`` NaN where
        ``omega_lattice`` is; ``c2_R_long_wave`` (n,) (NaN where Eq. 20 has no root in
        (0, c2_T_par)); ``reason_lattice`` (n, m)
        str (named so that it does not clash with the ``reason`` of dispersion.solve).
        If several bound modes exist, the one selected is the one continuous with the long-wave
        Rayleigh wave: the root closest to omega_sine_law (reported in ``n_surface_modes``).

    Notes
    -----
    omega^2 ~ theta^2 is computed from O(1) row matrices, so its absolute rounding error is
    ~eps |A0|: the relative error grows like eps / (theta^2 c_R^2) (measured: <= 4e-9 at
    theta = 1e-3 a percent inside the instabilities; honest ``omega_lattice_error`` always).
    Where the error estimate exceeds omega (theta ~< 1e-6 from 0 or pi), or the band bottom
    is within rounding of 0, the result is NaN with a "theta too close to 0 or pi" reason.
    """
    pot = get_potential(potential)
    th_in = as_1d(theta, "theta")
    bad_th = ~((th_in > 0) & (th_in < np.pi))
    th = np.where(bad_th, 0.5 * np.pi, th_in)
    A0, A0s, A1 = row_matrices(pot, d_over_d0, th)
    n, m = A0.shape[:2]
    A0r, A0sr, A1r = _real_basis(A0), _real_basis(A0s), _real_basis(A1)
    e_min = bulk_band_bottom(A0, A1)
    # Rounding: the row matrices carry absolute errors ~eps |A0| that the acoustic cancellation
    # (omega^2 ~ theta^2) does not reduce, so omega^2 is known to ~eps |A0| at best.
    rounding = 8 * np.finfo(float).eps * np.abs(A0r).max(axis=(-1, -2))
    reason = np.full((n, m), "", dtype=object)
    reason[e_min <= 0] = "bulk unstable: bulk continuum reaches omega^2 <= 0 at this theta"
    reason[np.abs(e_min) <= rounding] = REASON_ROUNDING
    reason[:, bad_th] = "theta outside (0, pi)"
    ok = reason == ""
    top = np.where(ok, e_min, 1.0)

    def f(r, steps=None):
        """(det(E - E_s(E)), decimation steps used, contraction) at E = r * top."""
        Es, _, _, k, con = surface_matrix(r * top, A0r, A0sr, A1r, tol=tol,
                                          n_steps=steps if steps else n_steps, active=ok)
        E = (r * top)[..., None, None] * np.eye(2)
        return det2(E - Es), k, con

    # Scan for sign changes (bound modes) on r = omega^2 / omega_bulk_min^2 in (0, 1).
    r_grid = 1.0 - np.geomspace(1.0, 1e-7, n_scan)  # dense towards the band bottom
    r_grid[0] = 1e-9
    with np.errstate(all="ignore"):
        fs = np.stack([f(np.full((n, m), r))[0] for r in r_grid], axis=-1)
    change = np.signbit(fs[..., :-1]) != np.signbit(fs[..., 1:])
    n_modes = np.where(ok, change.sum(axis=-1), -1)  # -1: no scan ran (see reason)
    reason[ok & (n_modes == 0)] = "no bound surface mode below the bulk continuum"
    ok &= n_modes > 0
    # Pick the bracket closest to the long-wave sine law (continuity with the Rayleigh wave).
    lw = long_wave(pot, d_over_d0)
    c2 = lw["c2_R_cauchy"]
    # Eq. (20)'s root is a Rayleigh speed only in (0, c2_T_par); outside (d/d0 0.5 and 0.7 of
    # the harmonic lattice: negative) the long-wave crystal has no Rayleigh wave: NaN.
    c2_rayleigh = np.where((c2 > 0) & (c2 < lw["c2_T_par"]), c2, np.nan)
    dx = 0.5 * as_1d(d_over_d0)
    with np.errstate(all="ignore"):
        w_sine = np.sqrt(c2)[:, None] / dx[:, None] * np.sin(th)[None, :]
        r_sine = w_sine**2 / top
    mid = 0.5 * (r_grid[:-1] + r_grid[1:])
    dist = np.where(change, np.abs(mid - np.nan_to_num(r_sine, nan=0.5)[..., None]), np.inf)
    j = np.argmin(dist, axis=-1)
    lo, hi = r_grid[j], r_grid[j + 1]
    flo = np.take_along_axis(fs, j[..., None], -1)[..., 0]
    fhi = np.take_along_axis(fs, j[..., None] + 1, -1)[..., 0]
    side = np.zeros((n, m), dtype=int)
    for _ in range(200):  # Illinois regula falsi, vectorised; bisection when it stalls
        if np.all(~ok | (hi - lo <= rtol_root * hi)):
            break
        with np.errstate(all="ignore"):
            x = (lo * fhi - hi * flo) / (fhi - flo)
        x = np.where(np.isfinite(x) & (x > lo) & (x < hi), x, 0.5 * (lo + hi))
        x = np.where(np.abs(side) >= 3, 0.5 * (lo + hi), x)
        with np.errstate(all="ignore"):
            fx = f(x)[0]
        left = np.signbit(fx) == np.signbit(flo)
        lo, flo = np.where(left, x, lo), np.where(left, fx, flo)
        hi, fhi = np.where(left, hi, x), np.where(left, fhi, fx)
        fhi = np.where(left & (side > 0), 0.5 * fhi, fhi)
        flo = np.where(~left & (side < 0), 0.5 * flo, flo)
        side = np.where(left, np.maximum(side, 0) + 1, np.minimum(side, 0) - 1)
    root = 0.5 * (lo + hi)
    with np.errstate(all="ignore"):
        f_now, steps, _ = f(root)
        f_next, _, con = f(root, steps=steps + 1)  # one step more than the model used
        h = 1e-6 * root  # Illinois halves flo/fhi, so take the slope afresh
        slope = (f(root + h)[0] - f(root - h)[0]) / (2 * h)
        d_next = np.abs(f_next - f_now) / np.abs(slope)  # root change that step would cause
        E = root * top
        Es = surface_matrix(E, A0r, A0sr, A1r, tol=tol, n_steps=n_steps, active=ok)[0]
        S = E[..., None, None] * np.eye(2) - Es
        u = null_vector2(S)
        pol = u[..., 1] ** 2 / (u**2).sum(-1)
    omega = np.sqrt(E)
    # Truncation: d_next = root change one more decimation step (a crystal twice as deep) would
    # cause; later steps shrink by ~con = |alpha_K+1|/|alpha_K| each (doubly exponential), so the
    # remaining error is <= d_next/(1 - con) (safety factor 10). If con >= 0.5 the decimation has
    # not started to converge and the error is only bounded by the gap below the continuum.
    with np.errstate(all="ignore"):
        trunc = np.where(con < 0.5, 10 * d_next / (1 - con), 1.0)
    trunc = np.where(ok, np.nan_to_num(trunc, nan=1.0), 0.0) * top
    err_e2 = trunc + (hi - lo) * top + rounding
    err = err_e2 / (2 * omega)
    unresolved = ok & ~(err < omega)  # rounding swamps omega^2 ~ theta^2 c_R^2 (theta -> 0, pi)
    reason[unresolved] = REASON_UNRESOLVED
    ok &= ~unresolved
    nan = np.nan
    out = {
        "omega_lattice": np.where(ok, omega, nan),
        "omega_lattice_error": np.where(ok, err, nan),
        "omega_bulk_min": np.where(e_min > 0, np.sqrt(np.abs(e_min)), nan),
        "omega_sine_law": np.where(ok, w_sine, nan),
        "sine_law_deviation": np.where(ok, omega / w_sine - 1, nan),
        "c2_R_long_wave": c2_rayleigh,
        "depth": np.where(ok, 2.0**steps, nan),
        "n_surface_modes": n_modes,
        "polarisation": np.where(ok, pol, nan),
        "reason_lattice": reason,
    }
    return out


#: Strains of a dispersion scene checked by :func:`surface_mode` by default (the knob
#: ``accuracy.dispersion.check_points``): the numerical solve costs about 1 s per strain at
#: 512 theta, the analytic solution microseconds, so a long strain grid is checked on a sample.
DEFAULT_CHECK_POINTS = 5

#: ``reason_lattice`` of the strains outside the checked sample.
REASON_NOT_CHECKED = "not checked (sample): the lattice-dynamics check ran on a sample of the strains"


#: Span of d/d0 over which ``check_points`` strains are checked (that of the default grids,
#: 0.90 .. 1.10): the sample lattice has spacing ``CHECK_SPAN / check_points``.
CHECK_SPAN = 0.2


def check_sample(d_over_d0: ArrayLike, check_points: int = DEFAULT_CHECK_POINTS) -> np.ndarray:
    """Indices of the strains the lattice-dynamics check runs on, shape (k,), sorted.

    The rule looks at the strain values, not at their number or position in the grid, so a
    sample is stable when the grid is extended (a grid that grows keeps every strain it
    checked, and the parameter cache serves them): the points of the global lattice
    ``d/d0 = 1 + j h``, ``h = CHECK_SPAN / check_points`` (``check_points`` strains per 0.2
    of d/d0), that lie within the grid's range, each represented by the grid strain nearest
    to it (ties: the smaller strain; values compared to 1e-12, as the cache keys them).
    Points outside the old range cannot displace an old choice, since a strain added
    beyond the range is farther from every lattice point inside it than the old end was.
    A grid narrower than h, with no lattice point inside, checks the one strain nearest to
    the lattice (the only case an extension may change).

    Parameters
    ----------
    d_over_d0 : array_like, shape (n,)
        The strain grid (any order).
    check_points : int
        At least 1: strains checked per 0.2 of d/d0.

    Examples
    --------
    >>> check_sample([0.90, 0.95, 1.0, 1.05, 1.10]).tolist()   # the paper's triangular scene
    [0, 1, 2, 3, 4]
    >>> check_sample(np.linspace(0.90, 1.10, 41), 2).tolist()    # h = 0.1: 0.9, 1.0, 1.1
    [0, 20, 40]
    """
    if isinstance(check_points, (bool, np.bool_)) or int(check_points) != check_points or check_points < 1:
        raise InputError(f"check_points must be an integer >= 1, got {check_points!r}")
    d = np.round(np.asarray(d_over_d0, dtype=float).ravel(), 12)
    if d.size == 0:
        return np.zeros(0, int)
    if not np.isfinite(d).all():
        raise InputError("check_sample: d_over_d0 must be finite")
    h = CHECK_SPAN / int(check_points)
    j = np.arange(np.ceil(np.round((d.min() - 1.0) / h, 9)), np.floor(np.round((d.max() - 1.0) / h, 9)) + 1)
    lattice = 1.0 + j * h
    if lattice.size == 0:  # narrower than h: the strain nearest to the lattice
        near = 1.0 + np.round((d - 1.0) / h) * h
        lattice = near[[int(np.argmin(np.round(np.abs(d - near), 12)))]]
    order = np.lexsort((np.arange(d.size), d))  # by value, then position (duplicates: the first)
    ds = d[order]
    hi = np.clip(np.searchsorted(ds, lattice), 0, d.size - 1)  # first strain >= L (or the last)
    lo = np.searchsorted(ds, ds[np.maximum(hi - 1, 0)])  # the first of the largest strain < L
    below = np.round(np.abs(lattice - ds[lo]), 12)
    above = np.round(np.abs(ds[hi] - lattice), 12)
    picks = order[np.where(below <= above, lo, hi)]  # ties: the smaller strain
    return np.unique(picks)


def scatter_sample(checked: dict, index: np.ndarray, n: int) -> dict:
    """Results of :func:`surface_mode` on a strain sample spread onto the full grid of n strains.

    Strains outside ``index`` get NaN (float arrays), -1 (``n_surface_modes``: not counted)
    and :data:`REASON_NOT_CHECKED` (``reason_lattice``).

    Parameters
    ----------
    checked : dict
        name -> array with leading axis len(index).
    index : ndarray of int, shape (k,)
    n : int

    Returns
    -------
    dict
        name -> array with leading axis n.
    """
    out = {}
    for name, arr in checked.items():
        arr = np.asarray(arr)
        if arr.dtype == object:
            full = np.full((n,) + arr.shape[1:], REASON_NOT_CHECKED, dtype=object)
        elif np.issubdtype(arr.dtype, np.integer):
            full = np.full((n,) + arr.shape[1:], -1, dtype=arr.dtype)
        else:
            full = np.full((n,) + arr.shape[1:], np.nan, dtype=arr.dtype)
        full[index] = arr
        out[name] = full
    return out
