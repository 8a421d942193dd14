"""Mode shapes, group velocity (energy velocity) and depth profiles of guided modes of a stack.

At a mode (c, kh) the free-surface vector a_top (null vector of the boundary matrix) fixes every
partial-wave amplitude: layer by layer from the top, c_d = Xm^-1 a_top, c_u = Rr c_d (the
recursion's matrices, :func:`surfwave.layers.recursion.top_impedance`), the displacement at the
layer's bottom starts the next layer, and the substrate's decaying amplitudes follow from it.

Group velocity. For a lossless guided mode the group velocity equals the energy velocity,
v_g = <P_1> / (2 <T>) (mean power flow along x1 over twice the mean kinetic energy, both per unit
width and integrated over depth; the electric enthalpy of a quasi-static piezoelectric medium
does not depend on omega, so the same ratio holds with the potential). With U = sum gamma_j v_j
e_j(z) in a layer, the generalised stress sigma_.1 = ik (Q + p R) a per partial wave and
z in units of 1/k:

    v_g / c = Re sum_layers sum_ij conj(g_i) g_j conj(a_i) . (Q + p_j R) a_j I_ij
              / sum_layers X_l sum_ij conj(g_i) g_j conj(a_i) . a_j|_mech I_ij,

I_ij = int conj(e_i) e_j dz in closed form; on a free piezoelectric surface the vacuum adds
-EPS0 |phi_top|^2 / 2 to the numerator. This is exact (no differencing); the tests compare it
with c + kh dc/dkh from finite differences.
"""
from __future__ import annotations

import numpy as np

from surfwave.layers.group_check import checked_group_velocity
from surfwave.layers.linalg import safe_solve
from surfwave.layers.partial import Blocks, Family
from surfwave.layers.recursion import boundary_matrix, top_impedance
from surfwave.solvers.boundary import Boundary, as_boundary

__all__ = ["mode_fields"]

#: Largest |eigenvalue| of the (dimensionless) boundary matrix at a mode whose surface vector counts
#: as resolved (its energy velocity is then taken without a check); well-resolved roots give 1e-13,
#: the trapped modes whose energy velocity was wrong 0.15 ... 0.2.
RESOLVED = 1e-9


def _overlap(p, e0, et, t) -> np.ndarray:
    """I_ij = int_0^t conj(e_i(z)) e_j(z) dz for e_j(z) = e0_j exp(i p_j z); e0, et: values at 0 and t.

    p, e0, et : (m, r); t : (m,) or None (semi-infinite: decaying waves). Returns (m, r, r).
    """
    D = p[:, None, :] - np.conj(p)[:, :, None]                      # p_j - conj(p_i)
    g0 = np.conj(e0)[:, :, None] * e0[:, None, :]
    if t is None:
        return g0 * (1j / D)
    gt = np.conj(et)[:, :, None] * et[:, None, :]
    tt = t[:, None, None]
    with np.errstate(all="ignore"):
        exact = (gt - g0) / (1j * D)
        x = 1j * D * tt
        series = g0 * tt * (1 + x / 2 + x * x / 6 + x ** 3 / 24)
    return np.where(np.abs(D * tt) < 1e-3, series, exact)


