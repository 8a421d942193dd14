"""Piezoelectric crystal tensors: class constructors, point-group generators, rotations, bulk waves.

Conventions (docs/piezoelectric-materials.md)
---------------------------------------------
* Voigt pairs as in :mod:`surfwave.solvers.tensors`: 1 = 11, 2 = 22, 3 = 33, 4 = 23, 5 = 13,
  6 = 12. Stiffness C_IJ = C_ijkl; piezoelectric stress constants e_kI = e_kij with NO factor 2
  (e_k(ij) = e_kI for i != j too), so T_ij = C_ijkl u_k,l + e_kij phi,k and
  D_j = e_jkl u_k,l - eps_jl phi,l.
* Standard settings (IEEE Std 176-1987 / Nye):
  - 3m (LiNbO3, LiTaO3): x3 = Z along the 3-fold axis, the mirror plane is the YZ plane (mirror
    perpendicular to crystal X), so every tensor is invariant under x -> -x; X is then NOT a
    2-fold axis. Non-zero e: e15 = e24, e22 = -e21 = -e16, e31 = e32, e33.
  - 32 (alpha-quartz, langasite): x3 = Z along the 3-fold axis, X along a 2-fold axis.
    Non-zero e: e11 = -e12 = -e26, e14 = -e25.
  - 6mm (AlN, ZnO, GaN): x3 = c axis; e15 = e24, e31 = e32, e33.
  - -43m (GaAs): cube axes; e14 = e25 = e36.
  - Trigonal stiffness (classes 3m, 32, -3m): C11, C12, C13, C14, C33, C44 with
    C22 = C11, C23 = C13, C24 = -C14, C55 = C44, C56 = C14, C66 = (C11 - C12)/2. The same form
    serves 3m (mirror perpendicular to X) and 32 (2-fold along X): both contain the 2-fold about X
    once inversion is added (Laue class -3m).

Examples
--------
>>> e = trigonal_3m_piezo(3.7, 2.5, 0.2, 1.3)          # LiNbO3, Warner 1967, C/m^2
>>> bool(is_invariant(piezo_voigt_to_tensor(e), point_group_generators("3m")))
True
"""
from __future__ import annotations

from typing import Iterable

import numpy as np
from numpy.typing import ArrayLike

from surfwave.errors import InputError
from surfwave.solvers.tensors import VOIGT_INDEX, VOIGT_PAIRS, cubic_voigt, hexagonal_voigt

#: Vacuum permittivity, F/m (CODATA 2018).
EPS0 = 8.8541878128e-12


def _arrays(*values: ArrayLike) -> tuple[np.ndarray, ...]:
    return np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in values))


def trigonal_3m_voigt(C11: ArrayLike, C12: ArrayLike, C13: ArrayLike, C14: ArrayLike, C33: ArrayLike,
                      C44: ArrayLike) -> np.ndarray:
    """Voigt stiffness of a trigonal crystal of class 3m (or 32, -3m), standard setting.

    Parameters
    ----------
    C11, C12, C13, C14, C33, C44 : float or array_like
        Independent constants (any unit, returned in the same; GPa in the database).

    Returns
    -------
    ndarray, shape (..., 6, 6)
        C66 = (C11 - C12)/2, C24 = -C14, C56 = C14 (mirror perpendicular to X or 2-fold along X).
    """
    C11, C12, C13, C14, C33, C44 = _arrays(C11, C12, C13, C14, C33, C44)
    C6 = np.zeros(C11.shape + (6, 6))
    C6[..., 0, 0] = C6[..., 1, 1] = C11
    C6[..., 0, 1] = C6[..., 1, 0] = C12
    C6[..., 0, 2] = C6[..., 2, 0] = C6[..., 1, 2] = C6[..., 2, 1] = C13
    C6[..., 0, 3] = C6[..., 3, 0] = C14
    C6[..., 1, 3] = C6[..., 3, 1] = -C14
    C6[..., 4, 5] = C6[..., 5, 4] = C14
    C6[..., 2, 2] = C33
    C6[..., 3, 3] = C6[..., 4, 4] = C44
    C6[..., 5, 5] = 0.5 * (C11 - C12)
    return C6


#: Class 32 has the same stiffness form as 3m in the standard setting (X a 2-fold axis).
trigonal_32_voigt = trigonal_3m_voigt


def hexagonal_6mm_voigt(C11: ArrayLike, C12: ArrayLike, C13: ArrayLike, C33: ArrayLike, C44: ArrayLike) -> np.ndarray:
    """Voigt stiffness of a hexagonal crystal (6mm and every hexagonal class), c along x3."""
    return hexagonal_voigt(C11, C12, C13, C33, C44)


