"""Space groups (spglib 2.x) of the prestressed cells and the mirror planes of Eq. (17)."""
from __future__ import annotations

import numpy as np
import pytest
import spglib.error

from surfwave.errors import SymmetryError
from surfwave.model_crystals import symmetry
from surfwave.model_crystals.lattices import build


def test_new_error_handling_is_on():
    """spglib 2.x: with OLD_ERROR_HANDLING = False failures raise instead of warning
    (STYLE.md, phonopy / spglib facts); surfwave.model_crystals.symmetry sets it on import."""
    assert spglib.error.OLD_ERROR_HANDLING is False


@pytest.mark.parametrize(
    "lattice, loading, direction, groups",
    [
        # docs/physics/paper.md: FCC Fm-3m unstressed, I4/mmm under in-plane hydrostatic stress.
        ("fcc", "in_plane_hydrostatic", "[100]", ["I4/mmm", "Fm-3m", "I4/mmm"]),
        ("fcc", "in_plane_hydrostatic", "[110]", ["I4/mmm", "Fm-3m", "I4/mmm"]),
        # Uniaxial along a cube axis keeps a 4-fold axis; along [110] the cell is orthorhombic.
        ("fcc", "uniaxial", "[100]", ["I4/mmm", "Fm-3m", "I4/mmm"]),
        ("fcc", "uniaxial", "[110]", ["Immm", "Fm-3m", "Immm"]),
        # Triangular lattice in its vacuum-padded cell: hexagonal, then centred rectangular.
        ("triangular", "uniaxial", "[10]", ["Cmmm", "P6/mmm", "Cmmm"]),
    ],
)
def test_space_groups_and_mirrors(lattice, loading, direction, groups):
    """Expected groups by hand (one-atom cells): FCC is Fm-3m; stretching the two in-plane cube
    axes equally (or one cube axis) keeps the 4-fold axis: body-centred tetragonal I4/mmm;
    stretching along [110] leaves three orthogonal 2-fold axes: Immm. The 2D triangular
    lattice padded with vacuum is P6/mmm, uniaxially stretched centred rectangular Cmmm.
    Every one has the lab-frame mirrors x -> -x and z -> -z that Eq. (17) needs."""
    r = symmetry.crystal_symmetry(lattice, loading, "lj", direction, [0.95, 1.0, 1.05])
    assert r["space_group"].tolist() == groups
    assert r["mirror_x"].all() and r["mirror_z"].all()
    assert r["cell"].shape == (3, 3, 3)
    symmetry.require_mirrors(r, [0.95, 1.0, 1.05])  # no error


def test_space_group_numbers():
    """International Tables numbers: Fm-3m = 225, I4/mmm = 139."""
    r = symmetry.crystal_symmetry("fcc", "in_plane_hydrostatic", None, "[100]", [1.0, 0.9])
    assert r["space_group_number"].tolist() == [225, 139]


def test_rotated_frame_lacks_mirrors_and_raises():
    """Propagation 17 degrees off [100] is not in a mirror plane: Eq. (17) does not apply."""
    cell = build("fcc", "in_plane_hydrostatic", None, "[100]", [0.95]).cell3d()
    a = np.deg2rad(17.0)
    rot = np.array([[np.cos(a), 0, -np.sin(a)], [0, 1, 0], [np.sin(a), 0, np.cos(a)]])
    r = symmetry.analyse(cell @ rot.T)
    assert r["space_group"][0] == "I4/mmm"  # same crystal, rotated lab frame
    assert not r["mirror_x"][0]
    with pytest.raises(SymmetryError, match="d/d0 = 0.95.*x -> -x"):
        symmetry.require_mirrors(r, [0.95])


def test_cartesian_rotations_identity_frame():
    """For an orthorhombic cell along the lab axes, fractional and Cartesian rotations are the
    same matrix (R_cart = L^T R L^-T with diagonal L)."""
    cell = np.diag([1.0, 2.0, 3.0])
    rots = np.array([np.diag([-1, 1, 1])], dtype=float)
    np.testing.assert_allclose(symmetry.cartesian_rotations(cell, rots)[0], np.diag([-1.0, 1, 1]))


def test_a_cell_seen_before_gets_the_fresh_answer():
    """Cells analysed earlier in the process (another potential, same geometry) are answered
    from memory; the reference is spglib on the same cells with the memory emptied."""
    cells = build("fcc", "in_plane_hydrostatic", None, "[110]", [0.95, 1.0, 1.05]).cell3d()
    first = symmetry.analyse(cells)
    again = symmetry.analyse(cells)
    symmetry._SEEN.clear()
    fresh = symmetry.analyse(cells)
    for key in fresh:
        assert np.array_equal(first[key], fresh[key]) and np.array_equal(again[key], fresh[key])
    assert fresh["space_group"].tolist() == ["I4/mmm", "Fm-3m", "I4/mmm"]
