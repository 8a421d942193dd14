"""Space groups by symmetry class (spglib once per class) against spglib on every cell.

The grids pass through every special strain each loading reaches (zero strain, FCC squeezed
to BCC, the triangular lattice stretched to a square and back to a triangular one, the
accidental tetragonal points of uniaxial [110]), from 1e-10 to 5e-2 away on both sides, so
they cross spglib's tolerance, the doubt zone of the class key and the plain classes.
"""
from __future__ import annotations

import numpy as np
import pytest
import spglib
from scipy.optimize import brentq

from surfwave.model_crystals import symmetry
from surfwave.model_crystals.lattices import build

SQRT2 = np.sqrt(2.0)


def spglib_reference(cells: np.ndarray, symprec: float = 1e-5):
    """spglib on each cell, and the mirrors as the previous implementation found them: a
    Cartesian operation of spglib's dataset within 1e-6 of diag(-1, 1, 1) (or diag(1, 1, -1))."""
    groups, numbers, mx, mz = [], [], [], []
    for cell in cells:
        ds = spglib.get_symmetry_dataset((cell, [[0.0, 0.0, 0.0]], [1]), symprec=symprec)
        rots = cell.T @ np.asarray(ds.rotations, dtype=float) @ np.linalg.inv(cell.T)
        groups.append(ds.international)
        numbers.append(ds.number)
        mx.append(np.any(np.all(np.abs(rots - np.diag([-1.0, 1, 1])) < 1e-6, axis=(1, 2))))
        mz.append(np.any(np.all(np.abs(rots - np.diag([1.0, 1, -1])) < 1e-6, axis=(1, 2))))
    return {"space_group": np.array(groups), "space_group_number": np.array(numbers),
            "mirror_x": np.array(mx), "mirror_z": np.array(mz)}


def _uniaxial_special(potential: str, direction: str) -> dict[float, str]:
    """Strains where uniaxially loaded FCC gains symmetry, and the group expected there.

    [100]: face-centred cube axes (s, t, t) (t_y = t_z = t): BCC (Im-3m) when s = t / sqrt 2
    (the Bain path). [110]: body-centred axes (s, sqrt 2 t_y, t_z) along x, y, z; where two
    are equal (a) the lattice is body-centred tetragonal, I4/mmm, unless the third is
    c = sqrt 2 a (FCC again, Fm-3m) or c = a (BCC). Roots of the lateral solve
    (lattices.build), bracketed on a coarse grid."""
    def axes(s):
        t = build("fcc", "uniaxial", potential, direction, np.atleast_1d(s)).stretch
        if direction == "[100]":
            return np.stack([SQRT2 * t[:, 0] - t[:, 1]], axis=-1), None
        body = np.stack([t[:, 0], SQRT2 * t[:, 1], t[:, 2]], axis=-1)
        return np.stack([body[:, i] - body[:, j] for i, j in pairs], axis=-1), body

    pairs = [(0, 1), (0, 2), (1, 2)]
    grid = np.linspace(0.55, 1.6, 22)
    f, _ = axes(grid)
    out = {}
    for j in range(f.shape[1]):
        for i in np.flatnonzero(np.sign(f[:-1, j]) * np.sign(f[1:, j]) < 0):
            root = brentq(lambda s: axes(s)[0][0, j], grid[i], grid[i + 1], xtol=1e-15)
            if abs(root - 1.0) < 1e-3:
                continue
            body = axes(root)[1]
            if body is None:
                out[root] = "Im-3m"
                continue
            a, c = body[0, pairs[j][0]], body[0, 3 - sum(pairs[j])]  # equal pair, third axis
            out[root] = ("Im-3m" if np.isclose(c, a) else
                         "Fm-3m" if np.isclose(c, SQRT2 * a) else "I4/mmm")
    return out


def _grid_through(specials, lo, hi) -> np.ndarray:
    """A coarse grid over (lo, hi) plus each special strain and points 1e-10 ... 5e-2 from it."""
    offsets = np.geomspace(1e-10, 5e-2, 22)
    pts = [np.linspace(lo, hi, 41)[1:-1]]
    for x in specials:
        pts.append(np.concatenate([[x], x - offsets, x + offsets]))
    d = np.unique(np.concatenate(pts))
    return d[(d > lo) & (d < hi)]


