"""Third-order elastic constants of non-cubic classes from their independent Brugger constants.

The dependent components are not typed in: they follow from the point group. The Voigt
third-order tensors invariant under the class's generators
(:func:`surfwave.solvers.piezo_tensors.point_group_generators`, standard setting: Z the
three-fold axis, X a two-fold axis for class 32) form a linear subspace (14-dimensional for
class 32, Fumi, Phys. Rev. 86, 561 (1952)); :func:`trigonal_32_toec` returns the member of that
subspace whose 14 named components (Thurston, McSkimin and Andreatch, J. Appl. Phys. 37, 267
(1966): C111, C112, C113, C114, C123, C124, C133, C134, C144, C155, C222, C333, C344, C444) take
the given values.

:func:`toec_from_named` does the same for every class the piezoelectric database uses
(:data:`TOEC_NAMES`: 14 constants for 32 and 3m, 10 for 6mm, 6 for -43m), and
:func:`checked_toec` checks a user's full (6, 6, 6) array: finite, fully symmetric and, where
the crystal class is known, invariant under its point group (a function that assumes a
symmetry checks it).

No constant set for quartz or LiNbO3 is stored yet (none was found in a stored source); a user
who has one passes it to ``surfwave.material(..., toec=...)`` as a dict of the named constants
or a Voigt array, in the setting of the database's second-order set: where two settings differ
by the half turn about Z, as the signs of C14 and e11 of quartz do between IEEE 1949 and 1978,
the components with an odd number of tensor indices in X or Y change sign: C114, C124, C134,
C444. :func:`surfwave.real_crystals.toec.pressure_derivatives` checks a set against measured
pressure derivatives (docs/physics/third-order-constants.md).

Examples
--------
>>> C3 = trigonal_32_toec(**{k: float(i + 1) for i, k in enumerate(TRIGONAL_32_TOEC)})
>>> round(float(C3[0, 0, 0]), 12), round(float(C3[3, 3, 3]), 12)   # C111, C444 as given
(1.0, 14.0)
"""
from __future__ import annotations

from functools import lru_cache
from typing import Mapping

import numpy as np
from numpy.typing import ArrayLike

from surfwave.errors import InputError
from surfwave.real_crystals.toec import toec_tensor
from surfwave.solvers.piezo_tensors import point_group_generators
from surfwave.solvers.tensors import VOIGT_PAIRS
from surfwave.validate import MAX_CONSTANT_GPA

__all__ = ["HEXAGONAL_6MM_TOEC", "INVARIANCE_TOL", "MAX_TOEC_GPA", "TOEC_NAMES", "TRIGONAL_32_TOEC", "checked_toec",
           "invariant_toec_basis", "rotate_toec", "toec_from_named", "toec_from_user", "trigonal_32_toec"]

#: The 14 independent Brugger constants of class 32 (Thurston, McSkimin and Andreatch 1966).
TRIGONAL_32_TOEC = ("C111", "C112", "C113", "C114", "C123", "C124", "C133", "C134", "C144", "C155", "C222",
                    "C333", "C344", "C444")
#: The 10 independent Brugger constants of a hexagonal crystal (6mm: AlN, ZnO, GaN).
HEXAGONAL_6MM_TOEC = ("C111", "C112", "C113", "C123", "C133", "C144", "C155", "C222", "C333", "C344")
#: The independent constants by which each class's third-order stiffness is given (3m: the same
#: 14 names as 32, as Cho and Yamanouchi tabulate LiNbO3; -43m: the cubic six).
TOEC_NAMES = {"32": TRIGONAL_32_TOEC, "3m": TRIGONAL_32_TOEC, "6mm": HEXAGONAL_6MM_TOEC,
              "-43m": ("C111", "C112", "C123", "C144", "C155", "C456")}
