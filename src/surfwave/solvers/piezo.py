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
searched in t = sqrt(1 - X/X_L) by the Anderson-Bjorck (modified regula falsi) method, vectorised
over the points. The limiting X_L is the lowest trace X along x1 of the piezoelectrically
stiffened bulk waves (Gamma + gamma gamma^T / eps(n)) over sagittal wave normals.
Computations run in scaled units: A / max|A|, eps / max|eps|, e / sqrt(max|A| max|eps|)
(phi scaled by sqrt(max|eps| / max|A|)), so the 8 x 8 N is well conditioned.
"""
from __future__ import annotations

import numpy as np

from surfwave.errors import InputError
from surfwave.solvers.piezo_stroh import (  # noqa: F401  (re-exported: the public building blocks)
    generalised_blocks, generalised_tensor, impedance, limiting_x, piezo_bulk_speeds, stroh_matrix,
    stroh_polynomial_parts)

#: Vacuum permittivity, F/m (CODATA 2018).
EPS0 = 8.8541878128e-12
#: Smallest t = sqrt(1 - X/X_L) searched (roots closer to X_L than T_MIN^2 relative: none).
T_MIN = 1e-6
MAX_ITER = 80

REASON_PSEUDO = ("no subsonic surface wave: the lowest eigenvalue of the surface impedance stays positive "
                 "up to the stiffened limiting speed (pseudo/leaky regime; see surfwave.solvers.leaky)")
REASON_UNSTABLE = "no surface wave: the impedance is not positive definite at v = 0 or a stiffened bulk wave has rho v^2 <= 0"
REASON_T = "no surface wave: the stiffened T block (A_i2k2 + e e / eps22) is not positive definite"


def _effective(Z, free, eps0) -> np.ndarray:
    """Mechanical 3 x 3 impedance with the electrical condition applied (Hermitian), (m, 3, 3).

    free: Z_mm - Z_me (Z_ee - eps0)^-1 Z_em (open circuit, b_4 = i eps0 a_4); else Z_mm (phi = 0).
    """
    zee = Z[:, 3, 3].real - eps0
    schur = Z[:, :3, :3] - Z[:, :3, 3:] * Z[:, 3:, :3] / zee[:, None, None]
    Zf = np.where(free[:, None, None], schur, Z[:, :3, :3])
    return 0.5 * (Zf + np.conj(np.swapaxes(Zf, -1, -2)))


def _lam(Q, R, T, X, free, eps0, guess=None, parts=None):
    """Lowest eigenvalue of the effective impedance at X (-1 where not subsonic) and the decaying p."""
    r = impedance(Q, R, T, X, guess, parts)
    lam = np.full(len(X), -1.0)                                    # beyond X_L by rounding: root lies below
    ok = r["subsonic"]
    if ok.any():
        lam[ok] = np.linalg.eigvalsh(_effective(r["Z"][ok], free[ok], eps0[ok]))[:, 0]
    return lam, r["p"]


def _root_search(Q, R, T, XL, free, eps0, tol, parts) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Root X in (0, XL) of the lowest eigenvalue lam of the effective impedance; NaN where none.

    lam(t) with X = XL (1 - t^2) increases with t; bracket [T_MIN, 1], Anderson-Bjorck steps, vectorised
    over the points not yet converged. Returns X (m,), status (m,) int: 0 root, 1 no root
    (lam > 0 at t = T_MIN), 2 lam(X = 0) <= 0, and the decaying p (m, 4) of the last step.
    """
    m = len(XL)
    X = np.full(m, np.nan)
    status = np.zeros(m, dtype=int)
    P = np.full((m, 4), np.nan + 0j)
    f1 = _lam(Q, R, T, np.zeros(m), free, eps0)[0]
    f0, guess = _lam(Q, R, T, XL * (1 - T_MIN ** 2), free, eps0)
    status[~(f1 > 0)] = 2
    status[(f1 > 0) & (f0 > 0)] = 1
    idx = np.flatnonzero(status == 0)
    a, fa = np.full(idx.size, T_MIN), f0[idx]                       # fa <= 0
    b, fb = np.ones(idx.size), f1[idx]                              # fb > 0
    side = np.zeros(idx.size, dtype=int)
    x_old = np.full(idx.size, np.nan)
    X[idx[fa == 0]] = XL[idx[fa == 0]] * (1 - T_MIN ** 2)
    P[idx[fa == 0]] = guess[idx[fa == 0]]
    keep = fa != 0
    idx, a, fa, b, fb, side, x_old = (v[keep] for v in (idx, a, fa, b, fb, side, x_old))
    guess = guess[idx]
    for _ in range(MAX_ITER):
        if idx.size == 0:
            break
        x = (a * fb - b * fa) / (fb - fa)
        x = np.where((x > a) & (x < b), x, 0.5 * (a + b))
        f, p = _lam(Q[idx], R[idx], T[idx], XL[idx] * (1 - x * x), free[idx], eps0[idx], guess, parts[idx])
        neg = f <= 0
        # Anderson-Bjorck: when the same end is replaced twice running, scale the retained end's
        # value by 1 - f / f_replaced (0.5 if that is not positive)
        with np.errstate(all="ignore"):
            ga, gb = 1.0 - f / fa, 1.0 - f / fb
        ga, gb = np.where(ga > 0, ga, 0.5), np.where(gb > 0, gb, 0.5)
        fb = np.where(neg & (side == -1), ga * fb, fb)
        fa = np.where(~neg & (side == 1), gb * fa, fa)
        a, fa = np.where(neg, x, a), np.where(neg, f, fa)
        b, fb = np.where(neg, b, x), np.where(neg, fb, f)
        side = np.where(neg, -1, 1)
        Xn = XL[idx] * (1 - x * x)
        dX = 2 * x * XL[idx] * np.minimum(np.abs(x - x_old), b - a)
        done = (f == 0) | (dX <= 0.1 * tol * Xn) | (2 * b * (b - a) * XL[idx] <= 0.1 * tol * Xn)
        X[idx[done]] = Xn[done]
        P[idx[done]] = p[done]
        x_old, guess = x, np.where(np.isfinite(p), p, np.nan)
        keep = ~done
        idx, a, fa, b, fb, side, x_old, guess = (v[keep] for v in (idx, a, fa, b, fb, side, x_old, guess))
    status[idx] = 1                                                 # not converged (should not happen)
    return X, status, P


