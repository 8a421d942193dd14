"""Leaky continuation of a stack's modes above the substrate's limiting speed (complex speed).

Above the limiting speed c_L1 of a family (the slowest bulk sheet's trace speed along x1) a mode
can only exist as a leaky wave: one partial wave of the substrate is the bulk wave of that sheet
carrying energy down into it. As in the half-space solver (:mod:`surfwave.solvers.leaky`), with a
real frequency and a wave decaying along x1, k = k_r (1 + i delta) with delta > 0, the complex
speed c = omega / k has Im c < 0; the outgoing bulk root then has a small negative Im p, the
incoming one a small positive Im p. The substrate's partial-wave set is therefore, in ascending
Im p: the outgoing root (position nf - 1) and the nf - 1 decaying ones (positions nf + 1 ...
2 nf - 1), the incoming root (position nf) and the growing ones excluded. The layers need no
choice (their formula holds for any split).

At a fixed real omega H (so kh = omega H / c is complex with c) the boundary function
F(c) = det(-i M_top) is analytic in c. Candidates are the minima of |F| on a grid of real
speeds in the window (c_L1, c_L2) (c_L2: the second sheet's limiting speed; a single-sheet
family: 1.6 c_L1), refined by the secant method in complex c; omega H is then reset so that
Re(k) h = the requested kh and the root is refined again (twice). A root is kept when it
converged, lies in the window, and decays along x1 (delta > 0). Reported: the phase speed
omega / k_r and the attenuation 40 pi log10(e) delta dB per wavelength.
"""
from __future__ import annotations

import numpy as np

from surfwave.layers.partial import Blocks, Family, eigen
from surfwave.layers.recursion import top_impedance
from surfwave.solvers.boundary import Boundary, as_boundary

__all__ = ["DB_PER_DELTA", "leaky_continuation", "leaky_roots"]

#: dB per wavelength per unit delta (as in surfwave.solvers.leaky).
DB_PER_DELTA = 40 * np.pi * np.log10(np.e)
#: Real-speed grid points in the window.
SCAN = 48
#: Secant iterations per solve; outer resets of omega H.
ITER = 40
OUTER = 3
#: Relative step in c below which a secant search has converged.
TOL = 1e-12


def _windows(b: Blocks, fam: Family) -> tuple[float, float]:
    """(c_L1, c_L2) of the family in the substrate, m/s.

    c_L2 is the fastest bulk speed along x1 (at most 1.6 c_L1): the range scanned; only its part
    with a single radiating sheet is used (:func:`_one_real_pair`).
    """
    c1 = float(np.sqrt(fam.X_limit * b.sA / b.rho[-1]))
    mech = [i for i in fam.idx if i < 3]
    ix = np.ix_(mech, mech)
    Q, R, T = b.Q[-1][ix], b.R[-1][ix], b.T[-1][ix]
    _ = (R, T)
    w = np.linalg.eigvalsh(Q)                                     # bulk waves along x1
    speeds = np.sqrt(np.clip(w, 0, None) * b.sA / b.rho[-1])
    above = speeds[speeds > c1 * (1 + 1e-3)]
    c2 = float(above.max()) if above.size else 1.6 * c1
    return c1, min(c2, 1.6 * c1)


def substrate_outgoing(b: Blocks, fam: Family, c) -> np.ndarray:
    """Substrate impedance M = B A^-1 (m, nf, nf) of the outgoing set at complex speeds c (m,), Im c < 0."""
    ix = np.ix_(fam.idx, fam.idx)
    nf = len(fam.idx)
    c = np.asarray(c, dtype=complex)
    p, V = eigen(b.Q[-1][ix], b.R[-1][ix], b.T[-1][ix], b.rho[-1] * c * c / b.sA, fam.mech)
    cols = np.array([nf - 1, *range(nf + 1, 2 * nf)])
    A, B = V[:, :nf, cols], V[:, nf:, cols]
    with np.errstate(all="ignore"):
        return np.swapaxes(np.linalg.solve(np.swapaxes(A, -1, -2), np.swapaxes(B, -1, -2)), -1, -2)


def _one_real_pair(b: Blocks, fam: Family, c) -> np.ndarray:
    """True where the substrate has exactly one real pair of Stroh roots at the real speeds c (m,)
    (one radiating sheet: the window of this solver; two pairs, e.g. between the oblique minimum and
    the on-axis value of a cuspidal sheet, need two outgoing waves and are left out)."""
    ix = np.ix_(fam.idx, fam.idx)
    c = np.asarray(c, dtype=float)
    p, _ = eigen(b.Q[-1][ix], b.R[-1][ix], b.T[-1][ix], b.rho[-1] * c * c / b.sA, fam.mech)
    real = np.abs(p.imag) <= 1e-7 * np.maximum(1.0, np.abs(p))
    return real.sum(axis=-1) == 2


def _F(b: Blocks, fam: Family, c, WH, electrical: str | Boundary) -> np.ndarray:
    """det of the boundary matrix at complex speeds c (m,) and omega H (m,) (kh = omega H / c)."""
    M = top_impedance(b, fam, c, (WH / c)[:, None], M_sub=substrate_outgoing(b, fam, c))["M"][:, 0]
    Z = -1j * M
    if fam.phi is not None:
        Z, _ = as_boundary(electrical).stack_matrix(Z, fam.phi, b.eps0)
    with np.errstate(all="ignore"):
        return np.linalg.det(Z)


