"""Surface impedance of a layered half-space by the reflection-matrix (stiffness) recursion.

Lab frame x1 propagation, x2 inward normal; the top film's free surface is x2 = 0 and the films
follow downward, the substrate below them. In a layer of thickness t (in units of 1/k, i.e.
t = k h) the state [a; b] (displacement/potential and generalised traction on x2 = const,
divided by ik) is a sum of the 2n partial waves of :func:`surfwave.layers.partial.eigen`:

    [a; b](z) = V_d E_d(z) c_d + V_u E_u(z - t) c_u,   E(z) = diag exp(i p z),  0 <= z <= t,

the "down" waves (Im p >= 0) referred to the layer's top, the "up" ones (Im p <= 0) to its
bottom, so that every exponential that appears has modulus <= 1 at any thickness. Given the
impedance below the layer, b = M a at z = t, the up amplitudes follow from the down ones,
c_u = Rr c_d with Rr = -(B_u - M A_u)^-1 (B_d - M A_d) E_d(t), and at the top

    M_top = (B_d + B_u E_u(-t) Rr) (A_d + A_u E_u(-t) Rr)^-1.

Starting from the substrate's decaying waves (M = B_d A_d^-1) and going up layer by layer gives
the impedance of the whole stack at its free surface; Z = -i M_top is Hermitian for real speeds
below the substrate's limiting speed (no energy leaves the stack). A plain product of layer
transfer matrices exp(i t N) would carry exponentials exp(t |Im p|) and lose the decaying
information at large kh; this recursion never forms them (tests/layers/test_stability.py).

Boundary conditions at the top: mechanically free; electrically a
:class:`surfwave.solvers.boundary.Boundary` (or its name), which turns Z into the matrix of the
secular equation (:meth:`~surfwave.solvers.boundary.Boundary.stack_matrix`): free (the vacuum
above adds -EPS0 to the potential's diagonal: (Z - EPS0 e4 e4^T) a = 0) or metallized (phi = 0:
the mechanical block of Z).
"""
from __future__ import annotations

from typing import Any

import numpy as np

from surfwave.layers.linalg import safe_solve, safe_solve_right
from surfwave.layers.partial import Blocks, Family, eigen
from surfwave.solvers.boundary import FREE, METALLIZED, Boundary, as_boundary

__all__ = ["expi", "layer_eigs", "secular", "top_impedance"]


