"""Subsonic surface acoustic waves of piezoelectric half spaces (free and metallized), K^2, power flow.

Physics (docs/physics/piezoelectric.md). Fields U = (u1, u2, u3, phi); quasi-static constitutive
laws T_ij = A_ijkl u_k,l + e_kij phi,k and D_j = e_jkl u_k,l - eps_jl phi,l combine into one
generalised tensor E_IjKl (I, K = 0..3, index 3 electric): E_ijkl = A_ijkl, E_ij3l = e_lij,
E_3jkl = e_jkl, E_3j3l = -eps_jl, with sigma_Ij = E_IjKl U_K,l (sigma_ij = T_ij, sigma_3j = D_j).
Its Stroh blocks Q = E_I1K1, R = E_I1K2, T = E_I2K2 (4 x 4) give the 8 x 8 Stroh matrix
N(X) = [[-T^-1 R^T, T^-1], [R T^-1 R^T - Q + X D, -R T^-1]], D = diag(1, 1, 1, 0), X = rho v^2.

Lab frame: x1 propagation, x2 the normal INTO the crystal (crystal x2 > 0, vacuum x2 < 0),
x3 = x1 x x2. Partial waves U = a exp(ik(x1 + p x2)), generalised traction
b = (t_12, t_22, t_32, D_2)/(ik) = (R^T + p T) a. On the decaying subspace (4 roots Im p > 0)
b = M a, and Z = -i M is Hermitian below the limiting speed. Boundary conditions at x2 = 0:

* metallized (phi = 0, mechanically free): Z_mm u = 0 (Z_mm the mechanical 3 x 3 block);
* free (open circuit): the vacuum potential phi0 exp(ik x1 + k x2) has D_2 = -EPS0 k phi0 at the
  surface; continuity of D_2 = ik b_4 gives b_4 = +i EPS0 a_4, i.e. (Z - EPS0 e4 e4^T) a = 0;
  eliminating phi, Z_eff = Z_mm - Z_me (Z_ee - EPS0)^-1 Z_em (3 x 3 Hermitian) u = 0.

The SAW is where the lowest eigenvalue of Z_eff (or Z_mm) crosses zero for X in (0, X_L),
searched in t = sqrt(1 - X/X_L) by Newton / inverse-Hermite steps with the closed-form slope
d lam / dX, vectorised over the points (:mod:`surfwave.solvers.piezo_search`). At a sagittal
mirror (the blocks split, :func:`piezo_search.mirror_partition`) a sub-problem's wave above the
full X_L is reported as ``supersonic_decoupled``, as the elastic solver does. The limiting
X_L is the lowest trace X along x1 of the piezoelectrically
stiffened bulk waves (Gamma + gamma gamma^T / eps(n)) over sagittal wave normals.
Computations run in scaled units: A / max|A|, eps / max|eps|, e / sqrt(max|A| max|eps|)
(phi scaled by sqrt(max|eps| / max|A|)), so the 8 x 8 N is well conditioned.
"""
from __future__ import annotations

from typing import Sequence

import numpy as np
from numpy.typing import ArrayLike

from surfwave.errors import InputError
from surfwave.solvers import piezo_search as search
from surfwave.solvers.boundary import as_boundary
from surfwave.solvers.euler import euler_lab_axes  # noqa: F401  (re-exported: SAW Euler angles -> lab axes)
from surfwave.solvers.impedance import monic
from surfwave.solvers.piezo_stroh import (  # noqa: F401  (re-exported: the public building blocks)
    generalised_blocks,
    generalised_tensor,
    impedance,
    impedance_slope,
    limiting_x,
    piezo_bulk_speeds,
    stroh_matrix,
    stroh_polynomial_parts,
)
from surfwave.solvers.piezo_tensors import EPS0  # noqa: F401  (vacuum permittivity, F/m; re-exported)
from surfwave.vocab import ELECTRICAL  # noqa: F401  (kept: a public name of this module)

#: Smallest t = sqrt(1 - X/X_L) searched (roots closer to X_L than T_MIN^2 relative: none).
T_MIN = search.T_MIN

REASON_PSEUDO = ("no subsonic surface wave: the lowest eigenvalue of the surface impedance stays positive "
                 "up to the stiffened limiting speed (pseudo/leaky regime; see surfwave.solvers.leaky)")
REASON_UNSTABLE = ("no surface wave: the impedance is not positive definite at v = 0 or a stiffened bulk wave "
                   "has rho v^2 <= 0")
