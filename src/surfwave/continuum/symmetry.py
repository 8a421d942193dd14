"""Space groups of the prestressed crystals (spglib) and the mirror planes the theory needs.

Eq. (17) assumes that the sagittal motion (x, y) decouples from the shear-horizontal one
(z): the lab-frame reflections x -> -x and z -> -z must be symmetry operations of the
prestressed lattice. :func:`crystal_symmetry` reports the space group of every cell and
whether each mirror is present; :func:`require_mirrors` raises :class:`SymmetryError`
when one is missing. Expected (one atom per primitive cell): FCC Fm-3m at zero stress,
I4/mmm under in-plane hydrostatic (or uniaxial [100]) stress, Immm under uniaxial [110]
stress; the triangular lattice in its vacuum-padded 3D cell P6/mmm, then Cmmm.

Examples
--------
>>> r = crystal_symmetry("fcc", "in_plane_hydrostatic", None, "[110]", [0.95, 1.0])
>>> r["space_group"].tolist(), bool(r["mirror_x"].all()), bool(r["mirror_z"].all())
(['I4/mmm', 'Fm-3m'], True, True)
"""
from __future__ import annotations

import numpy as np
import spglib
import spglib.error

from surfwave.errors import SymmetryError
from surfwave.continuum.lattices import build
from surfwave.continuum.potentials import PairPotential

spglib.error.OLD_ERROR_HANDLING = False

#: Lab-frame reflections the surface-wave theory needs.
MIRRORS = {"mirror_x": np.diag([-1.0, 1.0, 1.0]), "mirror_z": np.diag([1.0, 1.0, -1.0])}

VARIABLES = {
    "space_group": {"long_name": "space group (Hermann-Mauguin, spglib) of the prestressed lattice", "dims": ()},
    "space_group_number": {"long_name": "space group number (International Tables)", "units": "1", "dims": ()},
    "mirror_x": {"long_name": "lab-frame reflection x -> -x is a symmetry operation", "dims": ()},
    "mirror_z": {"long_name": "lab-frame reflection z -> -z is a symmetry operation (sagittal plane is a mirror)", "dims": ()},
    "cell": {"long_name": "primitive lattice vectors (rows) in the lab frame (2D lattices padded with vacuum along z)",
             "units": "d0", "dims": ("vector", "xyz")},
    "volume": {"long_name": "volume (area in 2D) per atom", "units": "d0^3 (d0^2 for the 2D triangular lattice)", "dims": ()},
}


def cartesian_rotations(cell: np.ndarray, rotations: np.ndarray) -> np.ndarray:
    """Convert spglib's fractional rotations (m, 3, 3) to lab-frame (Cartesian) ones.

    With lattice vectors as the rows of ``cell`` (x = f @ cell), R_cart = L^T R L^-T.
    """
    lt = cell.T
    return lt @ rotations @ np.linalg.inv(lt)


#: Results of cells already analysed in this process (cell rounded to 1e-12 d0, symprec).
_SEEN: dict = {}
_SEEN_MAX = 10**6


def analyse(cells: np.ndarray, symprec: float = 1e-5) -> dict[str, np.ndarray]:
    """Space group and lab-frame mirrors of one-atom cells.

    Parameters
    ----------
    cells : ndarray, shape (n, 3, 3)
        Primitive vectors (rows), lab frame, units of d0.
    symprec : float
        spglib tolerance (d0).

    Returns
    -------
    dict
        ``space_group`` (n,) str, ``space_group_number`` (n,) int, ``mirror_x``,
        ``mirror_z`` (n,) bool.

    Raises
    ------
    SymmetryError
        If spglib cannot determine the symmetry of a cell.
    """
    cells = np.asarray(cells, dtype=float)
    out = {"space_group": [], "space_group_number": [], **{k: [] for k in MIRRORS}}
    for i, cell in enumerate(cells):
        key = (np.round(cell, 12).tobytes(), symprec)  # the same cell again (e.g. another
        if key in _SEEN:                               # potential, same geometry): same answer
            for name, value in zip(out, _SEEN[key]):
                out[name].append(value)
            continue
        try:
            ds = spglib.get_symmetry_dataset((cell, [[0.0, 0.0, 0.0]], [1]), symprec=symprec)
        except spglib.error.SpglibError as exc:
            raise SymmetryError(f"spglib failed on cell {i} ({cell.tolist()}): {exc}") from None
        if ds is None:
            raise SymmetryError(f"spglib found no symmetry for cell {i} ({cell.tolist()})")
        rots = cartesian_rotations(cell, np.asarray(ds.rotations, dtype=float))
        out["space_group"].append(ds.international)
        out["space_group_number"].append(int(ds.number))
        for name, mirror in MIRRORS.items():
            out[name].append(bool(np.any(np.all(np.abs(rots - mirror) < 1e-6, axis=(1, 2)))))
        if len(_SEEN) < _SEEN_MAX:
            _SEEN[key] = tuple(v[-1] for v in out.values())
    return {k: np.asarray(v) for k, v in out.items()}


def crystal_symmetry(
    lattice: str,
    loading: str,
    potential: str | PairPotential | None,
    direction: str,
    d_over_d0,
    symprec: float = 1e-5,
) -> dict[str, np.ndarray]:
    """Build the prestressed crystal (:func:`surfwave.continuum.lattices.build`) and analyse it.

    Returns
    -------
    dict
        The keys of :func:`analyse` plus ``cell`` (n, 3, 3) in d0 and ``volume`` (n,).
    """
    crystal = build(lattice, loading, potential, direction, d_over_d0)
    cells = crystal.cell3d()
    out = analyse(cells, symprec)
    out["cell"] = cells
    out["volume"] = np.asarray(crystal.volume, dtype=float)
    return out


def require_mirrors(result: dict, d_over_d0, what: str = "") -> None:
    """Raise :class:`SymmetryError` naming the first d/d0 whose lattice lacks a needed mirror."""
    d = np.atleast_1d(np.asarray(d_over_d0, dtype=float))
    for name in MIRRORS:
        bad = ~np.asarray(result[name], dtype=bool)
        if bad.any():
            i = int(np.argmax(bad))
            raise SymmetryError(
                f"{what}d/d0 = {d[i]:.6g}: space group {result['space_group'][i]} lacks the "
                f"lab-frame reflection {name.replace('mirror_', '')} -> -{name[-1]} that the "
                "sagittal/shear-horizontal decoupling (Eq. 17) assumes"
            )
