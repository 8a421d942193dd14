"""Geometries and input validation (docs/physics/paper.md, 'Prestressed geometries')."""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.errors import GeometryError, InputError
from surfwave.model_crystals.lattices import build


def test_in_plane_hydrostatic_keeps_out_of_plane_bonds_at_rest():
    """t = sqrt(2 - s^2): the 4 out-of-plane bonds of the half-set stay at d0; in-plane ones are s."""
    s = np.array([0.8, 1.0, 1.3])
    c = build("fcc", "in_plane_hydrostatic", None, "[110]", s)
    lengths = np.sort(np.linalg.norm(c.bonds, axis=-1), axis=1)
    for i, si in enumerate(s):
        np.testing.assert_allclose(sorted([si, si, 1, 1, 1, 1]), lengths[i], atol=1e-14)
    np.testing.assert_allclose(c.volume, np.sqrt(2) / 2 * s**2 * np.sqrt(2 - s**2))


def test_triangular_geometry():
    """d_x = d/2, d_y = sqrt(1 - d_x^2), V = 2 d_x d_y."""
    c = build("triangular", "uniaxial", None, "[10]", [1.0, 1.2])
    np.testing.assert_allclose(c.volume, [np.sqrt(3) / 2, 2 * 0.6 * 0.8])


@pytest.mark.parametrize("args,match", [
    (("fcc", "in_plane_hydrostatic", None, "[100]", 1.5), "d/d0 = 1.5"),
    (("fcc", "in_plane_hydrostatic", None, "[100]", np.sqrt(2)), "t\\^2"),
    (("triangular", "uniaxial", None, "[10]", 2.0), "d/d0 = 2"),
    (("fcc", "in_plane_hydrostatic", None, "[100]", -0.1), "d/d0 = -0.1"),
])
def test_impossible_geometry_is_an_error_naming_the_value(args, match):
    with pytest.raises(GeometryError, match=match):
        build(*args)


@pytest.mark.parametrize("args,match", [
    (("hcp", "uniaxial", None, "[10]", 1.0), "unknown lattice 'hcp'"),
    (("fcc", "shear", None, "[100]", 1.0), "loading 'shear'"),
    (("fcc", "uniaxial", None, "[111]", 1.0), "direction '\\[111\\]'"),
    (("triangular", "in_plane_hydrostatic", None, "[10]", 1.0), "not available"),
    (("fcc", "in_plane_hydrostatic", None, "[100]", [[1.0]]), "1-D"),
    (("fcc", "in_plane_hydrostatic", None, "[100]", np.nan), "finite"),
])
def test_bad_names_and_shapes(args, match):
    with pytest.raises(InputError, match=match):
        build(*args)


def test_unknown_potential_lists_known_ones():
    with pytest.raises(InputError, match="known potentials"):
        surfwave.point("fcc", "in_plane_hydrostatic", "buckingham", "[100]", 1.0)


def test_uniaxial_lateral_solve_failure_is_clear():
    """A lateral solve that does not converge (starved of iterations here) is a GeometryError
    naming the first failing d/d0, not a silent wrong geometry."""
    from surfwave.model_crystals.lattices import solve_lateral_stretch

    with pytest.raises(GeometryError, match="d/d0 = 1.2"):
        solve_lateral_stretch("[100]", np.array([1.0, 1.2]), "lj", max_iter=1)


def test_uniaxial_unstressed_is_identity():
    """d/d0 = 1 exactly: no stretch anywhere, zero stress."""
    for direction in ("[100]", "[110]"):
        c = build("fcc", "uniaxial", "lj", direction, 1.0)
        np.testing.assert_allclose(c.stretch, 1.0, atol=1e-14)
        assert surfwave.point("fcc", "uniaxial", "lj", direction, 1.0)["stress"][0] == 0.0


def test_uniaxial_collapse_is_an_error_naming_the_right_point():
    """FCC uniaxial [110]: with the out-of-plane bonds at rest the y-stretch goes to 0 as
    d/d0 -> sqrt 3 (the crystal flattens). That is an impossible geometry, and an array
    call names the failing point, not an innocent neighbour (found by the phonopy stage)."""
    with pytest.raises(GeometryError, match="d/d0 = 1.7315"):
        build("fcc", "uniaxial", "harmonic", "[110]", [1.5, 1.6, 1.7315])
    ok = build("fcc", "uniaxial", "harmonic", "[110]", [1.5, 1.6])
    np.testing.assert_allclose(ok.stretch[:, 1], np.sqrt((3 - ok.stretch[:, 0] ** 2) / 2), rtol=1e-10)


def test_swapped_arguments_fail_loudly():
    """The library-wide order is (lattice, loading, potential, direction, d/d0): a call in
    another order names the misplaced value instead of computing something else."""
    with pytest.raises(InputError, match=r"\[110\]"):
        build("fcc", "uniaxial", "[110]", "lj", 1.0)
    with pytest.raises(TypeError):  # the old 4-argument form lacks d/d0
        build("fcc", "in_plane_hydrostatic", "[110]", [0.9, 1.0])


def test_build_checked_stops_at_a_collapsed_geometry():
    """build_checked = build plus a GeometryError where a lab stretch or the volume vanishes;
    reference: harmonic uniaxial FCC [110] collapses laterally as d/d0 -> sqrt 3 (the lateral
    solve or the collapse check stops it), while d/d0 = 1.5 is an ordinary crystal."""
    from surfwave.model_crystals.lattices import build_checked

    ok = build_checked("fcc", "uniaxial", "harmonic", "[110]", [1.0, 1.5])
    assert ok.volume.min() > 0.1
    with pytest.raises(GeometryError, match="1.7315"):
        build_checked("fcc", "uniaxial", "harmonic", "[110]", [1.5, 1.7315])