REASON_T = "no surface wave: the stiffened T block (A_i2k2 + e e / eps22) is not positive definite"
REASON_NOROOT_MIRROR = ("no surface wave: neither below v_L nor, for the decoupled sub-problem of the mirror, "
                        "below its own limiting speed")


def _flux(Q, R, E, r, a0, free, eps0, p) -> np.ndarray:
    """Depth-integrated time-averaged energy flux (P1, P3) per unit surface width, scaled units.

    <P_j> = (omega k / 2) Re(U^H S_j U) with S_j = E_.j.1 + E_.j.2 K1 (generalised stress
    sigma_.j = ik S_j U); along the depth U(x2) = exp(ik K1 x2) a0, K1 = N1 + N2 M, so the
    integral is a0^H Y a0 with the Lyapunov equation A Y + Y B = C, A = (i K1)^H, B = i K1,
    C = -Herm(S_j) (k = 1). Solved without eigenvectors or a 16 x 16 system: with
    g(z) = prod_j (z - i conj(p_j)) (the characteristic polynomial of -A; p the decaying
    roots, the eigenvalues of K1), g(-A) = 0 and Y B^k - (-A)^k Y = sum_{i<k} (-A)^i C B^(k-1-i),
    so Y = H g(B)^-1 with H = sum_k g_k sum_{i<k} (-A)^i C B^(k-1-i); only a0^H H g(B)^-1 a0 is
    needed (vector-matrix products, as in :func:`piezo_stroh.impedance_slope`).
    Free surface: plus the vacuum's -eps0 |phi0|^2 / 2 in P1 (phi D_1 of exp(k x2) fields).
    """
    N, M = r["N"], r["M"]
    K1 = N[:, :4, :4] + N[:, :4, 4:] @ M
    B = 1j * K1
    mA = 1j * np.conj(np.swapaxes(K1, -1, -2))                     # -A = -(i K1)^H
    g = monic(1j * np.conj(p))                                     # ascending, g_4 = 1
    gB = g[:, 0, None, None] * np.eye(4) + g[:, 1, None, None] * B
    Bk = B
    for k in range(2, 5):
        Bk = Bk @ B
        gB = gB + g[:, k, None, None] * Bk
    y = np.linalg.solve(gB, a0[..., None])                         # (m, 4, 1)
    rows, cols = [np.conj(a0)[:, None, :]], [y]
    for _ in range(3):
        rows.append(rows[-1] @ mA)
        cols.append(B @ cols[-1])
    out = []
    for j in (0, 2):
        S = E[:, :, j, :, 0] + E[:, :, j, :, 1] @ K1
        C = -0.5 * (S + np.conj(np.swapaxes(S, -1, -2)))
        Cc = [C @ c for c in cols]
        val = sum(g[:, k] * sum((rows[i] @ Cc[k - 1 - i])[:, 0, 0] for i in range(k)) for k in range(1, 5))
        out.append(val.real)
    out[0] = out[0] - np.where(free, 0.5 * eps0 * np.abs(a0[:, 3]) ** 2, 0.0)
    return np.stack(out, axis=-1)


def _check(A, e, eps, rho, electrical) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    A, e, eps = (np.asarray(x, dtype=float) for x in (A, e, eps))
    if A.ndim == 4:
        A, e, eps = A[None], e[None] if e.ndim == 3 else e, eps[None] if eps.ndim == 2 else eps
    m = A.shape[0] if A.ndim == 5 else -1
    for name, x, shp in (("A", A, (3, 3, 3, 3)), ("e", e, (3, 3, 3)), ("eps", eps, (3, 3))):
        if x.shape != (m,) + shp:
            raise InputError(f"{name} must have shape (m,) + {shp} with m = {m} (from A), got {x.shape}")
        if not np.all(np.isfinite(x)):
            raise InputError(f"{name} contains non-finite values, e.g. {x[~np.isfinite(x)][:3]}")
    rho = np.broadcast_to(np.asarray(rho, dtype=float), (m,))
    if np.any(~np.isfinite(rho) | (rho <= 0)):
        raise InputError(f"density rho must be positive and finite, got {rho[~(rho > 0)][:3]}")
    asym = np.abs(eps - np.swapaxes(eps, -1, -2)).max(axis=(1, 2))
    w = np.linalg.eigvalsh(eps)[:, 0]
    bad = (w <= 0) | (asym > 1e-9 * np.abs(eps).max(axis=(1, 2)))
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise InputError(f"eps must be symmetric positive definite (F/m), got eps[{k}] = {eps[k].tolist()} "
                         f"(lowest eigenvalue {w[k]:.4g})")
    sA = np.abs(A).max(axis=(1, 2, 3, 4))
    if np.any(sA == 0):
        raise InputError("A vanishes at some point")
    el = np.broadcast_to(np.asarray(electrical, dtype=object), (m,))
    vacuum = {v: as_boundary(v).vacuum for v in set(el.tolist())}   # each condition asked once
    return A, e, eps, rho, np.array([vacuum[v] for v in el.tolist()], dtype=bool)