def mode_fields(b: Blocks, fam: Family, c, kh, electrical: str | Boundary = "free", depth=None,
                check: bool = True) -> dict:
    """Group velocity and (optionally) the depth profile of modes of one family.

    Parameters
    ----------
    b : Blocks
    fam : Family
    c, kh : array_like, shape (m,)
        Speeds (m/s) and kh of m modes.
    electrical : str or Boundary
        The top's electrical condition (:func:`surfwave.solvers.boundary.as_boundary`).
    depth : array_like, shape (d,), optional
        Depths below the free surface in units of the total film thickness (kh * depth = k x2);
        with it the profile U (m, d, nf) is returned (normalised to max |u| = 1).
    check : bool
        For modes whose boundary matrix has no eigenvalue below :data:`RESOLVED` (a zero on a
        pole: trapped under a barrier) or whose energy velocity is not finite, check the energy
        velocity against implicit differentiation of the secular eigenvalue and replace it by
        differences of c(kh) where it fails (:mod:`surfwave.layers.group_check`).

    Returns
    -------
    dict
        ``group_velocity`` (m,) m/s (the energy velocity along x1); ``power_flow_angle`` (m,)
        degrees, atan2(P3, P1) of the depth-integrated power flow (from x1 toward our x3 = the SAW
        frame's x2); ``a_top`` (m, nf) the surface vector; ``U`` (m, d, nf) complex with ``depth``.
    """
    c = np.atleast_1d(np.asarray(c, dtype=float))
    kh = np.atleast_1d(np.asarray(kh, dtype=float))
    m, nf = c.size, len(fam.idx)
    r = top_impedance(b, fam, c, kh[:, None], keep=True)
    Z, active = boundary_matrix(b, fam, r["M"][:, 0], electrical)
    bad = ~np.isfinite(Z).all(axis=(-1, -2))                             # a singular solve on the way (NaN)
    w, v = np.linalg.eigh(np.where(bad[:, None, None], np.eye(Z.shape[-1]), Z))
    v[bad] = np.nan
    j = np.argmin(np.abs(w), axis=-1)
    u = np.take_along_axis(v, j[:, None, None], axis=-1)[..., 0]
    a = np.zeros((m, nf), dtype=complex)
    a[:, active] = u
    a_top = a.copy()
    ix = np.ix_(fam.idx, fam.idx)
    mech = fam.mech
    num = np.zeros(m)
    num3 = np.zeros(m)
    den = np.zeros(m)
    if fam.phi is not None and as_boundary(electrical).vacuum:         # the field's energy above the top
        num -= 0.5 * b.eps0 * np.abs(a[:, fam.phi]) ** 2
    depth = None if depth is None else np.asarray(depth, dtype=float)
    U = None if depth is None else np.zeros((m, depth.size, nf), dtype=complex)
    z_top = np.zeros(m)                                                  # k x2 of the layer's top
    L = len(b.frac)
    for layer in range(L + 1):
        p, V = r["eigs"][layer]
        Q, R = b.Q[layer][ix], b.R[layer][ix]
        Q3, R3 = np.asarray(b.Q3)[layer][ix], np.asarray(b.R3)[layer][ix]
        X = b.rho[layer] * c * c / b.sA
        if layer < L:
            Xm, Rr, t = r["Xm"][layer][:, 0], r["Rr"][layer][:, 0], r["t"][layer][:, 0]
            cd = safe_solve(Xm, a[..., None])[..., 0]
            cu = (Rr @ cd[..., None])[..., 0]
            gam = np.concatenate([cu, cd], axis=-1)                      # order of p: up then down
            e0 = np.concatenate([np.exp(-1j * p[:, :nf] * t[:, None]), np.ones((m, nf))], axis=-1)
            et = np.concatenate([np.ones((m, nf)), np.exp(1j * p[:, nf:] * t[:, None])], axis=-1)
            I = _overlap(p, e0, et, t)
            Av = V[:, :nf, :]
            a = (Av @ (gam * et)[..., None])[..., 0]                     # displacement at the bottom
        else:
            Av = V[:, :nf, nf:]
            gam = safe_solve(Av, a[..., None])[..., 0]
            p = p[:, nf:]
            e0 = np.ones((m, nf), dtype=complex)
            I = _overlap(p, e0, e0, None)
            t = None
        S1 = Q[None, None] + p[:, :, None, None] * R[None, None]          # (m, r, nf, nf)
        Sa = np.einsum("mjkl,mlj->mkj", S1, Av)                           # (Q + p_j R) a_j
        G = np.einsum("mki,mkj->mij", np.conj(Av), Sa)
        K = np.einsum("mki,mkj->mij", np.conj(Av) * mech[None, :, None], Av)
        gg = np.conj(gam)[:, :, None] * gam[:, None, :]
        num += np.einsum("mij,mij->m", gg, G * I).real
        S3 = Q3[None, None] + p[:, :, None, None] * R3[None, None]
        G3 = np.einsum("mki,mkj->mij", np.conj(Av), np.einsum("mjkl,mlj->mkj", S3, Av))
        num3 += np.einsum("mij,mij->m", gg, G3 * I).real
        den += X * np.einsum("mij,mij->m", gg, K * I).real
        if U is not None:
            zl = depth[None, :] * kh[:, None] - z_top[:, None]            # (m, d) local k z
            tl = np.inf if t is None else t[:, None]
            inside = (zl >= 0) & (zl <= tl) if layer < L else zl >= 0
            if layer < L:
                ph = np.concatenate([np.exp(1j * p[:, None, :nf] * (zl - t[:, None])[..., None]),
                                     np.exp(1j * p[:, None, nf:] * zl[..., None])], axis=-1)
            else:
                ph = np.exp(1j * p[:, None, :] * np.maximum(zl, 0)[..., None])
            val = np.einsum("mkr,mdr->mdk", Av, gam[:, None, :] * ph)
            U = np.where(inside[..., None], val, U)
        if t is not None:
            z_top = z_top + t
    with np.errstate(all="ignore"):
        vg = c * num / den
    if check:
        # a mode trapped under a barrier: its zero of the boundary matrix sits on a pole, the
        # matrix has no small eigenvalue at the root and its null vector (the surface vector) is
        # not resolved; check those (and failed ones) against differences (surfwave.layers.group_check)
        sus = ~(np.abs(w).min(axis=-1) <= RESOLVED) | ~np.isfinite(vg)
        if sus.any():
            vg[sus] = checked_group_velocity(b, fam, c[sus], kh[sus], vg[sus], electrical,
                                             np.where(bad[:, None], np.nan, w)[sus])
    out = {"group_velocity": vg, "a_top": a_top,
           "power_flow_angle": np.degrees(np.arctan2(num3, num))}
    if U is not None:
        scale = np.abs(U[..., :3] if nf > 3 else U).max(axis=(1, 2), keepdims=True)
        out["U"] = U / np.where(scale > 0, scale, 1)
    return out