CASES = [
    # (lattice, loading, potential, direction, special strains -> expected group there)
    ("fcc", "in_plane_hydrostatic", None, "[100]", {1.0: "Fm-3m", np.sqrt(4 / 3): "Im-3m"}),
    ("fcc", "in_plane_hydrostatic", None, "[110]", {1.0: "Fm-3m", np.sqrt(4 / 3): "Im-3m"}),
    ("triangular", "uniaxial", None, "[10]", {1.0: "P6/mmm", SQRT2: "P4/mmm", np.sqrt(3.0): "P6/mmm"}),
    ("fcc", "uniaxial", "lj", "[100]", "roots"),
    ("fcc", "uniaxial", "morse", "[100]", "roots"),
    ("fcc", "uniaxial", "lj", "[110]", "roots"),
]


@pytest.mark.parametrize("lattice, loading, potential, direction, specials", CASES)
def test_classes_match_spglib_on_every_cell(lattice, loading, potential, direction, specials):
    """Reference: spglib 2.x on each cell separately, and the mirrors as the previous
    implementation derived them from spglib's operations. The special strains are found by
    hand (BCC at s = sqrt(4/3) for in-plane hydrostatic loading, where t/s = 1/sqrt 2; square
    at d/d0 = sqrt 2 and triangular again at sqrt 3 for the stretched triangular lattice) or
    as roots of the uniaxial lateral solve; the expected group at each is checked, so the grid
    really passes through it."""
    if specials == "roots":
        specials = _uniaxial_special(potential, direction)
        assert specials, "the uniaxial grid should reach an accidental higher symmetry"
        specials[1.0] = "Fm-3m"
    lo, hi = (0.5, 1.6) if loading == "uniaxial" and lattice == "fcc" else (0.0, 2.0)
    if loading == "in_plane_hydrostatic":
        hi = SQRT2
    d = _grid_through(specials, lo, hi)
    stats = {}
    got = symmetry.crystal_symmetry(lattice, loading, potential, direction, d, stats=stats)
    want = spglib_reference(got["cell"])
    for key, value in want.items():
        bad = np.flatnonzero(got[key] != value)
        assert bad.size == 0, (key, d[bad][:5], got[key][bad][:5], value[bad][:5])
    for x, group in specials.items():
        assert got["space_group"][np.argmin(np.abs(d - x))] == group, x
    # only cells near a special strain (the key within 1e-2 ... 1e2 symprec of a change) are
    # left to spglib one by one; the classes did the rest
    near = np.abs(d[:, None] - np.array(list(specials))).min(axis=1) < 2e-2
    assert stats["in_doubt"] <= near.sum() and stats["classes"] < 20


def test_order_and_potential_do_not_matter():
    """Shuffled cells (with the same cells twice) get spglib's answer cell by cell: the class
    representatives need not be neighbours on the grid."""
    rng = np.random.default_rng(3)
    d = _grid_through([1.0, np.sqrt(4 / 3)], 0.0, SQRT2)
    cells = build("fcc", "in_plane_hydrostatic", None, "[110]", d).cell3d()
    cells = np.concatenate([cells, cells])[rng.permutation(2 * d.size)]
    got = symmetry.analyse(cells)
    want = spglib_reference(cells)
    for key, value in want.items():
        assert np.array_equal(got[key], value), key


def test_lattice_residual_closed_form():
    """A 90 degree rotation about z maps the orthorhombic lattice diag(1, 1.2, 3) to vectors
    0.2 d0 from the nearest lattice vectors (by hand: (1, 0, 0) -> (0, 1, 0) vs (0, 1.2, 0));
    on the tetragonal diag(1, 1, 3) it is a symmetry (residual 0); the mirrors are symmetries
    of both."""
    rot = np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])
    ops = np.stack([rot, *symmetry.MIRRORS.values()])
    res = symmetry.lattice_residual(np.stack([np.diag([1.0, 1.2, 3.0]), np.diag([1.0, 1.0, 3.0])]), ops)
    np.testing.assert_allclose(res, [[0.2, 0, 0], [0, 0, 0]], atol=1e-14)


def test_shells_of_fcc_and_bcc():
    """Shell multiplicities (one vector per +/- pair) by hand: FCC 12, 6, 24, 12 neighbours at
    1, sqrt 2, sqrt 3, 2 -> 6, 3, 12, 6; BCC 8, 6, 12, 24 -> 4, 3, 6, 12."""
    fcc = build("fcc", "in_plane_hydrostatic", None, "[100]", [1.0]).cell3d()
    bcc = 0.5 * np.array([[-1.0, 1, 1], [1, -1, 1], [1, 1, -1]])
    mult, doubt = symmetry.shell_multiplicities(np.concatenate([fcc, bcc[None]]), 1e-5)
    assert mult.tolist() == [[6, 3, 12, 6], [4, 3, 6, 12]]
    assert not doubt.any()