def piezo_surface_wave(A: ArrayLike, e: ArrayLike, eps: ArrayLike, rho: ArrayLike, *,
                       electrical: str | Sequence[str] | np.ndarray = "free", tol: float = 1e-12) -> dict:
    """Subsonic surface acoustic wave of a piezoelectric half space, vectorised over m points.

    Parameters
    ----------
    A : array_like, shape (m, 3, 3, 3, 3), Pa
        Wave-propagation tensor, lab frame (x1 propagation, x2 inward normal), prestress inside.
    e : array_like, shape (m, 3, 3, 3), C/m^2
        Piezoelectric stress tensor e_kij, lab frame.
    eps : array_like, shape (m, 3, 3), F/m
        Absolute clamped permittivity, lab frame, symmetric positive definite.
    rho : float or array_like, shape (m,), kg/m^3
    electrical : "free" | "metallized", or an (m,) array of those
        Open-circuit surface (vacuum above) or a perfectly conducting, grounded film (phi = 0).
    tol : float
        Relative accuracy of X = rho c^2.

    Returns
    -------
    dict of ndarray
        ``c`` (m,) m/s (NaN where no subsonic wave); ``c_limit`` (m,) m/s, the lowest trace
        speed along x1 of the stiffened bulk waves over sagittal normals; ``wave_type`` (m,)
        object "surface" | "supersonic_decoupled" | "pseudo" | "none" (supersonic_decoupled: a
        wave of a mirror's decoupled sub-problem above c_limit); ``reason`` (m,) object ("" where
        c is finite); ``mirror`` (m,) object: "sagittal+phi" ((u1, u2, phi) | (u3) decouple),
        "sagittal" ((u1, u2) | (u3, phi)) or "";
        ``polarisation`` (m, 4) complex: surface (u1, u2, u3, phi) with |(u1, u2, u3)| = 1
        (dimensionless) and phi in volts per metre of surface displacement amplitude (phi/|u|,
        independent of wavelength), phase such that u2 is real >= 0 (u1 if u2 ~ 0);
        ``potential_share`` (m,) dimensionless: eps_bar |phi|^2 / (rho c^2 |u|^2 + eps_bar |phi|^2)
        at the surface, eps_bar = tr(eps)/3 (electric field energy scale eps k^2 |phi|^2 against
        the kinetic rho omega^2 |u|^2; 0 when e = 0);
        ``decay`` (m, 4) complex Stroh eigenvalues p (Im p > 0, ascending Im p);
        ``power_flow_angle`` (m,) degrees, angle of the depth-integrated energy flux (mechanical
        + electrical, with the vacuum's share for a free surface) from x1 towards our +x3
        (= +x2 of the SAW convention), i.e. atan2(P3, P1); ``method`` (m,) "piezo-stroh".

    Raises
    ------
    InputError
        Wrong shapes, non-finite values, rho <= 0, eps not symmetric positive definite, an
        unknown ``electrical``.

    Notes
    -----
    K^2 = 2 (c_free - c_metallized) / c_free: :func:`coupling_coefficient` (one call for both
    conditions, sharing the limiting speed and the first step). With e = 0 the potential
    decouples and both conditions reduce to :func:`surfwave.solvers.stroh.surface_wave`.
    """
    A, e, eps, rho, free = _check(A, e, eps, rho, electrical)
    m = A.shape[0]
    return _solve(_prepare(A, e, eps, rho), free, np.arange(m), tol)


