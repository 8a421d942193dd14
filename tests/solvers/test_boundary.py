"""The surface's electrical condition as an object (surfwave.solvers.boundary).

References: the boundary conditions of a piezoelectric half space in the EPS0 = 1 scaling
(docs/physics/leaky-waves.md; Farnell and Adler): free (open circuit, vacuum above) M - i e4 e4^T,
metallized (phi = 0) the mechanical 3 x 3 block; and the string-named solvers' own answers,
which a boundary object must reproduce bit for bit.
"""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.errors import InputError
from surfwave.real_crystals.piezo_materials import get_cut, lab_tensors
from surfwave.solvers import stroh
from surfwave.solvers.boundary import FREE, METALLIZED, Boundary, Metallized, as_boundary
from surfwave.solvers.leaky import leaky_wave
from surfwave.solvers.piezo import piezo_surface_wave


def test_secular_matrices():
    """Free: only M_44 changes, by -i; metallized: the mechanical block; M itself is untouched."""
    rng = np.random.default_rng(0)
    M = rng.normal(size=(5, 4, 4)) + 1j * rng.normal(size=(5, 4, 4))
    keep = M.copy()
    f, m = FREE.secular_matrix(M), METALLIZED.secular_matrix(M)
    d = f - M
    assert d[:, 3, 3] == pytest.approx(np.full(5, -1j)) and np.count_nonzero(d) == 5
    assert np.array_equal(m, M[:, :3, :3]) and np.array_equal(M, keep)
    assert FREE.vacuum and not METALLIZED.vacuum


def test_names_and_refusals():
    assert as_boundary("free") is FREE and as_boundary(METALLIZED) is METALLIZED
    with pytest.raises(InputError, match="'grounded'"):
        as_boundary("grounded")


class Shorted(Metallized):
    """A new boundary is one class: here a renamed metallized surface."""

    name = "shorted"


def test_a_new_boundary_class_plugs_into_the_solvers():
    """A Boundary subclass (its own name, the physics of phi = 0) gives the leaky and the
    subsonic solvers' metallized answers bit for bit, keyed by its name: the solvers ask the
    object, not the condition's name. 64Y-X LiNbO3 (a leaky cut) and Y-Z LiNbO3."""
    assert issubclass(Shorted, Boundary)
    for cut in ("64Y-X LiNbO3", "Y-Z LiNbO3"):
        c = get_cut(cut)
        t = lab_tensors(c.material, c.lab_axes[None])
        A = stroh.wave_propagation_tensor(t["C"], np.zeros((1, 3, 3)))
        rho = np.full(1, t["rho"])
        ref = leaky_wave(A, rho, t["e"], t["eps"], electrical="metallized")
        new = leaky_wave(A, rho, t["e"], t["eps"], electrical=(Shorted(), FREE))
        assert set(new) == {"shorted", "free"}
        for key in ("c_leaky", "leaky_attenuation"):
            np.testing.assert_array_equal(new["shorted"][key], ref[key])
        sub_ref = piezo_surface_wave(A, t["e"], t["eps"], rho, electrical="metallized")
        sub_new = piezo_surface_wave(A, t["e"], t["eps"], rho, electrical=np.array([Shorted()], dtype=object))
        np.testing.assert_array_equal(sub_new["c"], sub_ref["c"])


def test_the_boundaries_are_the_vocabulary():
    """The named boundaries are exactly surfwave.vocab.ELECTRICAL, in its order."""
    from surfwave import vocab
    from surfwave.solvers.boundary import BOUNDARIES

    assert tuple(BOUNDARIES) == vocab.ELECTRICAL


def test_a_new_boundary_class_goes_through_the_front_door():
    """The same renamed metallized surface through surfwave.material: the whole path (resolver,
    case, one path, piezoelectric batch, leaky wave) answers with the metallized numbers and
    labels them with the new name; free and metallized speeds and K^2 are unchanged."""
    import surfwave

    ref = surfwave.material("LiNbO3", cut="64Y-X", electrical="metallized")
    new = surfwave.material("LiNbO3", cut="64Y-X", electrical=Shorted())
    assert new["electrical"] == "shorted"
    for key in ("c_R", "c_leaky", "leaky_attenuation", "c_free", "c_metallized", "K2", "power_flow_angle"):
        np.testing.assert_array_equal(new[key], ref[key])
    assert new["wave_type"] == ref["wave_type"]