#: Largest |third-order constant| accepted, GPa (diamond's are about 1e4; larger values are in Pa).
MAX_TOEC_GPA = MAX_CONSTANT_GPA
#: Largest departure from the class's invariant subspace accepted in a user's array, relative to
#: its largest component (rounding of typed components is far below; a wrong sign is not).
INVARIANCE_TOL = 1e-6
_PAIRS = np.array(VOIGT_PAIRS)
# the 56 independent Voigt components I <= J <= K
_TRIPLES: list[tuple[int, ...]] = [(i, j, k) for i in range(6) for j in range(i, 6) for k in range(j, 6)]


def _from_triples(x) -> np.ndarray:
    """Fully symmetric Voigt (6, 6, 6) from its 56 components I <= J <= K."""
    out = np.zeros((6, 6, 6))
    for v, (i, j, k) in zip(x, _TRIPLES):
        for p in {(i, j, k), (i, k, j), (j, i, k), (j, k, i), (k, i, j), (k, j, i)}:
            out[p] = v
    return out


def rotate_toec(C3: ArrayLike, R: ArrayLike) -> np.ndarray:
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


def toec_from_named(crystal_class: str, constants: Mapping[str, float]) -> np.ndarray:
    """Voigt third-order stiffness of a crystal class from its independent named constants.

    Parameters
    ----------
    crystal_class : {"32", "3m", "6mm", "-43m"}
        Point group, standard setting (:func:`surfwave.solvers.piezo_tensors.point_group_generators`).
    constants : mapping of str to float
        Exactly the names of :data:`TOEC_NAMES` ``[crystal_class]`` (Brugger constants, GPa).

    Returns
    -------
    ndarray, shape (6, 6, 6)
        Fully symmetric, invariant under the class's generators, with the given values at the
        named components.

    Raises
    ------
    InputError
        An unknown class, a missing, unknown, boolean or non-finite constant (named), values
        beyond :data:`MAX_TOEC_GPA` (Pa).
    """
    if crystal_class not in TOEC_NAMES:
        raise InputError(f"third-order constants by name: crystal class {crystal_class!r} not one of "
                         f"{sorted(TOEC_NAMES)}; give a (6, 6, 6) Voigt array instead")
    names = TOEC_NAMES[crystal_class]
    missing = [k for k in names if k not in constants]
    unknown = [k for k in constants if k not in names]
    if missing or unknown:
        raise InputError(f"class-{crystal_class} third-order constants: missing {missing}, unknown {unknown}; "
                         f"give exactly {list(names)}")
    flags = [k for k in names if isinstance(constants[k], (bool, np.bool_))]
    if flags:
        raise InputError(f"class-{crystal_class} third-order constants must be numbers (GPa), not True/False: "
                         f"{flags}")
    try:
        values = np.array([float(constants[k]) for k in names])
    except (TypeError, ValueError):
        raise InputError(f"class-{crystal_class} third-order constants must be numbers (GPa), "
                         f"got {dict(constants)}") from None
    if not np.all(np.isfinite(values)):
        raise InputError(f"class-{crystal_class} third-order constants must be finite, got {dict(constants)}")
    big = float(np.abs(values).max())
    if big > MAX_TOEC_GPA:
        raise InputError(f"third-order constants must be in GPa; the largest is {big:.4g}, which looks like Pa "
                         "(divide by 1e9)")
    B = invariant_toec_basis(crystal_class)
    cols = [_TRIPLES.index(tuple(int(c) - 1 for c in k[1:])) for k in names]
    y = np.linalg.solve(B[:, cols].T, values)
    return _from_triples(y @ B)


def trigonal_32_toec(**constants: float) -> np.ndarray:
    """Voigt third-order stiffness of a class-32 crystal (alpha-quartz) from its 14 constants.

    Parameters
    ----------
    **constants : float
        Every name of :data:`TRIGONAL_32_TOEC` (Brugger constants, GPa), standard setting (Z the
        three-fold axis, X a two-fold axis).

    Returns
    -------
    ndarray, shape (6, 6, 6)
        :func:`toec_from_named` of class 32.

    Raises
    ------
    InputError
        A missing, unknown or non-finite constant (named).
    """
    return toec_from_named("32", constants)