def coupling_coefficient(A: ArrayLike, e: ArrayLike, eps: ArrayLike, rho: ArrayLike, *, tol: float = 1e-12) -> dict:
    """K^2 = 2 (c_free - c_metallized) / c_free with both speeds; dict of (m,) arrays.

    One call solving both conditions: the blocks, the limiting speed, the Stroh polynomial and
    the first impedance evaluation (eigenvalues of N) are shared. Also returns the full
    outputs of :func:`piezo_surface_wave` as ``free`` and ``metallized`` (dicts).
    """
    A, e, eps, rho, _ = _check(A, e, eps, rho, "free")
    m = A.shape[0]
    both = _solve(_prepare(A, e, eps, rho), np.repeat([True, False], m), np.tile(np.arange(m), 2), tol)
    rf = {k: v[:m] for k, v in both.items()}
    rm = {k: v[m:] for k, v in both.items()}
    return {"c_free": rf["c"], "c_metallized": rm["c"], "K2": 2 * (rf["c"] - rm["c"]) / rf["c"],
            "free": rf, "metallized": rm}


def _prepare(A, e, eps, rho) -> dict:
    """Scaled blocks, limiting speed, Stroh polynomial and mirror partition per orientation."""
    m = A.shape[0]
    sA = np.abs(A).max(axis=(1, 2, 3, 4))
    sE = np.abs(eps).max(axis=(1, 2))
    E = generalised_tensor(A / sA[:, None, None, None, None], e / np.sqrt(sA * sE)[:, None, None, None],
                           eps / sE[:, None, None])
    Q, R, T = E[:, :, 0, :, 0], E[:, :, 0, :, 1], E[:, :, 1, :, 1]
    Tst = T[:, :3, :3] - T[:, :3, 3:] * T[:, 3:, :3] / T[:, 3:, 3:]
    Tpd = np.linalg.eigvalsh(Tst)[:, 0] > 0
    XL = np.full(m, np.nan)
    if Tpd.any():
        XL[Tpd] = limiting_x(Q[Tpd], R[Tpd], T[Tpd])
    stable = Tpd & (XL > 0)
    parts = np.zeros((m, 4, 9))
    if stable.any():
        parts[stable] = stroh_polynomial_parts(Q[stable], R[stable], T[stable])
    return {"sA": sA, "sE": sE, "rho": rho, "E": E, "Q": Q, "R": R, "T": T, "XL": XL, "Tpd": Tpd,
            "stable": stable, "parts": parts, "eps": eps, "mirror": search.mirror_partition(Q, R, T)}


def _solve(pr: dict, free, rows, tol) -> dict:
    """Solve the points ``rows`` (k,) of the prepared orientations under conditions ``free`` (k,)."""
    m = len(rows)
    Q, R, T, E, XL, parts = (pr[k][rows] for k in ("Q", "R", "T", "E", "XL", "parts"))
    sA, sE, rho, eps, mir = pr["sA"][rows], pr["sE"][rows], pr["rho"][rows], pr["eps"][rows], pr["mirror"][rows]
    Tpd, stable = pr["Tpd"][rows], pr["stable"][rows]
    alpha = np.sqrt(sA / sE)                                        # phi = alpha * phi_hat
    eps0 = EPS0 / sE
    X = np.full(m, np.nan)
    status = np.full(m, 2)
    P = np.full((m, 4), np.nan + 0j)
    last = {"Z": np.full((m, 4, 4), np.nan + 0j), "M": np.full((m, 4, 4), np.nan + 0j), "N": np.full((m, 8, 8), np.nan)}
    if stable.any():
        s = np.flatnonzero(stable)
        u, inv = np.unique(rows[s], return_inverse=True)            # one first step per orientation
        q = pr
        X0 = q["XL"][u] * (1.0 - search.T_START ** 2)
        first = impedance(q["Q"][u], q["R"][u], q["T"][u], X0, nm=3)
        first = {k: v[inv] for k, v in first.items()}
        X[s], status[s], P[s], ls = search.root_search(Q[s], R[s], T[s], XL[s], free[s], eps0[s], tol, parts[s], 3,
                                                       first)
        for key in last:
            last[key][s] = ls[key]
    found = np.isfinite(X)
    pol = np.full((m, 4), np.nan + 0j)
    decay = np.full((m, 4), np.nan + 0j)
    pfa = np.full(m, np.nan)
    if found.any():
        f = found
        r = {key: v[f] for key, v in last.items()}                 # the search's last step (within tol)
        a0 = search.lowest(r["Z"], free[f], eps0[f], 3)[1]
        ref = np.where(np.abs(a0[:, 1]) > 1e-8, a0[:, 1], a0[:, 0])
        a0 = a0 * (np.conj(ref) / np.abs(ref))[:, None]
        Pf = _flux(Q[f], R[f], E[f], r, a0, free[f], eps0[f], P[f])
        pfa[f] = np.degrees(np.arctan2(Pf[:, 1], Pf[:, 0]))
        pol[f] = a0
        decay[f] = P[f]
    # sagittal mirrors: the decoupled sub-problem above the full limiting speed
    sup = np.zeros(m, dtype=bool)
    todo = stable & (status == 1) & (mir != "")
    if todo.any():
        Xs, pols, decs = _mirror_waves(Q[todo], R[todo], T[todo], XL[todo], free[todo], eps0[todo], mir[todo], tol)
        k = np.flatnonzero(todo)
        ok = np.isfinite(Xs)
        X[k[ok]], pol[k[ok]], decay[k[ok]] = Xs[ok], pols[ok], decs[ok]
        pfa[k[ok]] = 0.0                                            # the mirror x3 -> -x3: no flux along x3
        sup[k[ok]] = Xs[ok] >= XL[k[ok]] * (1 - 1e-12)               # as the elastic solver labels them
        status[k[~ok]] = 3
    found = np.isfinite(X)
    reason = np.full(m, "", dtype=object)
    reason[status == 1] = REASON_PSEUDO
    reason[status == 2] = REASON_UNSTABLE
    reason[status == 3] = REASON_NOROOT_MIRROR
    reason[~Tpd] = REASON_T
    reason[found] = ""
    wave_type = np.where(found, np.where(sup, "supersonic_decoupled", "surface"),
                         np.where(status == 1, "pseudo", "none")).astype(object)
    pol[:, 3] = pol[:, 3] * alpha
    ebar = np.trace(eps, axis1=1, axis2=2) / 3.0
    el = ebar * np.abs(pol[:, 3]) ** 2
    with np.errstate(all="ignore"):
        share = el / (X * sA + el)
    return {
        "c": np.sqrt(X * sA / rho),
        "c_limit": np.sqrt(XL * sA / rho),
        "wave_type": wave_type,
        "reason": reason,
        "polarisation": pol,
        "potential_share": share,
        "decay": decay,
        "power_flow_angle": pfa,
        "mirror": mir,
        "method": np.full(m, "piezo-stroh", dtype=object),
    }