def cubic_43m_voigt(C11: ArrayLike, C12: ArrayLike, C44: ArrayLike) -> np.ndarray:
    """Voigt stiffness of a cubic crystal (-43m and every cubic class), cube axes."""
    return cubic_voigt(C11, C12, C44)


def trigonal_3m_piezo(e15: ArrayLike, e22: ArrayLike, e31: ArrayLike, e33: ArrayLike) -> np.ndarray:
    """Piezoelectric stress constants of class 3m, mirror perpendicular to X (IEEE setting).

    Returns
    -------
    ndarray, shape (..., 3, 6)
        ``[[0, 0, 0, 0, e15, -e22], [-e22, e22, 0, e15, 0, 0], [e31, e31, e33, 0, 0, 0]]``, C/m^2.
    """
    e15, e22, e31, e33 = _arrays(e15, e22, e31, e33)
    e = np.zeros(e15.shape + (3, 6))
    e[..., 0, 4] = e15
    e[..., 0, 5] = -e22
    e[..., 1, 0] = -e22
    e[..., 1, 1] = e22
    e[..., 1, 3] = e15
    e[..., 2, 0] = e[..., 2, 1] = e31
    e[..., 2, 2] = e33
    return e


def trigonal_32_piezo(e11: ArrayLike, e14: ArrayLike) -> np.ndarray:
    """Piezoelectric stress constants of class 32, X along a 2-fold axis (IEEE setting).

    Returns
    -------
    ndarray, shape (..., 3, 6)
        ``[[e11, -e11, 0, e14, 0, 0], [0, 0, 0, 0, -e14, -e11], [0, 0, 0, 0, 0, 0]]``, C/m^2.
    """
    e11, e14 = _arrays(e11, e14)
    e = np.zeros(e11.shape + (3, 6))
    e[..., 0, 0] = e11
    e[..., 0, 1] = -e11
    e[..., 0, 3] = e14
    e[..., 1, 4] = -e14
    e[..., 1, 5] = -e11
    return e


def hexagonal_6mm_piezo(e15: ArrayLike, e31: ArrayLike, e33: ArrayLike) -> np.ndarray:
    """Piezoelectric stress constants of class 6mm (wurtzite), c along x3; shape (..., 3, 6)."""
    e15, e31, e33 = _arrays(e15, e31, e33)
    e = np.zeros(e15.shape + (3, 6))
    e[..., 0, 4] = e[..., 1, 3] = e15
    e[..., 2, 0] = e[..., 2, 1] = e31
    e[..., 2, 2] = e33
    return e


def cubic_43m_piezo(e14: ArrayLike) -> np.ndarray:
    """Piezoelectric stress constants of class -43m (zinc blende), cube axes; shape (..., 3, 6)."""
    (e14,) = _arrays(e14)
    e = np.zeros(e14.shape + (3, 6))
    e[..., 0, 3] = e[..., 1, 4] = e[..., 2, 5] = e14
    return e


def uniaxial_eps(eps11: ArrayLike, eps33: ArrayLike) -> np.ndarray:
    """Permittivity of a uniaxial crystal (trigonal, hexagonal), optic axis x3; shape (..., 3, 3)."""
    eps11, eps33 = _arrays(eps11, eps33)
    eps = np.zeros(eps11.shape + (3, 3))
    eps[..., 0, 0] = eps[..., 1, 1] = eps11
    eps[..., 2, 2] = eps33
    return eps


def piezo_voigt_to_tensor(e6: ArrayLike) -> np.ndarray:
    """e_kij from the Voigt e_kI (e_k(ij) = e_kI, no factors 2); (..., 3, 6) -> (..., 3, 3, 3)."""
    e6 = np.asarray(e6, dtype=float)
    if e6.shape[-2:] != (3, 6):
        raise InputError(f"a Voigt piezoelectric matrix has shape (..., 3, 6), got {e6.shape}")
    return e6[..., :, VOIGT_INDEX]


def piezo_tensor_to_voigt(e: ArrayLike) -> np.ndarray:
    """Voigt e_kI of a piezoelectric tensor e_kij; (..., 3, 3, 3) -> (..., 3, 6)."""
    e = np.asarray(e, dtype=float)
    i = np.array([p[0] for p in VOIGT_PAIRS])
    j = np.array([p[1] for p in VOIGT_PAIRS])
    return e[..., :, i, j]


def rotate3(e: ArrayLike, R: ArrayLike) -> np.ndarray:
    """A third-rank tensor in rotated axes: e'_abc = R_ai R_bj R_ck e_ijk.

    Parameters
    ----------
    e : array_like, shape (..., 3, 3, 3)
    R : array_like, shape (..., 3, 3)
        Rows are the new axes in the old ones. A polar tensor (e) takes improper R as they are.
    """
    return np.einsum("...ai,...bj,...ck,...ijk->...abc", np.asarray(R, dtype=float),
                     np.asarray(R, dtype=float), np.asarray(R, dtype=float), np.asarray(e, dtype=float))


