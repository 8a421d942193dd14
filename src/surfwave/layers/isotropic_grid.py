"""The speed grid of the isotropic path's scan (:mod:`surfwave.layers.isotropic_scan`) and its rows.

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
pi in depth, so a cell holds a fraction of a mode spacing.
The scan (:mod:`surfwave.layers.isotropic_scan`) evaluates the secular functions on this grid; a
sign change is a mode, and its hunt for pairs hidden in one cell and its rescans are described there.
"""
from __future__ import annotations

import functools
import math

import numpy as np

from surfwave.layers.isotropic import IsoStack

__all__ = ["FLOOR", "N_BASE", "N_LOW", "N_TOP", "PHASE_STEP", "Rows", "phase_curve", "slowest_speed", "speed_grid"]

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
#: Relative offsets above a film's bulk speed added to the phase curve's points (:func:`phase_curve`),
#: 10 per decade: a chord of sqrt over one of these cells is within 1 % of it.
_ONSET = np.geomspace(1e-12, 1e-2, 101)
_ONSET.setflags(write=False)
#: The points of (i) in t (module docstring).
_TOP_T = np.geomspace(1e-7, 0.02, N_TOP, endpoint=False)
_TOP_T.setflags(write=False)
#: sqrt(1 - t^2) of those points (c / c_lim).
_TOP_ROOT = np.sqrt(1.0 - _TOP_T * _TOP_T)
_TOP_ROOT.setflags(write=False)


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

    def grid_t(self, rows: np.ndarray, c: np.ndarray) -> np.ndarray:
        """kh (n, r) of rows (r,) at speeds c (n,), speed-major (:meth:`grid` transposed)."""
        b = self.base[rows][None, :]
        return b / c[:, None] if self.freq else np.broadcast_to(b, (c.size, rows.size))

    def pairs(self, rows: np.ndarray, c: np.ndarray) -> np.ndarray:
        """kh (m,) of (row, speed) pairs (m,)."""
        return self.base[rows] / c if self.freq else self.base[rows]

    def kh_max(self, c: np.ndarray) -> np.ndarray:
        """An upper bound (n,) of every row's kh at speeds c (n,)."""
        top = float(self.base.max(initial=0.0))
        return top / c if self.freq else np.full(c.shape, top)


@functools.lru_cache(maxsize=256)
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


def speed_grid(st: IsoStack, rows_of: Rows, fine: int = 1,
               curve: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """Ascending speeds (n,) in [c_floor, c_lim) (module docstring), for the rows' largest kh at each speed.

    ``curve``: :func:`phase_curve` of ``st`` when already computed (it does not depend on the rows).
    """
    c_lim = st.c_lim
    c_lo = 0.95 * slowest_speed(st)
    t_hi = math.sqrt(1.0 - (c_lo / c_lim) ** 2)
    t = _linspace(0.02, t_hi, N_BASE * fine)
    base = np.concatenate([c_lim * np.sqrt(1.0 - t * t), _linspace(c_lo, c_lim, N_BASE * fine)])
    c_floor = FLOOR * float(st.shear.min())
    low = _geometric(c_floor, c_lo, N_LOW) if c_floor < c_lo else np.zeros(0)
    parts = [c_lim * _TOP_ROOT, np.array([c_lo]), low]                      # c_lo itself, always
    if st.frac.size:
        aux, nu = phase_curve(st) if curve is None else curve
        phase = rows_of.kh_max(aux) * nu
        levels = np.arange(PHASE_STEP / fine, float(phase[-1]), PHASE_STEP / fine)
        if levels.size:
            pts = np.interp(levels, phase, aux)
            parts.append(pts)
            # a base point within half the base spacing of a phase point adds nothing
            t_base = np.sqrt(np.maximum(1.0 - (base / c_lim) ** 2, 0.0))
            step_c = (c_lim - c_lo) / (N_BASE * fine)                       # of the c-uniform part
            dc = np.minimum(step_c, c_lim * c_lim * t_base * t_hi / (base * N_BASE * fine))   # and the t-uniform
            k = (np.minimum(np.maximum(np.searchsorted(pts, base), 1), pts.size - 1) if pts.size > 1
                 else np.zeros(base.size, int))
            near = np.minimum(np.abs(pts[k] - base), np.abs(pts[np.maximum(k - 1, 0)] - base))
            base = base[near > 0.5 * dc]
    g = np.sort(np.concatenate(parts + [base]))
    keep = np.empty(g.size, dtype=bool)                                  # distinct values (np.unique's rule)
    keep[:1] = True
    np.not_equal(g[1:], g[:-1], out=keep[1:])
    keep &= (g == c_lo) | (np.abs(g - c_lo) > 1e-12 * c_lo)              # c_lo once (not also rounded from t_hi)
    keep &= (g >= min(c_floor, c_lo)) & (g < c_lim)
    return g[keep]


def phase_curve(st: IsoStack) -> tuple[np.ndarray, np.ndarray]:
    """Speeds aux (k,) from c_lo to c_lim (m/s) and sum_l h_l/H (nu_a + nu_b) of the films there (k,).

    c_lo = 0.95 x :func:`slowest_speed`; the phase of the grid's part (iii) is kh_max(c) times the
    second array (it does not depend on the rows), placed by linear interpolation between these
    points: 4000 uniform ones and, above each film's bulk speed v in that range, v (1 + d) for
    d = 1e-12 ... 1e-2 geometric (:data:`_ONSET`), where the phase rises as sqrt(c - v) (a chord
    across the first uniform cell above v put a heavy film's first Love modes at kh = 100, all
    within 0.2 m/s of its shear speed, in one cell: found by the count, not by the grid).
    """
    c_lo, c_lim = 0.95 * slowest_speed(st), st.c_lim
    aux = _linspace(c_lo, c_lim, 4000)
    onsets = [float(v[i]) for v in (st.shear, st.longitudinal) for i in range(st.frac.size) if c_lo < v[i] < c_lim]
    if onsets:                                 # nu ~ sqrt(2 (c - v) / v) just above v: linear there only on these
        more = (np.array(onsets)[:, None] * (1.0 + _ONSET)).ravel()
        aux = np.sort(np.concatenate([aux, more[more < c_lim]]))
    nu = np.zeros(aux.size)
    for v in (st.shear, st.longitudinal):
        for i in range(st.frac.size):
            j = int(np.searchsorted(aux, v[i], side="right"))        # the term is 0 below v (exactly)
            if j < aux.size:
                a = aux[j:]
                nu[j:] += st.frac[i] * (np.sqrt(np.maximum((a / v[i]) ** 2 - 1.0, 0.0)))
    return aux, nu


def _geometric(a: float, b: float, n: int) -> np.ndarray:
    """n points from a (exactly) towards b (excluded), uniform in log10 (numpy's geomspace without its generality)."""
    out = np.power(10.0, _linspace(np.log10(a), np.log10(b), n, endpoint=False))
    out[0] = a
    return out


def _linspace(a: float, b: float, n: int, endpoint: bool = True) -> np.ndarray:
    """n >= 2 points from a to b (or towards b), uniform: numpy's linspace of two scalars, without its generality."""
    y = np.arange(n, dtype=float)
    y *= (b - a) / (n - 1 if endpoint else n)
    y += a
    if endpoint:
        y[-1] = b
    return y
