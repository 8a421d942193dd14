"""Prestressed crystal geometries in the lab frame of docs/physics/paper.md.

Lab frame: x = propagation direction, y = surface normal pointing into the crystal,
z = in-plane direction normal to x (3D only). Lengths in units of the rest length d0.

Supported (lattice, loading, direction):

* ``("triangular", "uniaxial", "[10]")``: rows along x with in-row spacing 2 d_x and row
  spacing d_y; inclined bonds at rest length, d_x^2 + d_y^2 = 1, so sigma_yy = 0.
  ``d_over_d0`` = 2 d_x, allowed in (0, 2).
* ``("fcc", "in_plane_hydrostatic", "[100]" | "[110]")``: (001) surface; the in-plane cube
  edges scaled by s = d/d0, the normal one by t = sqrt(2 - s^2) (out-of-plane bonds at d0).
  Allowed s in (0, sqrt 2).
* ``("fcc", "uniaxial", "[100]" | "[110]")``: stretch s along x; the stretches along y and z
  solved numerically from sigma_yy = sigma_zz = 0 (needs the potential).

``d_over_d0`` is always the stretch of the lattice along the propagation direction x.

Examples
--------
>>> from surfwave.model_crystals.lattices import build
>>> c = build("fcc", "in_plane_hydrostatic", None, "[110]", [0.9, 1.0])
>>> c.bonds.shape, c.volume.shape
((2, 6, 3), (2,))
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from surfwave.errors import GeometryError, InputError
from surfwave.model_crystals.potentials import PairPotential, get_potential
from surfwave.solvers.orientation import lab_axes
from surfwave.validate import as_1d
from surfwave.vocab import Direction, Lattice, Loading

LATTICES: dict[str, dict] = {
    "fcc": {"dim": 3, "loadings": ("in_plane_hydrostatic", "uniaxial"),
            "directions": ("[100]", "[110]")},
    "triangular": {"dim": 2, "loadings": ("uniaxial",), "directions": ("[10]",)},
}

#: Smallest lateral stretch accepted in the uniaxial solve; below it the crystal has
#: collapsed into a plane (e.g. FCC uniaxial [110] near d/d0 = sqrt 3).
MIN_LATERAL_STRETCH = 0.05

#: Vacuum padding (in d0) of the 3D cell that wraps the 2D triangular lattice for spglib/phonopy.
TRIANGULAR_VACUUM = 10.0

# FCC with nearest-neighbour distance 1: cube edge a = sqrt 2. Half of the 12 neighbours
# (one of each +/- pair), in crystal axes.
_A_FCC = np.sqrt(2.0)
_FCC_HALF_NEIGHBOURS = 0.5 * _A_FCC * np.array(
    [[1, 1, 0], [1, -1, 0], [1, 0, 1], [1, 0, -1], [0, 1, 1], [0, 1, -1]], dtype=float
)
_FCC_PRIMITIVE = 0.5 * _A_FCC * np.array([[0, 1, 1], [1, 0, 1], [1, 1, 0]], dtype=float)

# Rows: lab axes x, y, z expressed in crystal axes; the crystal [001] is the surface normal
# (pointing into the crystal). One place for the convention: solvers.orientation.
_FCC_LAB_AXES = {d: lab_axes("(001)", d) for d in ("[100]", "[110]")}


@dataclass(frozen=True)
class Crystal:
    """A prestressed Bravais crystal at several strains, in the lab frame.

    Attributes
    ----------
    lattice, loading, direction : str
        What was built.
    d_over_d0 : ndarray, shape (n,)
        Stretch along x (1 = unstressed).
    bonds : ndarray, shape (n, nb, dim)
        Half of the nearest-neighbour bond vectors (one of each +/- pair), so that sums
        over them count each bond once per atom. Units of d0.
    cell : ndarray, shape (n, dim, dim)
        Primitive lattice vectors (rows), lab frame, units of d0.
    volume : ndarray, shape (n,)
        Volume (area in 2D) per atom, d0^3 (d0^2).
    stretch : ndarray, shape (n, dim)
        Stretches along the lab axes x, y (, z) relative to the unstressed lattice.
    """

    lattice: str
    loading: str
    direction: str
    d_over_d0: np.ndarray
    bonds: np.ndarray
    cell: np.ndarray
    volume: np.ndarray
    stretch: np.ndarray

    @property
    def dim(self) -> int:
        """Spatial dimension (2 or 3)."""
        return self.bonds.shape[-1]

    @property
    def density(self) -> np.ndarray:
        """Mass density rho = m / V, shape (n,), in m / d0^dim."""
        return 1.0 / self.volume

    def cell3d(self) -> np.ndarray:
        """Primitive cell as 3D vectors, shape (n, 3, 3); 2D lattices padded with vacuum along z."""
        if self.dim == 3:
            return self.cell.copy()
        n = self.cell.shape[0]
        out = np.zeros((n, 3, 3))
        out[:, :2, :2] = self.cell
        out[:, 2, 2] = TRIANGULAR_VACUUM
        return out


def check_combination(lattice: str, loading: str, direction: str) -> None:
    """Raise :class:`InputError` unless (lattice, loading, direction) is supported."""
    if lattice not in LATTICES:
        raise InputError(f"unknown lattice {lattice!r}; known lattices: {sorted(LATTICES)}")
    spec = LATTICES[lattice]
    if loading not in spec["loadings"]:
        raise InputError(
            f"loading {loading!r} is not available for lattice {lattice!r}; "
            f"choose one of {list(spec['loadings'])}"
        )
    if direction not in spec["directions"]:
        raise InputError(
            f"direction {direction!r} is not available for lattice {lattice!r}; "
            f"choose one of {list(spec['directions'])}"
        )


#: Largest d/d0 (exclusive) of FCC under uniaxial load, whose geometry alone sets no limit: at
#: twice its rest length a bond is far past the breaking point of any pair potential in use
#: (LJ's inflection lies at d/d0 = 1.109), and the continuation from d/d0 = 1 in steps of 0.02
#: would take (d/d0 - 1) / 0.02 steps (5e7 at d/d0 = 1e6; an overflow at 1e308).
MAX_UNIAXIAL_STRETCH = 2.0


def d_over_d0_range(lattice: str, loading: str) -> tuple[float, float]:
    """Open interval of d/d0 values the geometry can take (before stability is asked)."""
    if lattice == "triangular":
        return (0.0, 2.0)
    if loading == "in_plane_hydrostatic":
        return (0.0, float(np.sqrt(2.0)))
    return (0.0, MAX_UNIAXIAL_STRETCH)  # uniaxial FCC: bonds at twice their length


def check_d_over_d0(lattice: str, loading: str, d_over_d0: ArrayLike) -> np.ndarray:
    """Return d_over_d0 as a 1-D array, or raise :class:`GeometryError` naming the bad value."""
    s = as_1d(d_over_d0)
    lo, hi = d_over_d0_range(lattice, loading)
    bad = s[(s <= lo) | (s >= hi)]
    if bad.size:
        why = {
            "triangular": "the inclined bonds cannot stay at rest length unless 0 < d/d0 < 2",
            "fcc": "t^2 = 2 - (d/d0)^2 must be positive, so 0 < d/d0 < sqrt 2",
        }[lattice]
        if lattice == "fcc" and loading == "uniaxial":
            why = (f"a stretch must be positive and below {MAX_UNIAXIAL_STRETCH:g}: bonds at twice their rest "
                   "length are far past the breaking point of any pair potential")
        raise GeometryError(
            f"impossible geometry for {lattice} {loading}: d/d0 = {bad[0]:.6g} ({why})"
        )
    return s


def _deform(vectors: np.ndarray, stretch: np.ndarray) -> np.ndarray:
    """Apply diagonal stretches (n, dim) to lab-frame vectors (m, dim) -> (n, m, dim)."""
    return vectors[None, :, :] * stretch[:, None, :]


def _fcc_lab(direction: str) -> tuple[np.ndarray, np.ndarray]:
    axes = _FCC_LAB_AXES[direction]
    return _FCC_HALF_NEIGHBOURS @ axes.T, _FCC_PRIMITIVE @ axes.T


def _lateral_stress(bonds_sq: np.ndarray, stretch: np.ndarray, pot: PairPotential, jacobian: bool = False):
    """V sigma_yy and V sigma_zz, shape (n, 2), for lab stretches (n, 3).

    ``bonds_sq`` holds the squared lab components b_a^2 of the unstressed half-neighbours,
    shape (nb, 3). With r_a = b_a lambda_a, w = phi'(r)/r and V sigma_aa = sum_b r_a^2 w,
    ``jacobian`` also returns the derivatives with respect to the three stretches
    (lambda_x, lambda_y, lambda_z) = (s, t_y, t_z), shape (n, 2, 3):
    d(V sigma_aa)/d lambda_c = 2 delta_ac V sigma_aa / lambda_a
    + lambda_a^2 lambda_c sum_b b_a^2 b_c^2 w'(r) / r.
    """
    lam2 = stretch * stretch
    r2 = lam2 @ bonds_sq.T  # (n, nb) squared bond lengths
    length = np.sqrt(r2)
    w = pot.dphi(length) / length
    f = (w @ bonds_sq[:, 1:]) * lam2[:, 1:]
    if not jacobian:
        return f
    dw_r = (pot.d2phi(length) - w) / r2  # w'(r) / r
    pairs = (bonds_sq[:, 1:, None] * bonds_sq[:, None, :]).reshape(len(bonds_sq), 6)  # b_a^2 b_c^2
    jac = (dw_r @ pairs).reshape(-1, 2, 3) * (lam2[:, 1:, None] * stretch[:, None, :])
    jac[:, 0, 1] += 2.0 * f[:, 0] / stretch[:, 1]
    jac[:, 1, 2] += 2.0 * f[:, 1] / stretch[:, 2]
    return f, jac


def _solve2(jac: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """x with jac @ x = rhs for (n, 2, 2) matrices and (n, 2) right-hand sides (Cramer's rule;
    non-finite where jac is singular)."""
    a, b, c, d = jac[:, 0, 0], jac[:, 0, 1], jac[:, 1, 0], jac[:, 1, 1]
    with np.errstate(all="ignore"):
        det = a * d - b * c
        return np.column_stack([(d * rhs[:, 0] - b * rhs[:, 1]) / det, (a * rhs[:, 1] - c * rhs[:, 0]) / det])


def _newton(bonds_sq, s, t, pot, tol, max_iter) -> tuple[np.ndarray, np.ndarray]:
    """Newton on sigma_yy = sigma_zz = 0 at the stretches s (n,) from the start t (n, 2).

    Steps are clipped to 0.2; a point whose stretch falls to :data:`MIN_LATERAL_STRETCH` or
    becomes non-finite fails and is frozen, and so does one not at |V sigma| < ``tol``
    within ``max_iter`` iterations. Only the unconverged points are evaluated.

    Returns
    -------
    t : ndarray, shape (n, 2)
    failed : ndarray of bool, shape (n,)
    """
    t = np.array(t, dtype=float)
    failed = np.zeros(s.size, dtype=bool)
    todo = np.arange(s.size)
    for _ in range(max_iter):
        f, jac = _lateral_stress(bonds_sq, np.column_stack([s[todo], t[todo]]), pot, jacobian=True)
        left = ~np.all(np.abs(f) < tol, axis=-1)
        todo, f, jac = todo[left], f[left], jac[left]
        if not todo.size:
            return t, failed
        step = _solve2(jac[:, :, 1:], f)
        t[todo] -= np.clip(np.where(np.isfinite(step), step, 0.0), -0.2, 0.2)
        bad = np.any(t[todo] <= MIN_LATERAL_STRETCH, axis=-1) | ~np.all(np.isfinite(t[todo]), axis=-1)
        failed[todo[bad]] = True
        todo = todo[~bad]
    failed[todo] = True  # not converged within max_iter
    return t, failed


def _continuation(bonds_sq, s, pot, tol, max_iter) -> tuple[np.ndarray, np.ndarray]:
    """March every point from s = 1 to its target in steps of at most 0.02, Newton at each.

    Following the strain path from the unstressed lattice selects the branch connected to
    it; a point that fails is frozen so it cannot spoil the others. Returns (t (n, 2),
    failed (n,)).
    """
    t = np.ones((s.size, 2))
    failed = np.zeros(s.size, dtype=bool)
    steps = 1 + int(np.ceil(np.max(np.abs(s - 1.0), initial=0.0) / 0.02))
    for k in range(1, steps + 1):
        ok = np.flatnonzero(~failed)
        if not ok.size:  # every point has failed: nothing left to march
            break
        t[ok], failed[ok] = _newton(bonds_sq, 1.0 + (s[ok] - 1.0) * k / steps, t[ok], pot, tol, max_iter)
    return t, failed


#: Spacing of the anchor stretches that :func:`solve_lateral_stretch` follows by continuation
#: before it interpolates between them (cubic Hermite, error ~ spacing^4 / 384 t'''').
ANCHOR_SPACING = 0.01


def solve_lateral_stretch(
    direction: str,
    s: np.ndarray,
    potential: str | PairPotential,
    tol: float = 1e-13,
    max_iter: int = 60,
) -> np.ndarray:
    """Stretches (t_y, t_z) with sigma_yy = sigma_zz = 0 for FCC stretched by s along x.

    The branch connected to the unstressed crystal: continuation from s = 1 in steps of at
    most 0.02 with Newton's method at each step, vectorised over s. Many points are not
    each marched: anchors :data:`ANCHOR_SPACING` apart across the range of s are, and every
    point then starts Newton from the cubic Hermite interpolant of the anchors (slopes
    dt/ds = -(d sigma/dt)^-1 d sigma/ds from the same Jacobian), which converges in one or
    two steps; a point that fails there, or lies next to a failed anchor, is marched itself.

    Parameters
    ----------
    direction : {"[100]", "[110]"}
    s : ndarray, shape (n,)
        Stretch along x.
    potential : str or PairPotential
    tol : float
        Convergence threshold on |V sigma| in K d0^2.
    max_iter : int
        Newton iterations allowed per continuation step.

    Returns
    -------
    ndarray, shape (n, 2)
        t_y, t_z.

    Raises
    ------
    GeometryError
        Naming the first d/d0 whose solve does not converge or ends at a non-positive stretch.
    """
    pot = get_potential(potential)
    bonds_sq = _fcc_lab(direction)[0] ** 2
    s = np.asarray(s, dtype=float)
    values, inverse = np.unique(s, return_inverse=True)
    n_anchors = 2 + int(np.ceil((values[-1] - values[0]) / ANCHOR_SPACING)) if values.size else 0
    if values.size <= 2 * n_anchors:
        t, failed = _continuation(bonds_sq, values, pot, tol, max_iter)
    else:
        anchors = np.linspace(values[0], values[-1], n_anchors)
        t_a, failed_a = _continuation(bonds_sq, anchors, pot, tol, max_iter)
        t_a[failed_a] = 1.0  # placeholders: intervals next to a failed anchor are not interpolated
        _, jac = _lateral_stress(bonds_sq, np.column_stack([anchors, t_a]), pot, jacobian=True)
        slope = -_solve2(jac[:, :, 1:], jac[:, :, 0])  # dt/ds along the branch
        i = np.clip(np.searchsorted(anchors, values), 1, n_anchors - 1)  # interval [i - 1, i]
        ok_a = ~failed_a & np.all(np.isfinite(slope), axis=-1)
        good = ok_a[i - 1] & ok_a[i]
        h = anchors[i] - anchors[i - 1]
        u = ((values - anchors[i - 1]) / h)[:, None]
        start = ((1 + 2 * u) * (1 - u) ** 2 * t_a[i - 1] + u**2 * (3 - 2 * u) * t_a[i]
                 + h[:, None] * (u * (1 - u) ** 2 * slope[i - 1] - u**2 * (1 - u) * slope[i]))
        t = np.ones((values.size, 2))
        failed = ~good
        t[good], failed[good] = _newton(bonds_sq, values[good], start[good], pot, tol, max_iter)
        if failed.any():  # march these points themselves, as with few points
            t[failed], failed[failed] = _continuation(bonds_sq, values[failed], pot, tol, max_iter)
    failed = failed[inverse]
    if failed.any():
        raise GeometryError(
            f"fcc uniaxial {direction} with potential {pot.name!r}: no lateral stretches with "
            f"sigma_yy = sigma_zz = 0 (the crystal collapses or the solve does not converge) "
            f"at d/d0 = {s[failed][0]:.6g}"
        )
    return t[inverse]


def build(
    lattice: Lattice,
    loading: Loading,
    potential: str | PairPotential | None,
    direction: Direction,
    d_over_d0: ArrayLike,
) -> Crystal:
    """Build the prestressed crystal at one or several stretches.

    The arguments come in the order used throughout the library (:func:`surfwave.point`,
    :func:`surfwave.model_crystals.elastic.properties`, ...): lattice, loading, potential,
    direction, d/d0.

    Parameters
    ----------
    lattice : {"fcc", "triangular"}
    loading : {"uniaxial", "in_plane_hydrostatic"}
    potential : str or PairPotential or None
        Needed only for FCC uniaxial loading (the lateral stretches depend on it); None
        elsewhere. A name is checked against the registry in every case.
    direction : {"[100]", "[110]", "[10]"}
    d_over_d0 : float or array_like, shape (n,)
        Stretch along the propagation direction x (1 = unstressed).

    Returns
    -------
    Crystal

    Raises
    ------
    InputError
        Unknown or unsupported names.
    GeometryError
        A geometry that cannot exist, naming the offending d/d0.
    """
    if potential is not None:
        potential = get_potential(potential)
    check_combination(lattice, loading, direction)
    s = check_d_over_d0(lattice, loading, d_over_d0)
    if lattice == "triangular":
        dx = 0.5 * s
        dy = np.sqrt(1.0 - dx**2)
        bonds = np.stack(
            [np.column_stack([2 * dx, 0 * dx]), np.column_stack([dx, dy]), np.column_stack([-dx, dy])],
            axis=1,
        )
        cell = np.stack([np.column_stack([2 * dx, 0 * dx]), np.column_stack([dx, dy])], axis=1)
        volume = 2.0 * dx * dy
        stretch = np.column_stack([s, dy / np.sqrt(0.75)])
        return Crystal(lattice, loading, direction, s, bonds, cell, volume, stretch)

    bonds0, cell0 = _fcc_lab(direction)
    if loading == "in_plane_hydrostatic":
        t = np.sqrt(2.0 - s**2)
        stretch = np.column_stack([s, t, s])  # lab y is the crystal [001] normal
    else:
        if potential is None:
            raise InputError("fcc uniaxial loading needs the potential to solve the lateral stretches")
        stretch = np.column_stack([s, solve_lateral_stretch(direction, s, potential)])
    bonds = _deform(bonds0, stretch)
    cell = _deform(cell0, stretch)
    volume = np.abs(np.linalg.det(cell))
    return Crystal(lattice, loading, direction, s, bonds, cell, volume, stretch)


#: A lab stretch or a volume per atom below this (d0, d0^dim) counts as a collapsed geometry.
COLLAPSED = 1e-6


def build_checked(
    lattice: Lattice,
    loading: Loading,
    potential: str | PairPotential | None,
    direction: Direction,
    d_over_d0: ArrayLike,
) -> Crystal:
    """:func:`build`, and a :class:`GeometryError` where the crystal has collapsed.

    A geometry that exists but whose lab stretches or volume per atom fall below
    :data:`COLLAPSED` (e.g. the lateral collapse t_y -> 0 of harmonic uniaxial FCC [110]
    near d/d0 = sqrt 3) has no meaningful force constants or symmetry; the phonopy and
    stability routes use this builder so they stop there.

    Raises
    ------
    InputError, GeometryError
        As :func:`build`; GeometryError naming the first collapsed d/d0 and its stretches.
    """
    crystal = build(lattice, loading, potential, direction, d_over_d0)
    bad = (crystal.stretch.min(axis=1) < COLLAPSED) | (crystal.volume < COLLAPSED)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise GeometryError(
            f"degenerate geometry at d/d0 = {crystal.d_over_d0[i]:.6g}: lab stretches "
            f"{np.round(crystal.stretch[i], 8)}"
        )
    return crystal