def _secant(b, fam, c0, c1, WH, electrical):
    """Complex secant from (c0, c1) (m,) at fixed omega H; returns c (m,) and a converged flag."""
    f0, f1 = _F(b, fam, c0, WH, electrical), _F(b, fam, c1, WH, electrical)
    ok = np.zeros(c0.shape, dtype=bool)
    idx = np.arange(c0.size)
    out = c1.copy()
    for _ in range(ITER):
        if idx.size == 0:
            break
        with np.errstate(all="ignore"):
            step = -f1 * (c1 - c0) / (f1 - f0)
        big = np.abs(step) > 0.05 * np.abs(c1)
        step = np.where(big, step / np.abs(step) * 0.05 * np.abs(c1), step)
        c2 = c1 + step
        bad = ~np.isfinite(c2)
        f2 = _F(b, fam, np.where(bad, c1, c2), WH[idx], electrical)
        done = (np.abs(step) <= TOL * np.abs(c1)) & ~bad
        out[idx] = np.where(bad, np.nan, c2)
        ok[idx[done]] = True
        keep = ~done & ~bad & np.isfinite(f2)
        idx, c0, f0, c1, f1 = idx[keep], c1[keep], f1[keep], c2[keep], f2[keep]
    return out, ok


def leaky_roots(b: Blocks, fam: Family, kh: np.ndarray, electrical: str | Boundary = "free") -> list[np.ndarray]:
    """Complex speeds (m/s, Im c < 0) of the leaky modes of one family at each real kh = Re(k) H.

    Returns
    -------
    list of ndarray
        Per kh, the verified roots in ascending real part (empty where none).
    """
    c1, c2 = _windows(b, fam)
    w = np.linspace(0.0, 0.5 * np.pi, SCAN + 2)[1:-1]
    cg = np.sqrt(c1 * c1 + (c2 * c2 - c1 * c1) * np.sin(w) ** 2)
    single = _one_real_pair(b, fam, cg)
    CC, KK = np.meshgrid(cg, kh, indexing="ij")                          # (SCAN, k)
    cz = (CC * (1 - 1e-9j)).ravel()
    F = np.abs(_F(b, fam, cz, KK.ravel() * CC.ravel(), electrical)).reshape(CC.shape)
    F = np.where(np.isfinite(F) & single[:, None], F, np.inf)
    interior = (F[1:-1] < F[:-2]) & (F[1:-1] < F[2:])
    ic, ik = np.nonzero(interior)
    ic = ic + 1
    out: list[np.ndarray] = [np.zeros(0, dtype=complex) for _ in kh]
    if ic.size == 0:
        return out
    c_start = cg[ic]
    WH = kh[ik] * c_start
    c, ok = _secant(b, fam, c_start * (1 - 1e-4j), c_start * (1 - 2e-3j), WH, electrical)
    for _ in range(OUTER):
        good = ok & np.isfinite(c)
        WH = np.where(good, kh[ik] / np.real(1 / np.where(good, c, 1.0)), WH)
        c_new, ok2 = _secant(b, fam, np.where(good, c, c_start) * (1 + 1e-7j), np.where(good, c, c_start), WH,
                             electrical)
        c, ok = c_new, ok & ok2
    with np.errstate(all="ignore"):
        q = 1 / c
        phase = 1 / q.real
        delta = q.imag / q.real
    keep = ok & np.isfinite(c) & (phase > c1 * (1 + 1e-9)) & (phase < c2) & (delta > 1e-12)
    keep[keep] &= _one_real_pair(b, fam, phase[keep])
    for k in range(kh.size):
        sel = np.sort_complex(c[keep & (ik == k)])
        uniq: list[complex] = []
        for z in sel:
            if not any(abs(z - u) <= 1e-8 * abs(z) for u in uniq):
                uniq.append(z)
        out[k] = np.array(uniq, dtype=complex)
    return out


def leaky_continuation(sol: dict, kh: np.ndarray, electrical: str | Boundary, cs, vgs, k2s, att):
    """Append each family's leaky modes after its guided ones (phase speed, attenuation; v_g and K2 NaN).

    Returns
    -------
    cs, vgs, k2s, att, leaky : lists of (k, n_f') arrays per family; ``leaky`` is 1.0 where the
    entry is a leaky mode, 0.0 where guided, NaN where empty.
    """
    b = sol["blocks"]
    out_c, out_v, out_k, out_a, out_l = [], [], [], [], []
    for f, fam in enumerate(sol["families"]):
        roots = leaky_roots(b, fam, kh, electrical)
        ng = np.isfinite(cs[f]).sum(axis=1)
        width = max(int(max((ng[i] + len(r) for i, r in enumerate(roots)), default=0)), cs[f].shape[1])
        C = np.full((kh.size, width), np.nan)
        V, K, A, L = (np.full(C.shape, np.nan) for _ in range(4))
        n0 = cs[f].shape[1]
        C[:, :n0], V[:, :n0], K[:, :n0], A[:, :n0] = cs[f], vgs[f], k2s[f], att[f]
        L[:, :n0] = np.where(np.isfinite(cs[f]), 0.0, np.nan)
        for i, r in enumerate(roots):
            if r.size == 0:
                continue
            q = 1 / r
            cols = ng[i] + np.arange(r.size)
            C[i, cols] = 1 / q.real
            A[i, cols] = DB_PER_DELTA * q.imag / q.real
            L[i, cols] = 1.0
        out_c.append(C)
        out_v.append(V)
        out_k.append(K)
        out_a.append(A)
        out_l.append(L)
    return out_c, out_v, out_k, out_a, out_l
