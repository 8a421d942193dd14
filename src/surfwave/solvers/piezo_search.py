"""Root search of the piezoelectric SAW solver (:mod:`surfwave.solvers.piezo`) and its mirror sub-problems.

Everything here works on scaled generalised Stroh blocks Q, R, T (m, n, n) whose first ``nm``
components are mechanical and whose last (if n > nm) is the electric potential.

Root search (docs/physics/piezoelectric.md): the lowest eigenvalue lam of the effective 3 x 3
impedance (metallized: Z_mm; free: Z_mm - Z_me (Z_ee - eps0)^-1 Z_em) decreases with X; its
zero in (0, X_L) is found by Newton's method in t = sqrt(1 - X/X_L) from ``T_START`` (then
inverse cubic Hermite steps through the two latest points) safeguarded by bisection: one step
is :func:`surfwave.solvers.stroh.bracketed_step`, shared with the elastic search
(:func:`surfwave.solvers.stroh._root_search`). The slope
d lam / dX = a^H (dZ/dX) a comes in closed form from the Sylvester equation of the Riccati
equation (:func:`piezo_stroh.impedance_slope`), a = (u, phi). After the first step the decaying
Stroh roots are tracked (Newton on the Stroh polynomial); eigenvalues of N only at the first
step and where tracking cannot vouch for its roots.

Mirrors: where the generalised blocks split into two uncoupled sets of components
(:func:`mirror_partition`) each set is its own Stroh problem with its own limiting speed; a
sub-problem's surface wave above the full X_L is ``supersonic_decoupled``.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from surfwave.solvers.impedance import lowest_eigenpair
from surfwave.solvers.piezo_stroh import impedance, impedance_slope, stroh_matrix
from surfwave.solvers.stroh import T_MIN, bracketed_step

#: Starting point of the Newton iteration (X = 0.91 X_L), as in the elastic solver.
T_START = 0.3
MAX_ITER = 100
#: Relative size below which a coupling entry of the scaled blocks counts as zero.
SYMMETRY_TOL = 1e-10

#: The two ways a sagittal mirror (or a two-fold axis along x3) can split (u1, u2, u3, phi):
#: "sagittal+phi": (u1, u2, phi) | (u3) -- x1 x2 a mirror plane of the crystal (e odd in index 3 vanish);
#: "sagittal": (u1, u2) | (u3, phi) -- a two-fold axis along x3 (e even in index 3 vanish: phi
#: couples to the SH motion, Bleustein-Gulyaev).
PARTITIONS = {"sagittal+phi": ([0, 1, 3], [2]), "sagittal": ([0, 1], [2, 3])}


def mirror_partition(Q: np.ndarray, R: np.ndarray, T: np.ndarray, tol: float = SYMMETRY_TOL) -> np.ndarray:
    """Which split of (u1, u2, u3, phi) the generalised blocks allow, (m,) object.

    A split S | S' holds where every coupling entry Q_JK, R_JK, R_KJ, T_JK with J in S, K in S'
    is below ``tol`` times max|Q, R, T| (the blocks carry E_IjKl with j, l in {1, 2}, so these are
    the components of A, e and eps with an odd number of indices 3 for the first split and
    those of e with an even number for the second, checked as the numbers are, not assumed
    from the crystal class). Returns "sagittal+phi" where (u1, u2, phi) | (u3) holds (also
    when e = 0: phi then decouples from everything), else "sagittal" where (u1, u2) | (u3, phi)
    holds, else "" (no mirror). Q, R, T: (m, 4, 4), any consistent scaling.
    """
    scale = np.maximum.reduce([np.abs(B).max(axis=(1, 2)) for B in (Q, R, T)])
    out = np.full(Q.shape[0], "", dtype=object)
    for name in ("sagittal", "sagittal+phi"):                      # the second wins where both hold
        S, S2 = PARTITIONS[name]
        a, b = np.ix_(S, S2)
        blocks = (Q[:, a, b], R[:, a, b], np.swapaxes(R, 1, 2)[:, a, b], T[:, a, b])
        c = np.maximum.reduce([np.abs(B).max(axis=(1, 2)) for B in blocks])
        out[c <= tol * scale] = name
    return out


def effective(Z: np.ndarray, free: np.ndarray, eps0: np.ndarray, nm: int) -> np.ndarray:
    """Mechanical nm x nm impedance with the electrical condition applied (Hermitian), (m, nm, nm).

    free: Z_mm - Z_me (Z_ee - eps0)^-1 Z_em (open circuit, b_e = i eps0 a_e); else Z_mm (phi = 0).
    Without an electric component (n = nm): Z.
    """
    if Z.shape[-1] == nm:
        Zf = Z
    else:
        zee = Z[:, nm, nm].real - eps0
        schur = Z[:, :nm, :nm] - Z[:, :nm, nm:] * Z[:, nm:, :nm] / zee[:, None, None]
        Zf = np.where(free[:, None, None], schur, Z[:, :nm, :nm])
    return 0.5 * (Zf + np.conj(np.swapaxes(Zf, -1, -2)))


def lowest(Z: np.ndarray, free: np.ndarray, eps0: np.ndarray, nm: int) -> tuple[np.ndarray, np.ndarray]:
    """Lowest eigenvalue (m,) of the effective impedance and the extended vector a = (u, phi) (m, n).

    u: unit eigenvector; phi = -Z_em u / (Z_ee - eps0) (free) or 0 (metallized). NaN rows of Z
    (not subsonic) give lam = NaN.
    """
    bad = ~np.isfinite(Z).all(axis=(1, 2))
    Zf = effective(np.where(bad[:, None, None], np.eye(Z.shape[-1]), Z), free, eps0, nm)
    lam, u = lowest_eigenpair(Zf)
    lam = np.where(bad, np.nan, lam)
    if Z.shape[-1] == nm:
        return lam, u
    zee = Z[:, nm, nm].real - eps0
    with np.errstate(all="ignore"):
        ph = np.where(free, -np.einsum("mj,mj->m", Z[:, nm, :nm], u) / zee, 0.0)
    return lam, np.concatenate([u, ph[:, None]], axis=-1)


def root_search(Q: np.ndarray, R: np.ndarray, T: np.ndarray, XL: np.ndarray, free: np.ndarray, eps0: np.ndarray,
                tol: float, parts: np.ndarray, nm: int, first: dict[str, Any] | None = None
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """Subsonic root X in (0, XL) of the lowest eigenvalue lam of the effective impedance.

    Safeguarded Newton / inverse-Hermite iteration in t = sqrt(1 - X/XL) from ``T_START``,
    vectorised over the points not yet converged (the port of the elastic solver's search, see
    the module docstring); bracket (lo, hi) from (T_MIN, 1) shrinks with the sign of each lam
    (lam increases with t). A point driven to t = T_MIN with lam > 0 has no subsonic root; one
    converging near X = 0 has lam(X = 0) > 0 verified. ``first``: the :func:`impedance` dict
    at t = T_START for all m points (shared between electrical conditions), optional.

    Returns X (m,) (NaN where none), status (m,) int (0 root, 1 no root below X_L, 2
    lam(X = 0) <= 0), the decaying p (m, n) of the last step and that step's impedance
    (dict ``Z``, ``M``, ``N``; within ``tol`` of the root, as the elastic solver's outputs).
    """
    m, n = Q.shape[0], Q.shape[-1]
    X = np.full(m, np.nan)
    status = np.zeros(m, dtype=int)
    P = np.full((m, n), np.nan + 0j)
    last = {"Z": np.full((m, n, n), np.nan + 0j), "M": np.full((m, n, n), np.nan + 0j),
            "N": np.full((m, 2 * n, 2 * n), np.nan)}
    if m == 0:
        return X, status, P, last

    N0 = stroh_matrix(Q, R, T, np.zeros(m), nm)

    def ev(i, t, guess=None, r=None):
        if r is None:
            r = impedance(Q[i], R[i], T[i], XL[i] * (1.0 - t * t), guess, parts[i], nm, N0[i])
        lam, a = lowest(r["Z"], free[i], eps0[i], nm)
        return lam, impedance_slope(r, a, nm) * (-2.0 * t * XL[i]), r

    idx = np.arange(m)
    lo, hi = np.full(m, T_MIN), np.ones(m)
    hi_checked = np.zeros(m, dtype=bool)
    t = np.full(m, T_START)
    guess = None
    tp, lp, gp = (np.full(m, np.nan) for _ in range(3))
    for it in range(MAX_ITER):
        if idx.size == 0:
            break
        lam, dlam, r = ev(idx, t, guess, first if (it == 0 and first is not None) else None)
        p = r["p"]
        bad = ~np.isfinite(lam) | ~np.isfinite(dlam)
        lam = np.where(bad, -1.0, lam)                             # supersonic by rounding: root lies above
        neg, lo, hi, new, done = bracketed_step(lam, dlam, t, lo, hi, bad, (tp, lp, gp), XL[idx], tol)
        hi_checked |= ~neg
        none = ~neg & (t <= T_MIN)
        need = done & ~hi_checked & (new > 0.99)
        st = np.where(none, 1, 0)
        if need.any():
            k = idx[need]
            lam1 = lowest(impedance(Q[k], R[k], T[k], np.zeros(k.size), nm=nm)["Z"], free[k], eps0[k], nm)[0]
            badk = np.flatnonzero(need)[~(np.isfinite(lam1) & (lam1 > 0))]
            new[badk] = np.nan
            st[badk] = 2
        new = np.where(none, np.nan, new)
        done |= none
        X[idx[done]] = XL[idx[done]] * (1.0 - new[done] ** 2)
        status[idx[done]] = st[done]
        P[idx[done]] = p[done]
        for key in last:
            last[key][idx[done]] = r[key][done]
        keep = ~done
        tp, lp, gp = (np.where(bad, np.nan, v)[keep] for v in (t, lam, dlam))
        idx, lo, hi, t, hi_checked, guess = idx[keep], lo[keep], hi[keep], new[keep], hi_checked[keep], p[keep]
    status[idx] = 1                                                 # not converged (should not happen)
    return X, status, P, last