def checked_toec(C3: ArrayLike, crystal_class: str | None = None) -> np.ndarray:
    """A user's Voigt third-order stiffness, checked: shape, finite, fully symmetric, invariant.

    Parameters
    ----------
    C3 : array_like, shape (6, 6, 6)
        Brugger constants, GPa, crystal axes of the second-order set it goes with.
    crystal_class : str, optional
        The crystal's class (:data:`TOEC_NAMES`); None skips the invariance check (a crystal
        given by its constants alone has no class on record).

    Returns
    -------
    ndarray, shape (6, 6, 6), float

    Raises
    ------
    InputError
        Wrong shape, non-finite entries, values above :data:`MAX_TOEC_GPA` (Pa), C3_IJK not
        symmetric under permutations of I, J, K, or (with a class) a departure from the class's
        invariant tensors larger than :data:`INVARIANCE_TOL` of the largest component (e.g. a
        sign of the other axis setting).
    """
    C3 = np.asarray(C3, dtype=float)
    if C3.shape != (6, 6, 6):
        raise InputError(f"third-order constants: a Voigt array of shape (6, 6, 6) in GPa, got shape {C3.shape}")
    if not np.all(np.isfinite(C3)):
        raise InputError("third-order constants must be finite")
    scale = max(float(np.abs(C3).max()), 1e-300)
    if scale > MAX_TOEC_GPA:
        raise InputError(f"third-order constants must be in GPa; the largest is {scale:.4g}, which looks like Pa "
                         "(divide by 1e9)")
    perms = [(0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
    asym = max(float(np.abs(C3 - C3.transpose(p)).max()) for p in perms)
    if asym > INVARIANCE_TOL * scale:
        raise InputError(f"third-order constants: C3[I, J, K] must not depend on the order of I, J, K "
                         f"(largest difference {asym:.3g} GPa)")
    if crystal_class is not None:
        B = invariant_toec_basis(crystal_class)
        y = np.array([C3[t] for t in _TRIPLES])
        off = float(np.abs(y - (y @ B.T) @ B).max())
        if off > INVARIANCE_TOL * scale:
            raise InputError(f"third-order constants are not those of a class-{crystal_class} crystal in the "
                             f"database's axes (off the invariant tensors by {off:.3g} GPa, largest component "
                             f"{scale:.3g} GPa): check the axis setting and signs, or give the named constants "
                             f"{list(TOEC_NAMES.get(crystal_class, ()))}")
    return C3


def toec_from_user(toec: Mapping[str, float] | ArrayLike, crystal_class: str | None) -> np.ndarray:
    """A caller's third-order constants (GPa) as a checked Voigt (6, 6, 6) array.

    Parameters
    ----------
    toec : mapping or array_like
        A mapping of the class's named constants (:data:`TOEC_NAMES`; a ``source`` key, as a
        YAML file may carry, is ignored), or a (6, 6, 6) Voigt array (:func:`checked_toec`).
    crystal_class : str or None
        The crystal's class; None (a crystal given by its constants) allows arrays only.

    Returns
    -------
    ndarray, shape (6, 6, 6)

    Raises
    ------
    InputError
        A string, a mapping without a class, or what :func:`toec_from_named` and
        :func:`checked_toec` refuse.
    """
    if isinstance(toec, Mapping):
        if crystal_class is None:
            raise InputError("third-order constants by name need the crystal's class; give a (6, 6, 6) Voigt array")
        names = {k: v for k, v in toec.items() if k != "source"}
        return toec_from_named(crystal_class, names)
    if isinstance(toec, str):
        raise InputError(f"toec must be True, False, a mapping of named constants or a (6, 6, 6) array, got {toec!r}")
    return checked_toec(toec, crystal_class)

