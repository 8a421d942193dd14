"""Space groups of the prestressed crystals (spglib) and the mirror planes the theory needs.

Eq. (17) assumes that the sagittal motion (x, y) decouples from the shear-horizontal one
(z): the lab-frame reflections x -> -x and z -> -z must be symmetry operations of the
prestressed lattice. :func:`crystal_symmetry` reports the space group of every cell and
whether each mirror is present; :func:`require_mirrors` raises :class:`SymmetryError`
when one is missing. Expected (one atom per primitive cell): FCC Fm-3m at zero stress,
I4/mmm under in-plane hydrostatic (or uniaxial [100]) stress, Immm under uniaxial [110]
stress; the triangular lattice in its vacuum-padded 3D cell P6/mmm, then Cmmm.

How it scales (:func:`analyse`): the mirrors are tested on every cell, exactly and
vectorised (a rotation R is a symmetry of a one-atom Bravais lattice with rows L iff
L R^T L^-1 is an integer matrix with det +-1). The space group, piecewise constant along a
strain grid, comes from spglib once per *symmetry class*: cells are grouped by a cheap
vectorised key (which operations of a reference cell's group survive, and the
multiplicities of the first lattice-vector shells); spglib analyses the first and the last
member of each class, and every operation it finds is verified on every member. A cell
whose key is ambiguous within the tolerance (a length gap or an operation residual
between 1e-2 and 30 symprec, i.e. near a special strain), whose shells are not resolved,
or that fails the verification, goes to spglib itself.

Examples
--------
>>> r = crystal_symmetry("fcc", "in_plane_hydrostatic", None, "[110]", [0.95, 1.0])
>>> r["space_group"].tolist(), bool(r["mirror_x"].all()), bool(r["mirror_z"].all())
(['I4/mmm', 'Fm-3m'], True, True)
"""
from __future__ import annotations

import itertools

import numpy as np
import spglib
import spglib.error
from numpy.typing import ArrayLike

from surfwave.errors import SymmetryError
from surfwave.model_crystals.lattices import build
from surfwave.model_crystals.potentials import PairPotential
from surfwave.validate import as_1d
from surfwave.vocab import Direction, Lattice, Loading

spglib.error.OLD_ERROR_HANDLING = False

#: Lab-frame reflections the surface-wave theory needs.
MIRRORS = {"mirror_x": np.diag([-1.0, 1.0, 1.0]), "mirror_z": np.diag([1.0, 1.0, -1.0])}

#: A mirror counts as present when the lattice maps onto itself to within this (d0; and
#: within symprec when that is smaller): exact up to rounding, as Eq. (17) needs.
MIRROR_TOL = 1e-6


#: What the crystal cube's ``method`` attribute says about how the groups were found.
METHOD = ("space group: spglib once per symmetry class (key: surviving operations of the "
          "unstrained group + multiplicities of the first lattice-vector shells), spglib on the "
          "first and last member of each class, every operation verified on every member "
          "(|L R^T - N L| < 1e-2 symprec, N integer); cells near a special strain (key within "
          "1e-2..30 symprec of a change) or failing the check analysed by spglib directly. "
          "Mirrors x->-x, z->-z tested exactly on every cell (L M^T L^-1 integer) and required")

#: A length gap or residual below CLEAR * symprec is zero for spglib, above FAR * symprec it
#: is not; in between the cell is in doubt and spglib analyses it. (spglib 2.x stops finding
#: a broken operation where its residual reaches 0.5 - 1 symprec and the smallest shell gap
#: 0.03 - 0.2 symprec: measured at the zero-strain, BCC and square points of our lattices.)
CLEAR, FAR = 1e-2, 30.0

#: Lattice vectors n L with n in [-K, K]^3 (one of each +/- pair) make the shells; the first
#: N_SHELLS complete shells enter the class key.
_K = 3
_HALF = np.array([n for n in itertools.product(range(-_K, _K + 1), repeat=3)
                  if n > (0, 0, 0)], dtype=float)  # lexicographically positive: one per pair
N_SHELLS = 4

#: Cells per vectorised chunk (bounds the memory: chunk x operations x 9 doubles).
_CHUNK = 2048