def _null(H) -> np.ndarray:
    """Unit eigenvector of the smallest |eigenvalue| of Hermitian H (m, d, d)."""
    w, v = np.linalg.eigh(H)
    j = np.argmin(np.abs(w), axis=-1)
    return np.take_along_axis(v, j[:, None, None], axis=-1)[..., 0]


def _flux(Q, R, E, r, a0, free, eps0) -> np.ndarray:
    """Depth-integrated time-averaged energy flux (P1, P3) per unit surface width, scaled units.

    <P_j> = (omega k / 2) Re(U^H S_j U) with S_j = E_.j.1 + E_.j.2 K1 (generalised stress
    sigma_.j = ik S_j U); along the depth U(x2) = exp(ik K1 x2) a0, K1 = N1 + N2 M, so the
    integral is a0^H Y a0 with the Lyapunov equation (i K1)^H Y + Y (i K1) = -Herm(S_j) (k = 1).
    Free surface: plus the vacuum's -eps0 |phi0|^2 / 2 in P1 (phi D_1 of exp(k x2) fields).
    """
    m = a0.shape[0]
    N, M = r["N"], r["M"]
    K1 = N[:, :4, :4] + N[:, :4, 4:] @ M
    L = 1j * K1
    I4 = np.eye(4)
    # (L^H Y + Y L)[a, b] = conj(L)[c, a] Y[c, b] + Y[a, c] L[c, b]
    op = np.einsum("mca,bd->mabcd", np.conj(L), I4) + np.einsum("ac,mdb->mabcd", I4, L)
    op = op.reshape(m, 16, 16)
    out = []
    for j in (0, 2):
        S = E[:, :, j, :, 0] + E[:, :, j, :, 1] @ K1
        S = 0.5 * (S + np.conj(np.swapaxes(S, -1, -2)))
        Y = np.linalg.solve(op, -S.reshape(m, 16, 1)).reshape(m, 4, 4)
        out.append(np.einsum("ma,mab,mb->m", np.conj(a0), Y, a0).real)
    out[0] = out[0] - np.where(free, 0.5 * eps0 * np.abs(a0[:, 3]) ** 2, 0.0)
    return np.stack(out, axis=-1)


def _check(A, e, eps, rho, electrical):
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
    unknown = sorted({str(v) for v in el if v not in ("free", "metallized")})
    if unknown:
        raise InputError(f"electrical must be 'free' or 'metallized', got {unknown}")
    return A, e, eps, rho, el == "free"