def _mirror_waves(Q, R, T, XL, free, eps0, mir, tol):
    """Surface waves of the decoupled sub-problems of mirror points, X (k,) NaN where none.

    "sagittal+phi": (u1, u2, phi), nm = 2; "sagittal": the elastic (u1, u2) problem and the
    (u3, phi) one (nm = 1, a Bleustein-Gulyaev wave); each with its own limiting speed, the
    slowest root kept. Returns X, the polarisation (k, 4) (scaled phi) and decay (k, 4) (the
    sub-problem's p, NaN-padded).
    """
    k = Q.shape[0]
    X = np.full(k, np.nan)
    pol = np.full((k, 4), np.nan + 0j)
    dec = np.full((k, 4), np.nan + 0j)
    subs = [("sagittal+phi", [0, 1, 3], 2), ("sagittal", [0, 1], 2), ("sagittal", [2, 3], 1)]
    for name, S, nm in subs:
        rows = np.flatnonzero(mir == name)
        if rows.size == 0:
            continue
        ix = np.ix_(rows, np.asarray(S), np.asarray(S))
        q, r, t = Q[ix], R[ix], T[ix]
        xl = limiting_x(q, r, t, nm)
        okl = np.isfinite(xl) & (xl > 0)
        rows, q, r, t, xl = rows[okl], q[okl], r[okl], t[okl], xl[okl]
        if rows.size == 0:
            continue
        parts = stroh_polynomial_parts(q, r, t, nm)
        Xs, st, p, _ = search.root_search(q, r, t, xl, free[rows], eps0[rows], tol, parts, nm)
        better = np.isfinite(Xs) & ~(X[rows] <= Xs)
        if not better.any():
            continue
        b = rows[better]
        imp = impedance(q[better], r[better], t[better], Xs[better], p[better], parts[better], nm)
        a = search.lowest(imp["Z"], free[b], eps0[b], nm)[1]
        ref = a[:, 1] if 1 in S else a[:, 0]
        ref = np.where(np.abs(ref) > 1e-8, ref, a[:, 0])
        a = a * (np.conj(ref) / np.abs(ref))[:, None]
        if len(S) < 4 and 3 not in S:
            a = np.concatenate([a, np.zeros((b.size, 1))], axis=-1)
        full = np.zeros((b.size, 4), dtype=complex)
        full[:, S if 3 in S else S + [3]] = a
        X[b], pol[b] = Xs[better], full
        dec[b] = np.nan
        dec[b, :len(S)] = p[better]
    return X, pol, dec