#: spglib results of cells already analysed in this process (cell rounded to 1e-12 d0,
#: symprec), e.g. the same geometry for another potential; at most _SEEN_MAX entries of up
#: to 48 x 9 doubles each (~20 MB).
_SEEN: dict = {}
_SEEN_MAX = 5000


def cartesian_rotations(cell: np.ndarray, rotations: np.ndarray) -> np.ndarray:
    """Convert spglib's fractional rotations (m, 3, 3) to lab-frame (Cartesian) ones.

    With lattice vectors as the rows of ``cell`` (x = f @ cell), R_cart = L^T R L^-T.
    """
    lt = cell.T
    return lt @ rotations @ np.linalg.inv(lt)


def lattice_residual(cells: np.ndarray, rotations: np.ndarray) -> np.ndarray:
    """How far each Cartesian rotation is from mapping each lattice onto itself.

    R is a symmetry of the lattice with rows L iff N = L R^T L^-1 is an integer matrix with
    det +-1; the residual is the largest distance between a rotated basis vector and the
    lattice vector round(N) L.

    Parameters
    ----------
    cells : ndarray, shape (n, 3, 3)
        Lattice vectors (rows), d0.
    rotations : ndarray, shape (m, 3, 3)
        Cartesian (lab-frame) rotations or reflections.

    Returns
    -------
    ndarray, shape (n, m)
        Residual in d0 (inf where round(N) is not unimodular).
    """
    cells = np.asarray(cells, dtype=float)
    rotations = np.asarray(rotations, dtype=float)
    n, m = cells.shape[0], rotations.shape[0]
    out = np.empty((n, m))
    r_t = rotations.transpose(2, 0, 1).reshape(3, 3 * m)  # [j, (m, k)] = R[m, k, j]
    for lo in range(0, n, _CHUNK):
        lat = cells[lo:lo + _CHUNK]
        c = lat.shape[0]
        # rows R a_i of every cell and operation: one matrix product, then per cell
        image = (lat.reshape(3 * c, 3) @ r_t).reshape(c, 3, m, 3).transpose(0, 2, 1, 3)
        n_real = image.reshape(c, 3 * m, 3) @ np.linalg.inv(lat)  # (c, 3m, 3): L R^T L^-1
        n_int = np.rint(n_real)
        miss = (n_real - n_int) @ lat  # rotated basis vector minus the nearest lattice vector
        sq = (miss[..., 0] ** 2 + miss[..., 1] ** 2 + miss[..., 2] ** 2).reshape(c, m, 3)
        res = np.sqrt(np.maximum(np.maximum(sq[..., 0], sq[..., 1]), sq[..., 2]))
        out[lo:lo + c] = np.where(np.abs(np.abs(_det3(n_int.reshape(c, m, 3, 3))) - 1) < 0.5,
                                  res, np.inf)
    return out


def _det3(a: np.ndarray) -> np.ndarray:
    """Determinants of (..., 3, 3) matrices (cofactor expansion, vectorised)."""
    return (a[..., 0, 0] * (a[..., 1, 1] * a[..., 2, 2] - a[..., 1, 2] * a[..., 2, 1])
            - a[..., 0, 1] * (a[..., 1, 0] * a[..., 2, 2] - a[..., 1, 2] * a[..., 2, 0])
            + a[..., 0, 2] * (a[..., 1, 0] * a[..., 2, 1] - a[..., 1, 1] * a[..., 2, 0]))


