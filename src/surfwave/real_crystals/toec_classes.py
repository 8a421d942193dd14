"""Third-order elastic constants of non-cubic classes from their independent Brugger constants.

The dependent components are not typed in: they follow from the point group. The Voigt
third-order tensors invariant under the class's generators
(:func:`surfwave.solvers.piezo_tensors.point_group_generators`, standard setting: Z the
three-fold axis, X a two-fold axis for class 32) form a linear subspace (14-dimensional for
class 32, Fumi, Phys. Rev. 86, 561 (1952)); :func:`trigonal_32_toec` returns the member of that
subspace whose 14 named components (Thurston, McSkimin and Andreatch, J. Appl. Phys. 37, 267
(1966): C111, C112, C113, C114, C123, C124, C133, C134, C144, C155, C222, C333, C344, C444) take
the given values.

No constant set for quartz is stored yet (it was not found in a stored source); the builder is
ready for one (materials ``piezoelectric.yaml``, with its axis setting checked against the
database's quartz: where two settings differ by the half turn about Z, as the signs of C14 and
e11 do between IEEE 1949 and 1978 for quartz, the components with an odd number of tensor
indices in X or Y change sign: C114, C124, C134, C444).

Examples
--------
>>> C3 = trigonal_32_toec(**{k: float(i + 1) for i, k in enumerate(TRIGONAL_32_TOEC)})
>>> round(float(C3[0, 0, 0]), 12), round(float(C3[3, 3, 3]), 12)   # C111, C444 as given
(1.0, 14.0)
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

from surfwave.errors import InputError
from surfwave.real_crystals.toec import toec_tensor
from surfwave.solvers.piezo_tensors import point_group_generators
from surfwave.solvers.tensors import VOIGT_PAIRS

__all__ = ["TRIGONAL_32_TOEC", "invariant_toec_basis", "rotate_toec", "trigonal_32_toec"]

#: The 14 independent Brugger constants of class 32 (Thurston, McSkimin and Andreatch 1966).
TRIGONAL_32_TOEC = ("C111", "C112", "C113", "C114", "C123", "C124", "C133", "C134", "C144", "C155", "C222",
                    "C333", "C344", "C444")
_PAIRS = np.array(VOIGT_PAIRS)
# the 56 independent Voigt components I <= J <= K
_TRIPLES = [(i, j, k) for i in range(6) for j in range(i, 6) for k in range(j, 6)]


def _from_triples(x) -> np.ndarray:
    """Fully symmetric Voigt (6, 6, 6) from its 56 components I <= J <= K."""
    out = np.zeros((6, 6, 6))
    for v, (i, j, k) in zip(x, _TRIPLES):
        for p in {(i, j, k), (i, k, j), (j, i, k), (j, k, i), (k, i, j), (k, j, i)}:
            out[p] = v
    return out


def rotate_toec(C3, R) -> np.ndarray:
    """Voigt third-order stiffness in rotated axes: C'_ijklmn = R_ia R_jb ... C_abcdef.

    Parameters
    ----------
    C3 : array_like, shape (6, 6, 6)
        Voigt, any units.
    R : array_like, shape (3, 3)
        Orthogonal matrix (rows: the new axes in old coordinates).

    Returns
    -------
    ndarray, shape (6, 6, 6)
    """
    T = toec_tensor(C3)
    R = np.asarray(R, dtype=float)
    T = np.einsum("ia,jb,kc,ld,me,nf,abcdef->ijklmn", R, R, R, R, R, R, T, optimize=True)
    P = _PAIRS
    return T[P[:, 0][:, None, None], P[:, 1][:, None, None], P[:, 0][None, :, None], P[:, 1][None, :, None],
             P[:, 0][None, None, :], P[:, 1][None, None, :]]


@lru_cache(maxsize=None)
def invariant_toec_basis(crystal_class: str) -> np.ndarray:
    """Orthonormal basis of the Voigt third-order tensors invariant under a point group.

    Parameters
    ----------
    crystal_class : str
        A class of :func:`surfwave.solvers.piezo_tensors.point_group_generators`.

    Returns
    -------
    ndarray, shape (n, 56)
        Rows span the invariant subspace, in the 56 components I <= J <= K (n = 14 for "32").
    """
    gens = point_group_generators(crystal_class)
    unit = np.eye(len(_TRIPLES))
    rows = []
    for g in gens:
        M = np.array([[rotate_toec(_from_triples(u), g)[t] for t in _TRIPLES] for u in unit]).T
        rows.append(M - unit)
    _, s, vt = np.linalg.svd(np.vstack(rows))
    return vt[np.sum(s > 1e-9 * s.max()):]


def trigonal_32_toec(**constants) -> np.ndarray:
    """Voigt third-order stiffness of a class-32 crystal (alpha-quartz) from its 14 constants.

    Parameters
    ----------
    **constants : float
        Every name of :data:`TRIGONAL_32_TOEC` (Brugger constants, GPa), standard setting (Z the
        three-fold axis, X a two-fold axis).

    Returns
    -------
    ndarray, shape (6, 6, 6)
        Fully symmetric, invariant under the 3-fold about Z and the 2-fold about X, with the
        given values at the named components.

    Raises
    ------
    InputError
        A missing, unknown or non-finite constant (named).
    """
    missing = [k for k in TRIGONAL_32_TOEC if k not in constants]
    unknown = [k for k in constants if k not in TRIGONAL_32_TOEC]
    if missing or unknown:
        raise InputError(f"class-32 third-order constants: missing {missing}, unknown {unknown}; "
                         f"give exactly {list(TRIGONAL_32_TOEC)}")
    values = np.array([float(constants[k]) for k in TRIGONAL_32_TOEC])
    if not np.all(np.isfinite(values)):
        raise InputError(f"class-32 third-order constants must be finite, got {dict(constants)}")
    B = invariant_toec_basis("32")                                  # (14, 56)
    cols = [_TRIPLES.index(tuple(int(c) - 1 for c in k[1:])) for k in TRIGONAL_32_TOEC]
    y = np.linalg.solve(B[:, cols].T, values)
    return _from_triples(y @ B)