def piezo_surface_wave(A, e, eps, rho, *, electrical="free", tol: float = 1e-12) -> dict:
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
        object "surface" | "pseudo" | "none"; ``reason`` (m,) object ("" where c is finite);
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
    K^2 = 2 (c_free - c_metallized) / c_free from two calls. With e = 0 the potential
    decouples and both conditions reduce to :func:`surfwave.solvers.stroh.surface_wave`.
    """
    A, e, eps, rho, free = _check(A, e, eps, rho, electrical)
    m = A.shape[0]
    sA = np.abs(A).max(axis=(1, 2, 3, 4))
    sE = np.abs(eps).max(axis=(1, 2))
    alpha = np.sqrt(sA / sE)                                        # phi = alpha * phi_hat
    Ah = A / sA[:, None, None, None, None]
    eh = e / np.sqrt(sA * sE)[:, None, None, None]
    epsh = eps / sE[:, None, None]
    eps0 = EPS0 / sE
    E = generalised_tensor(Ah, eh, epsh)
    Q, R, T = E[:, :, 0, :, 0], E[:, :, 0, :, 1], E[:, :, 1, :, 1]

    Tst = T[:, :3, :3] - T[:, :3, 3:] * T[:, 3:, :3] / T[:, 3:, 3:]
    Tpd = np.linalg.eigvalsh(Tst)[:, 0] > 0
    XL = np.full(m, np.nan)
    if Tpd.any():
        XL[Tpd] = limiting_x(Q[Tpd], R[Tpd], T[Tpd])
    stable = Tpd & (XL > 0)
    X = np.full(m, np.nan)
    status = np.full(m, 2)
    P = np.full((m, 4), np.nan + 0j)
    parts = np.zeros((m, 4, 9))
    if stable.any():
        parts[stable] = stroh_polynomial_parts(Q[stable], R[stable], T[stable])
        X[stable], status[stable], P[stable] = _root_search(Q[stable], R[stable], T[stable], XL[stable],
                                                            free[stable], eps0[stable], tol, parts[stable])
    found = np.isfinite(X)
    reason = np.full(m, "", dtype=object)
    reason[status == 1] = REASON_PSEUDO
    reason[status == 2] = REASON_UNSTABLE
    reason[~Tpd] = REASON_T
    reason[found] = ""
    wave_type = np.where(found, "surface", np.where(status == 1, "pseudo", "none")).astype(object)

    pol = np.full((m, 4), np.nan + 0j)
    decay = np.full((m, 4), np.nan + 0j)
    share = np.full(m, np.nan)
    pfa = np.full(m, np.nan)
    if found.any():
        f = found
        r = impedance(Q[f], R[f], T[f], X[f], P[f], parts[f])
        Z = r["Z"]
        u = _null(_effective(Z, free[f], eps0[f]))
        zee = Z[:, 3, 3].real - np.where(free[f], eps0[f], 0.0)
        ph = np.where(free[f], -np.einsum("mj,mj->m", Z[:, 3, :3], u) / zee, 0.0)
        a0 = np.concatenate([u, ph[:, None]], axis=-1)
        ref = np.where(np.abs(u[:, 1]) > 1e-8, u[:, 1], u[:, 0])
        a0 = a0 * (np.conj(ref) / np.abs(ref))[:, None]
        P = _flux(Q[f], R[f], E[f], r, a0, free[f], eps0[f])
        pfa[f] = np.degrees(np.arctan2(P[:, 1], P[:, 0]))
        pol[f, :3] = a0[:, :3]
        pol[f, 3] = a0[:, 3] * alpha[f]
        decay[f] = r["p"]
        ebar = np.trace(eps[f], axis1=1, axis2=2) / 3.0
        el = ebar * np.abs(pol[f, 3]) ** 2
        share[f] = el / (X[f] * sA[f] + el)
    return {
        "c": np.sqrt(X * sA / rho),
        "c_limit": np.sqrt(XL * sA / rho),
        "wave_type": wave_type,
        "reason": reason,
        "polarisation": pol,
        "potential_share": share,
        "decay": decay,
        "power_flow_angle": pfa,
        "method": np.full(m, "piezo-stroh", dtype=object),
    }


def coupling_coefficient(A, e, eps, rho, **kw) -> dict:
    """K^2 = 2 (c_free - c_metallized) / c_free with both speeds; dict of (m,) arrays."""
    rf = piezo_surface_wave(A, e, eps, rho, electrical="free", **kw)
    rm = piezo_surface_wave(A, e, eps, rho, electrical="metallized", **kw)
    return {"c_free": rf["c"], "c_metallized": rm["c"], "K2": 2 * (rf["c"] - rm["c"]) / rf["c"]}


def euler_lab_axes(phi, theta, psi) -> np.ndarray:
    """Our lab axes (rows x1, x2 inward, x3) in crystal axes from SAW Euler angles (degrees, ZXZ).

    SAW convention (IEEE Std 176): the SAW axes are the rows of Rz(psi) Rx(theta) Rz(phi)
    (passive rotations, first phi about Z, then theta about the new X, then psi about the new
    Z); SAW x1 = propagation, SAW x3 = outward normal. Ours: x1 = x1_SAW, x2 = -x3_SAW,
    x3 = x2_SAW. Scalars or arrays (broadcast) -> (..., 3, 3).
    """
    def rz(a):
        c, s = np.cos(a), np.sin(a)
        o, z = np.ones_like(a), np.zeros_like(a)
        return np.stack([np.stack([c, s, z], -1), np.stack([-s, c, z], -1), np.stack([z, z, o], -1)], -2)

    def rx(a):
        c, s = np.cos(a), np.sin(a)
        o, z = np.ones_like(a), np.zeros_like(a)
        return np.stack([np.stack([o, z, z], -1), np.stack([z, c, s], -1), np.stack([z, -s, c], -1)], -2)

    p, t, s = np.broadcast_arrays(*(np.radians(np.asarray(v, dtype=float)) for v in (phi, theta, psi)))
    Rs = rz(s) @ rx(t) @ rz(p)
    return np.stack([Rs[..., 0, :], -Rs[..., 2, :], Rs[..., 1, :]], axis=-2)