def shell_multiplicities(cells: np.ndarray, symprec: float) -> tuple[np.ndarray, np.ndarray]:
    """Multiplicities of the first lattice-vector shells, lengths equal within symprec.

    Every lattice vector of length <= K / max_i |L^-1 e_i| has integer coordinates in
    [-K, K], so the shells shorter than that are complete.

    Parameters
    ----------
    cells : ndarray, shape (n, 3, 3)
        Lattice vectors (rows), d0.
    symprec : float
        Length tolerance (d0).

    Returns
    -------
    mult : ndarray, shape (n, N_SHELLS), int
        Vectors (one of each +/- pair) in each of the first shells; -1 for a shell not
        complete within the searched vectors.
    doubt : ndarray, shape (n,), bool
        A gap between successive lengths between CLEAR and FAR symprec (spglib may or may
        not merge the two shells), or fewer than two complete shells.
    """
    cells = np.asarray(cells, dtype=float)
    n = cells.shape[0]
    mult = np.full((n, N_SHELLS), -1, dtype=np.int64)
    doubt = np.zeros(n, dtype=bool)
    for lo in range(0, n, _CHUNK):
        lat = cells[lo:lo + _CHUNK]
        vec = _HALF @ lat  # (c, nv, 3)
        lengths = np.sort(np.sqrt(np.sum(vec * vec, axis=-1)), axis=-1)  # (c, nv)
        r_max = _K / np.linalg.norm(np.linalg.inv(lat), axis=1).max(axis=-1)  # (c,)
        complete = lengths < (r_max - FAR * symprec)[:, None]
        gap = np.diff(lengths, axis=-1)
        new = gap > CLEAR * symprec
        ambiguous = new & (gap < FAR * symprec) & complete[:, 1:]
        shell = np.concatenate([np.zeros((lat.shape[0], 1), dtype=np.int64),
                                np.cumsum(new, axis=-1)], axis=-1)
        for k in range(N_SHELLS):
            inside = shell == k
            whole = np.all(complete | ~inside, axis=-1) & inside.any(axis=-1)
            mult[lo:lo + _CHUNK, k] = np.where(whole, inside.sum(axis=-1), -1)
        doubt[lo:lo + _CHUNK] = ambiguous.any(axis=-1) | ((mult[lo:lo + _CHUNK] >= 0).sum(-1) < 2)
    return mult, doubt


def _spglib(cell: np.ndarray, symprec: float, i: int) -> tuple[str, int, np.ndarray]:
    """spglib on one one-atom cell: (symbol, number, Cartesian rotations (m, 3, 3))."""
    key = (np.round(cell, 12).tobytes(), symprec)
    if key in _SEEN:
        return _SEEN[key]
    try:
        # spglib's hints ask for nested sequences; it takes the (3, 3) array as well
        ds = spglib.get_symmetry_dataset((cell, [[0.0, 0.0, 0.0]], [1]), symprec=symprec)  # type: ignore[arg-type]
    except spglib.error.SpglibError as exc:
        raise SymmetryError(f"spglib failed on cell {i} ({cell.tolist()}): {exc}") from None
    if ds is None:
        raise SymmetryError(f"spglib found no symmetry for cell {i} ({cell.tolist()})")
    out = (str(ds.international), int(ds.number),
           cartesian_rotations(cell, np.asarray(ds.rotations, dtype=float)))
    if len(_SEEN) < _SEEN_MAX:
        _SEEN[key] = out
    return out


def _proper(rotations: np.ndarray) -> np.ndarray:
    """The proper rotations (det +1) of a lattice's operations: a lattice is centrosymmetric,
    so R is a symmetry iff -R is, and testing the proper half suffices."""
    return rotations[_det3(rotations) > 0]


def _same_group(a: tuple, b: tuple) -> bool:
    """Same space group with the same lab-frame operations (as sets)."""
    if a[1] != b[1] or len(a[2]) != len(b[2]):
        return False
    diff = np.abs(a[2][:, None] - b[2][None]).max(axis=(-1, -2))
    return bool(np.all(diff.min(axis=1) < 1e-6))


