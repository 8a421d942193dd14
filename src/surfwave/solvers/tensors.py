"""Elastic tensors: Voigt notation, crystal-class constructors, rotations.

Voigt indices pair the tensor indices as 1 = 11, 2 = 22, 3 = 33, 4 = 23, 5 = 13, 6 = 12
(0-based here: 0..5). Stiffnesses in Voigt form need no factors of 2 (C_IJ = C_ijkl).

Examples
--------
>>> C = cubic_voigt(168.4, 121.4, 75.4)           # copper, GPa
>>> T = voigt_to_tensor(C)
>>> float(T[0, 1, 0, 1]), float(T[0, 0, 1, 1])
(75.4, 121.4)
>>> bool(np.allclose(tensor_to_voigt(T), C))
True
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

#: Tensor index pairs of the six Voigt indices (0-based): 11, 22, 33, 23, 13, 12.
VOIGT_PAIRS = ((0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1))
#: VOIGT_INDEX[i, j]: the Voigt index of the tensor pair (i, j), shape (3, 3).
VOIGT_INDEX = np.array([[0, 5, 4], [5, 1, 3], [4, 3, 2]])


def voigt_to_tensor(C6: ArrayLike) -> np.ndarray:
    """Full stiffness C_ijkl from its Voigt matrix.

    Parameters
    ----------
    C6 : array_like, shape (..., 6, 6)
        Voigt stiffness (any units; returned in the same units).

    Returns
    -------
    ndarray, shape (..., 3, 3, 3, 3)
    """
    C6 = np.asarray(C6, dtype=float)
    if C6.shape[-2:] != (6, 6):
        raise ValueError(f"a Voigt stiffness has shape (..., 6, 6), got {C6.shape}")
    return C6[..., VOIGT_INDEX[:, :, None, None], VOIGT_INDEX[None, None, :, :]]


def tensor_to_voigt(C: ArrayLike) -> np.ndarray:
    """Voigt matrix C_IJ of a stiffness tensor, shape (..., 3, 3, 3, 3) -> (..., 6, 6)."""
    C = np.asarray(C, dtype=float)
    i = np.array([p[0] for p in VOIGT_PAIRS])
    j = np.array([p[1] for p in VOIGT_PAIRS])
    return C[..., i[:, None], j[:, None], i[None, :], j[None, :]]


def cubic_voigt(C11: ArrayLike, C12: ArrayLike, C44: ArrayLike) -> np.ndarray:
    """Voigt stiffness of a cubic crystal in its cube axes; scalars or arrays -> (..., 6, 6)."""
    C11, C12, C44 = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (C11, C12, C44)))
    C6 = np.zeros(C11.shape + (6, 6))
    for a in range(3):
        for b in range(3):
            C6[..., a, b] = C12
        C6[..., a, a] = C11
        C6[..., a + 3, a + 3] = C44
    return C6


def hexagonal_voigt(C11: ArrayLike, C12: ArrayLike, C13: ArrayLike, C33: ArrayLike, C44: ArrayLike) -> np.ndarray:
    """Voigt stiffness of a hexagonal (transversely isotropic) crystal, c axis along x3.

    C66 = (C11 - C12)/2. Scalars or arrays -> (..., 6, 6).
    """
    C11, C12, C13, C33, C44 = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (C11, C12, C13, C33, C44)))
    C6 = np.zeros(C11.shape + (6, 6))
    C6[..., 0, 0] = C6[..., 1, 1] = C11
    C6[..., 0, 1] = C6[..., 1, 0] = C12
    C6[..., 0, 2] = C6[..., 2, 0] = C6[..., 1, 2] = C6[..., 2, 1] = C13
    C6[..., 2, 2] = C33
    C6[..., 3, 3] = C6[..., 4, 4] = C44
    C6[..., 5, 5] = 0.5 * (C11 - C12)
    return C6


def rotate4(C: ArrayLike, R: ArrayLike) -> np.ndarray:
    """A fourth-rank tensor in rotated axes: C'_abcd = R_ai R_bj R_ck R_dl C_ijkl.

    Parameters
    ----------
    C : array_like, shape (..., 3, 3, 3, 3)
    R : array_like, shape (..., 3, 3)
        Rows are the new axes written in the old ones (orthonormal).

    Returns
    -------
    ndarray, shape broadcast of (..., 3, 3, 3, 3)
    """
    C = np.asarray(C, dtype=float)
    R = np.asarray(R, dtype=float)
    if C.ndim == 5 and C.shape[0] >= _STACKED_MIN and R.shape == C.shape[:1] + (3, 3) \
            and C.shape[1:] == (3, 3, 3, 3) and C.flags.c_contiguous and R.flags.c_contiguous:
        return stacked_rotate4(C, R)
    out = np.einsum("...ai,...ijkl->...ajkl", R, C)
    out = np.einsum("...bj,...ajkl->...abkl", R, out)
    out = np.einsum("...ck,...abkl->...abcl", R, out)
    return np.einsum("...dl,...abcl->...abcd", R, out)


#: Stack size from which :func:`rotate4` takes :func:`stacked_rotate4` (below it the einsum chain is faster).
_STACKED_MIN = 8
#: Order in which the three terms of each contraction of :func:`rotate4` are added: that of the
#: einsum chain (the first three run over an outer axis, in index order; the last runs over the
#: innermost, contiguous axis, where numpy's two-lane SIMD reduction adds terms 0 and 2 first).
_EINSUM_ORDER = ((0, 1, 2), (0, 1, 2), (0, 1, 2), (0, 2, 1))


def stacked_rotate4(C: np.ndarray, R: np.ndarray) -> np.ndarray:
    """:func:`rotate4` of m stacked tensors, the same numbers as its einsum chain, faster for large m.

    The four contractions R_ai C_ijkl, ... are written as products and sums of whole arrays
    with the batch axis last (long inner loops), each sum in the order the einsum chain adds
    its three terms (:data:`_EINSUM_ORDER`), and exact zeros given the einsum's sign (+0): so
    every entry has the same bits as the einsum chain's (checked in tests/solvers/test_tensors.py).

    Parameters
    ----------
    C : ndarray, shape (m, 3, 3, 3, 3)
        C-contiguous float64.
    R : ndarray, shape (m, 3, 3)
        C-contiguous float64; rows are the new axes in the old ones.

    Returns
    -------
    ndarray, shape (m, 3, 3, 3, 3)
    """
    m = C.shape[0]
    X = np.ascontiguousarray(C.reshape(m, 81).T).reshape(3, 3, 3, 3, m)
    Rt = np.ascontiguousarray(R.reshape(m, 9).T).reshape(3, 3, m)
    tmp = np.empty_like(X)
    for axis, order in enumerate(_EINSUM_ORDER):
        out = np.empty_like(X)
        shape = [1, 1, 1, 1, m]
        shape[axis] = 3
        for n, i in enumerate(order):
            Xi = X[(slice(None),) * axis + (slice(i, i + 1),)]
            np.multiply(Rt[:, i].reshape(shape), Xi, out=out if n == 0 else tmp)
            if n:
                out += tmp
        X = out
    X += 0.0                  # -0 -> +0: the einsum's sums start from +0
    return np.ascontiguousarray(X.reshape(81, m).T).reshape(m, 3, 3, 3, 3)


def cross(a: ArrayLike, b: ArrayLike) -> np.ndarray:
    """a x b of 3-vectors (..., 3), broadcasting: np.cross's products and differences in its order
    (the same numbers), without its generic set-up (a few microseconds a call on small arrays)."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    tmp = np.empty(out.shape[:-1])
    for c, (i, j) in enumerate(((1, 2), (2, 0), (0, 1))):
        np.multiply(a[..., i], b[..., j], out=out[..., c])
        np.multiply(a[..., j], b[..., i], out=tmp)
        out[..., c] -= tmp
    return out


def rotate2(s: ArrayLike, R: ArrayLike) -> np.ndarray:
    """A second-rank tensor in rotated axes: s'_ab = R_ai R_bj s_ij; shapes (..., 3, 3)."""
    return np.einsum("...ai,...ij,...bj->...ab", np.asarray(R, dtype=float), np.asarray(s, dtype=float),
                     np.asarray(R, dtype=float))
