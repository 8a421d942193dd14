"""A check of the energy velocity of guided modes, and a robust second route where it fails.

The energy velocity of :func:`surfwave.layers.fields.mode_fields` is exact in exact arithmetic, but
for a mode trapped under a barrier at large kh the zero of the boundary matrix sits on one of its
poles, the matrix has no small eigenvalue at the root in floating point and its null vector (the
surface vector) is not resolved (random three-film stacks at kh = 60 gave 12741.7 m/s against
1645.07 m/s from differences of c(kh)); :func:`surfwave.layers.fields.mode_fields` sends such modes
here. The check: implicit differentiation of
the eigenvalue lambda(c, kh) of the Hermitian boundary matrix that vanishes at the mode,

    dc/dkh = -(d lambda / d kh) / (d lambda / d c),    v_g = c + kh dc/dkh,

with differences of relative step :data:`STEP` (one-sided from the mode first, then central).
Where the energy velocity differs from it by more than :data:`TOL` (relative) -- or either is not
finite -- the group velocity is taken from central differences of c(kh) itself: the family's modes are solved afresh
(:func:`surfwave.layers.modes.family_modes`, with the exact count) at kh (1 +- :data:`DKH`) and
kh (1 +- 2 :data:`DKH`) (Richardson's extrapolation of the two central differences) and the one
nearest the known root taken (NaN where that is ambiguous); this needs no amplitudes at all. The
zero of lambda of a trapped mode sits next to a pole (relative distance 1e-6 and less), hence the
check's small step; where the check itself is spoilt by rounding the robust route is merely taken
more often than needed.
"""
from __future__ import annotations

import numpy as np

from surfwave.layers.partial import Blocks, Family
from surfwave.layers.recursion import boundary_eigenvalues
from surfwave.solvers.boundary import Boundary

__all__ = ["checked_group_velocity"]

#: Relative steps of the implicit-differentiation check: one-sided and central with the first, central
#: with the second (it passes with any).
STEP = (1e-9, 1e-11)
#: Largest relative difference between the energy velocity and the check.
TOL = 1e-6
#: Relative kh step of the fallback's central differences (with the doubled step and
#: Richardson's extrapolation; the roots' rounding gives ~1e-8 of v_g).
DKH = 1e-4


def _eig(b: Blocks, fam: Family, c: np.ndarray, kh: np.ndarray, electrical: str | Boundary,
         j: np.ndarray) -> np.ndarray:
    """Eigenvalue number j (ascending) of the boundary matrix at (c, kh), all (m,)."""
    w = boundary_eigenvalues(b, fam, c, kh[:, None], electrical)[:, 0, :]
    return w[np.arange(c.size), j]


def _nearest(c0: np.ndarray, allc: np.ndarray) -> np.ndarray:
    """The speed in each row of allc (m, n) nearest to c0 (m,); NaN where it is not clearly the nearest (or n = 0)."""
    if allc.shape[1] == 0:
        return np.full(c0.size, np.nan)
    d = np.abs(np.where(np.isfinite(allc), allc, np.inf) - c0[:, None])
    order = np.argsort(d, axis=1)
    m = np.arange(c0.size)
    first = d[m, order[:, 0]]
    second = d[m, order[:, 1]] if allc.shape[1] > 1 else np.full(c0.size, np.inf)
    pick = allc[m, order[:, 0]]
    return np.where(np.isfinite(first) & (first < 0.25 * second), pick, np.nan)


def checked_group_velocity(b: Blocks, fam: Family, c: np.ndarray, kh: np.ndarray, v: np.ndarray,
                           electrical: str | Boundary, w: np.ndarray | None = None) -> np.ndarray:
    """The energy velocity ``v`` (m,) of modes (c, kh) (m,), replaced by differences of c(kh) where it fails the check.

    Parameters
    ----------
    b : Blocks
    fam : Family
    c, kh : ndarray, shape (m,)
        The modes (m/s, and kh).
    v : ndarray, shape (m,)
        Their energy velocities (m/s), :func:`surfwave.layers.fields.mode_fields`.
    electrical : str or Boundary
    w : ndarray, shape (m, na), optional
        The boundary matrix's eigenvalues at the modes (if already computed).

    Returns
    -------
    ndarray, shape (m,)
        Group velocity, m/s (NaN where neither route has an answer).
    """
    v = np.array(v, dtype=float)
    rows = np.flatnonzero(kh > 0)
    if rows.size == 0:
        return v
    cr, kr = c[rows], kh[rows]
    w0 = boundary_eigenvalues(b, fam, cr, kr[:, None], electrical)[:, 0, :] if w is None else np.asarray(w)[rows]
    j = np.argmin(np.where(np.isfinite(w0), np.abs(w0), np.inf), axis=-1)
    l0 = w0[np.arange(rows.size), j]
    bad = np.ones(rows.size, dtype=bool)
    for h, central in ((STEP[0], False), (STEP[0], True), (STEP[1], True)):
        i = np.flatnonzero(bad)
        if i.size == 0:
            break
        ci, ki, ji = cr[i], kr[i], j[i]
        lc = _eig(b, fam, ci * (1 + h), ki, electrical, ji)
        lk = _eig(b, fam, ci, ki * (1 + h), electrical, ji)
        if central:
            lc = lc - _eig(b, fam, ci * (1 - h), ki, electrical, ji)
            lk = lk - _eig(b, fam, ci, ki * (1 - h), electrical, ji)
        else:
            lc, lk = lc - l0[i], lk - l0[i]
        with np.errstate(all="ignore"):
            est = ci - ki * (lk / ki) / (lc / ci)
            bad[i] = ~(np.isfinite(est) & (np.abs(est - v[rows][i]) <= TOL * np.abs(est)))
    if not bad.any():
        return v
    from surfwave.layers.modes import family_modes

    cb, kb = cr[bad], kr[bad]
    uk, inv = np.unique(kb, return_inverse=True)                  # solves per distinct kh
    steps = (DKH, 2 * DKH)
    allc = family_modes(b, fam, np.concatenate([uk * (1 + s * sign) for s in steps for sign in (1, -1)]),
                        electrical=electrical)
    nk = uk.size
    diff = []
    for q, s in enumerate(steps):
        cp, cm = _nearest(cb, allc[2 * q * nk + inv]), _nearest(cb, allc[(2 * q + 1) * nk + inv])
        d = s * kb
        diff.append((cp * (kb + d) - cm * (kb - d)) / (2 * d))
    v[rows[bad]] = (4 * diff[0] - diff[1]) / 3                   # Richardson: truncation O(DKH^4)
    return v