def analyse(cells: np.ndarray, symprec: float = 1e-5, reference: np.ndarray | None = None,
            stats: dict | None = None) -> dict[str, np.ndarray]:
    """Space group and lab-frame mirrors of one-atom cells.

    The mirrors are tested on every cell (:func:`lattice_residual`). Each cell's space group
    is spglib's answer for a cell of the same symmetry class (same operations of the
    reference group surviving, same shell multiplicities, see :func:`shell_multiplicities`)
    whose every operation was verified on it to within 1e-2 symprec, the first and last
    members of the class giving the same group; a cell in doubt is analysed by spglib itself.

    Parameters
    ----------
    cells : ndarray, shape (n, 3, 3)
        Primitive vectors (rows), lab frame, units of d0.
    symprec : float
        spglib tolerance (d0).
    reference : ndarray, shape (3, 3), optional
        A cell whose group's operations split the classes (default: the first cell); the
        unstrained cell is the natural choice. Only the speed depends on it.
    stats : dict, optional
        Filled with ``cells``, ``classes``, ``spglib_calls`` (how much spglib ran) and
        ``in_doubt`` (cells analysed by spglib one by one).

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
    cells = np.asarray(cells, dtype=float).reshape(-1, 3, 3)
    n = cells.shape[0]
    res = lattice_residual(cells, np.stack(list(MIRRORS.values())))
    out: dict[str, np.ndarray] = {name: res[:, j] <= min(MIRROR_TOL, symprec) for j, name in enumerate(MIRRORS)}
    symbol = np.empty(n, dtype=object)
    number = np.zeros(n, dtype=np.int64)
    calls, n_classes, doubt = 0, 0, np.zeros(n, dtype=bool)
    if n:
        ref = cells[0] if reference is None else np.asarray(reference, dtype=float)
        ops0 = _proper(_spglib(ref, symprec, 0)[2])
        res0 = lattice_residual(cells, ops0)
        mult, doubt = shell_multiplicities(cells, symprec)
        doubt |= np.any((res0 > CLEAR * symprec) & (res0 < FAR * symprec), axis=1)
        key: np.ndarray = np.ascontiguousarray(np.concatenate([res0 <= CLEAR * symprec, mult], axis=1),
                                   dtype=np.int16)
        key = key.view(np.dtype((np.void, key.itemsize * key.shape[1]))).ravel()  # one row, one value
        sure = np.flatnonzero(~doubt)
        classes, inverse = np.unique(key[sure], return_inverse=True)
        order = np.argsort(inverse.ravel(), kind="stable")  # members in input order
        bounds = np.searchsorted(inverse.ravel()[order], np.arange(len(classes) + 1))
        for c in range(len(classes)):
            members = sure[order[bounds[c]:bounds[c + 1]]]
            first = _spglib(cells[members[0]], symprec, int(members[0]))
            last = _spglib(cells[members[-1]], symprec, int(members[-1]))
            calls += 1 + (len(members) > 1)
            if not _same_group(first, last):
                doubt[members] = True
                continue
            ok = np.all(lattice_residual(cells[members], _proper(first[2])) <= CLEAR * symprec,
                        axis=1)
            symbol[members[ok]] = first[0]
            number[members[ok]] = first[1]
            doubt[members[~ok]] = True
        for i in np.flatnonzero(doubt):
            symbol[i], number[i], _ = _spglib(cells[i], symprec, int(i))
            calls += 1
        n_classes = len(classes)
    if stats is not None:
        stats.update(cells=n, classes=n_classes, spglib_calls=calls, in_doubt=int(doubt.sum()))
    out = {"space_group": np.array(symbol.tolist(), dtype=str), "space_group_number": number,
           **out}
    return out


def crystal_symmetry(
    lattice: Lattice,
    loading: Loading,
    potential: str | PairPotential | None,
    direction: Direction,
    d_over_d0: ArrayLike,
    symprec: float = 1e-5,
    stats: dict | None = None,
) -> dict[str, np.ndarray]:
    """Build the prestressed crystal (:func:`surfwave.model_crystals.lattices.build`) and analyse it.

    The unstrained cell (d/d0 = 1) is the reference whose operations split the symmetry
    classes (:func:`analyse`).

    Returns
    -------
    dict
        The keys of :func:`analyse` plus ``cell`` (n, 3, 3) in d0 and ``volume`` (n,).
    """
    crystal = build(lattice, loading, potential, direction, d_over_d0)
    cells = crystal.cell3d()
    reference = build(lattice, loading, potential, direction, [1.0]).cell3d()[0]
    out = analyse(cells, symprec, reference, stats)
    out["cell"] = cells
    out["volume"] = np.asarray(crystal.volume, dtype=float)
    return out


def require_mirrors(result: dict, d_over_d0: ArrayLike, what: str = "") -> None:
    """Raise :class:`SymmetryError` naming the first d/d0 whose lattice lacks a needed mirror."""
    d = as_1d(d_over_d0)
    for name in MIRRORS:
        bad = ~np.asarray(result[name], dtype=bool)
        if bad.any():
            i = int(np.argmax(bad))
            raise SymmetryError(
                f"{what}d/d0 = {d[i]:.6g}: space group {result['space_group'][i]} lacks the "
                f"lab-frame reflection {name.replace('mirror_', '')} -> -{name[-1]} that the "
                "sagittal/shear-horizontal decoupling (Eq. 17) assumes"
            )