def _rot(axis, angle_deg: float) -> np.ndarray:
    """Active rotation by ``angle_deg`` about the unit vector ``axis`` (Rodrigues)."""
    n = np.asarray(axis, dtype=float)
    n = n / np.linalg.norm(n)
    a = np.radians(angle_deg)
    K = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    return np.eye(3) + np.sin(a) * K + (1 - np.cos(a)) * K @ K


def _mirror(normal) -> np.ndarray:
    n = np.asarray(normal, dtype=float)
    n = n / np.linalg.norm(n)
    return np.eye(3) - 2 * np.outer(n, n)


def point_group_generators(crystal_class: str) -> list[np.ndarray]:
    """Generators of a point group in its standard setting (see the module docstring).

    Parameters
    ----------
    crystal_class : {"3m", "32", "6mm", "-43m"}

    Returns
    -------
    list of ndarray, each shape (3, 3)
        Orthogonal matrices (improper for mirrors and -4); a tensor of the class is invariant
        under each.
    """
    gens = {
        "3m": [_rot([0, 0, 1], 120.0), _mirror([1, 0, 0])],
        "32": [_rot([0, 0, 1], 120.0), _rot([1, 0, 0], 180.0)],
        "6mm": [_rot([0, 0, 1], 60.0), _mirror([1, 0, 0])],
        "-43m": [-_rot([0, 0, 1], 90.0), _rot([1, 1, 1], 120.0), _mirror([1, -1, 0])],
    }
    if crystal_class not in gens:
        raise InputError(f"unknown crystal class {crystal_class!r}; known: {sorted(gens)}")
    return gens[crystal_class]


def invariance_residual(tensor: ArrayLike, generators: Iterable[np.ndarray]) -> float:
    """Largest |T' - T| over the generators, for a tensor of rank 2, 3 or 4 (shape (3,)*rank)."""
    T = np.asarray(tensor, dtype=float)
    worst = 0.0
    for g in generators:
        if T.ndim == 2:
            Tp = np.einsum("ai,bj,ij->ab", g, g, T)
        elif T.ndim == 3:
            Tp = rotate3(T, g)
        elif T.ndim == 4:
            Tp = np.einsum("ai,bj,ck,dl,ijkl->abcd", g, g, g, g, T)
        else:
            raise InputError(f"invariance_residual takes rank 2, 3 or 4, got shape {T.shape}")
        worst = max(worst, float(np.max(np.abs(Tp - T))))
    return worst


def is_invariant(tensor: ArrayLike, generators: Iterable[np.ndarray], rtol: float = 1e-12) -> bool:
    """Whether a tensor is unchanged by every generator, to ``rtol`` of its largest entry."""
    T = np.asarray(tensor, dtype=float)
    return invariance_residual(T, generators) <= rtol * max(float(np.max(np.abs(T))), 1e-300)


def stiffened_bulk_speeds(C: ArrayLike, e: ArrayLike, eps: ArrayLike, rho: ArrayLike,
                          n: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Bulk (plane) wave speeds of a piezoelectric crystal along ``n``, quasi-static field.

    Christoffel tensor with piezoelectric stiffening:
    G_ik = C_ijkl n_j n_l + g_i g_k / (n . eps . n), g_i = e_pij n_p n_j.

    Parameters
    ----------
    C : array_like, shape (..., 3, 3, 3, 3)
        Stiffness, Pa.
    e : array_like, shape (..., 3, 3, 3)
        Piezoelectric stress constants e_kij, C/m^2.
    eps : array_like, shape (..., 3, 3)
        Permittivity, F/m (absolute).
    rho : float or array_like, shape (...)
        Density, kg/m^3.
    n : array_like, shape (..., 3)
        Propagation direction (normalised here).

    Returns
    -------
    speeds : ndarray, shape (..., 3)
        m/s, ascending.
    polarisations : ndarray, shape (..., 3, 3)
        Column k is the displacement of speed k.
    """
    u = np.asarray(n, dtype=float)
    u = u / np.linalg.norm(u, axis=-1, keepdims=True)
    C, e, eps = (np.asarray(a, dtype=float) for a in (C, e, eps))
    G = np.einsum("...ijkl,...j,...l->...ik", C, u, u)
    g = np.einsum("...pij,...p,...j->...i", e, u, u)
    en = np.einsum("...p,...pq,...q->...", u, eps, u)
    G = G + g[..., :, None] * g[..., None, :] / en[..., None, None]
    w, v = np.linalg.eigh(G)
    return np.sqrt(w / np.asarray(rho, dtype=float)[..., None]), v