def layer_eigs(b: Blocks, fam: Family, c: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """Eigen-solutions (p, V) of every layer (top first) and the substrate (last) at speeds c (m,)."""
    ix = np.ix_(fam.idx, fam.idx)
    mech = fam.mech
    out = []
    for layer in range(b.Q.shape[0]):
        X = b.rho[layer] * c * c / b.sA
        out.append(eigen(b.Q[layer][ix], b.R[layer][ix], b.T[layer][ix], X, mech))
    return out


def expi(z: np.ndarray, decaying: bool) -> np.ndarray:
    """exp(i z); with ``decaying`` (Im z >= 0 up to rounding: real speeds) as exp(-Im z) (cos + i sin) of z's parts.

    The product form skips the complex exponential's special-value handling, which is not needed
    when |exp(i z)| <= 1 (about 30 % faster on the grid scan's (c, kh) arrays).
    """
    if not decaying or not np.iscomplexobj(z):
        return np.exp(1j * z)
    mag = np.exp(-z.imag)
    out = np.empty(z.shape, dtype=complex)
    out.real = mag * np.cos(z.real)
    out.imag = mag * np.sin(z.real)
    return out


def _solve_right(Y: np.ndarray, Xm: np.ndarray) -> np.ndarray:
    """Y Xm^-1 for stacks of square matrices (NaN where Xm is exactly singular)."""
    return safe_solve_right(Y, Xm)


def top_impedance(b: Blocks, fam: Family, c, kh, *, keep: bool = False, M_sub=None) -> dict:
    """Generalised impedance M_top (b = M a at the free surface) of the stack, family ``fam``.

    Parameters
    ----------
    b : Blocks
    fam : Family
    c : array_like, shape (m,)
        Phase speeds, m/s (below the family's limiting speed).
    kh : array_like, shape (m, k) or broadcastable
        Wavenumber times total film thickness for each speed.
    keep : bool
        Also return the per-layer quantities needed for the fields (:mod:`surfwave.layers.fields`).
    M_sub : ndarray, shape (m, nf, nf), optional
        The substrate's impedance (default: its decaying partial waves); the leaky continuation
        (:mod:`surfwave.layers.leaky`) passes the one of its outgoing set. ``c`` and ``kh`` may then
        be complex.

    Returns
    -------
    dict
        ``M`` (m, k, nf, nf) complex; with ``keep``: ``eigs`` (list of (p, V) per layer and the
        substrate), ``Rr`` and ``Xm`` (lists, per layer from the top, (m, k, nf, nf)) and ``t``
        (list of layer thicknesses k h_l, (m, k)).
    """
    c = np.atleast_1d(np.asarray(c))
    c = c.astype(np.result_type(c.dtype, float))
    real_c = not np.iscomplexobj(c) and M_sub is None
    kh = np.asarray(kh)
    kh = kh.astype(np.result_type(kh.dtype, float))
    kh = np.broadcast_to(kh.reshape(kh.shape + (1,) * (2 - kh.ndim)) if kh.ndim < 2 else kh,
                         (c.shape[0], np.shape(kh)[-1] if kh.ndim else 1))
    uc, inv = np.unique(c, return_inverse=True)
    if uc.size < c.size:                       # repeated speeds (e.g. bisection of one cell at many kh)
        eigs = [(p[inv], V[inv]) for p, V in layer_eigs(b, fam, uc)]
    else:
        eigs = layer_eigs(b, fam, c)
    nf = len(fam.idx)
    ps, Vs = eigs[-1]
    if M_sub is None:
        with np.errstate(all="ignore"):
            M = _solve_right(Vs[:, nf:, nf:], Vs[:, :nf, nf:])[:, None]      # (m, 1, nf, nf)
    else:
        M = np.asarray(M_sub)[:, None]
    # M stays (m, 1, nf, nf) while it depends on c only (the substrate's): the first film's
    # interface solve is then done once per speed and shared by every kh
    Rrs, Xms, ts = [], [], []
    for layer in range(len(b.frac) - 1, -1, -1):
        p, V = eigs[layer]
        t = kh * b.frac[layer]                                                 # (m, k)
        Ad, Bd, Au, Bu = (V[:, None, :nf, nf:], V[:, None, nf:, nf:], V[:, None, :nf, :nf], V[:, None, nf:, :nf])
        Ed = expi(p[:, None, nf:] * t[..., None], real_c)                     # (m, k, nf)
        Eu = expi(-p[:, None, :nf] * t[..., None], real_c)
        electrode = METALLIZED if b.electrode_below and b.electrode_below[layer] else FREE
        G = electrode.interface_rows(M, fam.phi) if fam.phi is not None else None
        if G is not None:
            # an electrode under this layer (surfwave.solvers.boundary.Metallized.interface_rows:
            # phi = 0 there, the mechanical state continuous)
            GVu = G[..., :, :nf] @ Au + G[..., :, nf:] @ Bu
            GVd = G[..., :, :nf] @ Ad + G[..., :, nf:] @ Bd
        else:
            GVu, GVd = Bu - M @ Au, Bd - M @ Ad
        with np.errstate(all="ignore"):
            if GVu.shape[-3] == 1 < t.shape[-1]:
                Rr = -safe_solve(GVu, GVd) * Ed[..., None, :]     # (GVu^-1 GVd) diag(Ed)
            else:
                Rr = -safe_solve(GVu, GVd * Ed[..., None, :])
            ER = Eu[..., :, None] * Rr
            XY = V[:, None, :, nf:] + V[:, None, :, :nf] @ ER               # [A_d; B_d] + [A_u; B_u] ER
            Xm = XY[..., :nf, :]
            M = _solve_right(XY[..., nf:, :], Xm)
        if keep:
            Rrs.append(Rr)
            Xms.append(Xm)
            ts.append(t)
    if M.shape[:-2] != kh.shape:
        M = np.broadcast_to(M, kh.shape + (nf, nf))
    out: dict[str, Any] = {"M": M}
    if keep:
        out.update(eigs=eigs, Rr=Rrs[::-1], Xm=Xms[::-1], t=ts[::-1])
    return out


def boundary_matrix(b: Blocks, fam: Family, M: np.ndarray, electrical: str | Boundary) -> tuple[np.ndarray, np.ndarray]:
    """The Hermitian matrix whose singularity is the free-surface condition, and its active components.

    Parameters
    ----------
    b : Blocks
    fam : Family
    M : ndarray, shape (..., nf, nf), complex
        The stack's impedance (:func:`top_impedance`).
    electrical : str or Boundary
        The top's condition (:func:`surfwave.solvers.boundary.as_boundary`).

    Returns
    -------
    Z : ndarray, shape (..., na, na)
        -i M (made exactly Hermitian), turned by the boundary's
        :meth:`~surfwave.solvers.boundary.Boundary.stack_matrix` (free: -EPS0 on the potential;
        metallized: the mechanical block).
    active : ndarray of int, shape (na,)
        Positions (within the family) of the components kept.
    """
    Z = -1j * M
    Z = 0.5 * (Z + np.conj(np.swapaxes(Z, -1, -2)))
    if fam.phi is None:
        return Z, np.arange(len(fam.idx))
    return as_boundary(electrical).stack_matrix(Z, fam.phi, b.eps0)


def boundary_eigenvalues(b: Blocks, fam: Family, c, kh, electrical: str | Boundary = "free") -> np.ndarray:
    """Eigenvalues (ascending) of the Hermitian boundary matrix at speeds c (m,) and kh (m, k), (m, k, na).

    Every eigenvalue decreases with c between poles (the impedance of a lossless stack is a
    reactance), so the number of negative eigenvalues rises by one at each mode and falls by one
    at each pole; :mod:`surfwave.layers.modes` uses this to tell modes from poles on its grid.
    """
    M = top_impedance(b, fam, c, kh)["M"]
    Z, _ = boundary_matrix(b, fam, M, electrical)
    with np.errstate(all="ignore"):
        bad = ~np.isfinite(Z).all(axis=(-1, -2))
        w = np.linalg.eigvalsh(np.where(bad[..., None, None], 0.0, Z))
    w[bad] = np.nan
    return w


def secular(b: Blocks, fam: Family, c, kh, electrical: str | Boundary = "free") -> np.ndarray:
    """Real secular function det(Z) of the family at speeds c (m,) and kh (m, k): zeros are guided modes.

    Z is Hermitian, so det Z is real; it changes sign at every mode and also at the poles of Z
    (speeds where the stack with a clamped top has a mode); :mod:`surfwave.layers.modes` tells
    them apart.

    Returns
    -------
    ndarray, shape (m, k), float (NaN where the evaluation failed)
    """
    M = top_impedance(b, fam, c, kh)["M"]
    Z, _ = boundary_matrix(b, fam, M, electrical)
    with np.errstate(all="ignore"):
        return np.linalg.det(Z).real
