"""Stability of a stressed crystal against homogeneous deformation: Wallace's tensor and the Born checks.

B_ijkl = C_ijkl + (d_ik s_jl + d_jk s_il + d_il s_jk + d_jl s_ik - 2 d_kl s_ij)/2 (Wallace; Wang,
Yip, Phillpot and Wolf 1993), with C the constants of the stressed state and s its Cauchy stress,
both in GPa and in the same axes; the crystal is stable where B (Voigt form, symmetrised) is
positive definite. With s = 0 it is the natural crystal's Born criterion on C.

These checks serve the stressed states of :mod:`surfwave.real_crystals.toec` and the case check
of :mod:`surfwave.case` (one wording of a failure: :func:`born_reason`).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from surfwave.solvers.tensors import VOIGT_PAIRS, tensor_to_voigt

__all__ = ["PD_MARGIN", "born_lowest", "born_reason", "born_stable", "lowest_if_needed", "wallace_tensor"]

_VI = np.array([p[0] for p in VOIGT_PAIRS])
_VJ = np.array([p[1] for p in VOIGT_PAIRS])
# Kronecker deltas of :func:`wallace_tensor` on the Voigt pairs (ij), (km): d_ik, d_jk, d_im, d_jm, d_km, (6, 6)
_WALLACE_DELTAS = tuple(np.eye(3)[a, b] for a, b in ((_VI[:, None], _VI[None, :]), (_VJ[:, None], _VI[None, :]),
                                                     (_VI[:, None], _VJ[None, :]), (_VJ[:, None], _VJ[None, :]),
                                                     (_VI[None, :], _VJ[None, :])))


def wallace_tensor(C: ArrayLike, sigma: ArrayLike) -> np.ndarray:
    """Wallace's stability tensor of a stressed crystal, Voigt form, symmetrised.

    B_ijkl = C_ijkl + (d_ik s_jl + d_jk s_il + d_il s_jk + d_jl s_ik - 2 d_kl s_ij)/2
    (Wallace; Wang, Yip, Phillpot and Wolf 1993), with C the constants of the stressed state.
    The stressed crystal is stable against homogeneous deformation where it is positive definite.

    Parameters
    ----------
    C : array_like, shape (..., 3, 3, 3, 3)
    sigma : array_like, shape (..., 3, 3)

    Returns
    -------
    ndarray, shape (..., 6, 6)
    """
    sigma = np.asarray(sigma, dtype=float)
    # the 36 Voigt entries only (the same products and sums as the full tensor, term by term)
    i, j = _VI[:, None], _VJ[:, None]
    k, m = _VI[None, :], _VJ[None, :]
    d_ik, d_jk, d_im, d_jm, d_km = _WALLACE_DELTAS
    B6 = tensor_to_voigt(C) + 0.5 * (
        d_ik * sigma[..., j, m] + d_jk * sigma[..., i, m]
        + d_im * sigma[..., j, k] + d_jm * sigma[..., i, k]
        - 2 * (d_km * sigma[..., i, j]))
    return 0.5 * (B6 + np.swapaxes(B6, -1, -2))


def born_lowest(C: ArrayLike, sigma: ArrayLike) -> np.ndarray:
    """Lowest eigenvalue of Wallace's stability tensor (:func:`wallace_tensor`), GPa.

    Parameters
    ----------
    C : array_like, shape (..., 3, 3, 3, 3)
        Constants of the stressed state, GPa.
    sigma : array_like, shape (..., 3, 3)
        Cauchy stress, GPa, same axes.

    Returns
    -------
    ndarray, shape (...)
    """
    return np.linalg.eigvalsh(wallace_tensor(C, sigma))[..., 0]


#: Margin of the positive-definiteness certificate of :func:`lowest_if_needed`: LAPACK Cholesky of
#: M - margin max|M| I, far above the ~1e-15 max|M| by which rounding moves an eigenvalue.
PD_MARGIN = 1e-9


def lowest_if_needed(M: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Whether the lowest eigenvalue of each symmetric 6 x 6 matrix is positive, and that eigenvalue
    where it is needed to say by how much it is not.

    The flags are those of ``np.linalg.eigvalsh(M)[..., 0] > 0``. A sufficient test first: where
    LAPACK's Cholesky factorisation of M - :data:`PD_MARGIN` max|M| I succeeds for the whole stack,
    every lowest eigenvalue exceeds 1e-9 max|M| less rounding (~1e-15 max|M|), so eigvalsh (as
    accurate) finds it positive too, and no eigenvalue is computed (5x cheaper). Otherwise
    eigvalsh decides, as before. Both read the lower triangle.

    Parameters
    ----------
    M : ndarray, shape (n, 6, 6)
        Finite symmetric matrices (GPa).

    Returns
    -------
    positive : ndarray of bool, shape (n,)
    lowest : ndarray, shape (n,)
        The lowest eigenvalue (eigvalsh) where the sufficient test did not decide; NaN where it did.
    """
    n = M.shape[0]
    if n:
        scale = np.abs(M).max(axis=(-2, -1))
        try:
            np.linalg.cholesky(M - (PD_MARGIN * scale)[:, None, None] * np.eye(M.shape[-1]))
            return np.ones(n, dtype=bool), np.full(n, np.nan)
        except np.linalg.LinAlgError:
            pass
    lowest = np.linalg.eigvalsh(M)[..., 0]
    return lowest > 0, lowest


def born_stable(C: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    """Born (Wallace) stability of a prestressed crystal: the stability tensor is positive definite.

    B_ijkl = C_ijkl + (d_ik s_jl + d_jk s_il + d_il s_jk + d_jl s_ik - 2 d_kl s_ij)/2 (Wallace;
    Wang, Yip, Phillpot and Wolf 1993), symmetrised, in Voigt form; d = Kronecker delta.

    Parameters
    ----------
    C : ndarray, shape (..., 3, 3, 3, 3)
    sigma : ndarray, shape (..., 3, 3)

    Returns
    -------
    ndarray of bool, shape (...)
    """
    return born_lowest(C, sigma) > 0


def born_reason(lowest: float) -> str:
    """The one wording of a Born failure, given the lowest eigenvalue of Wallace's B (GPa)."""
    return ("stressed crystal not Born-stable (lowest eigenvalue of Wallace's B = C* + stress terms: "
            f"{lowest:.3g} GPa)")
