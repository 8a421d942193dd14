"""Depth profiles of guided modes."""
from __future__ import annotations

import numpy as np

from surfwave.layers.profile import mode_profile
from surfwave.layers.stack import resolve_stack
from surfwave.solvers import stroh


def test_same_material_film_profile_is_the_half_space_wave():
    """A Si film on Si: the surface displacement of R is the half-space polarisation of
    stroh.surface_wave (up to phase), and the profile is continuous through the interface (depth 1)."""
    r = mode_profile("Si", [{"name": "Si", "thickness": 1e-6}], [2.0], [0.0, 1 - 1e-9, 1 + 1e-9, 3.0])
    sw = stroh.surface_wave(resolve_stack("Si", []).substrate.A, 2329.0)
    a = r["U"][0, 0] / np.linalg.norm(r["U"][0, 0])
    p = sw["polarisation"] / np.linalg.norm(sw["polarisation"])
    assert abs(abs(np.vdot(p, a)) - 1) < 1e-9
    np.testing.assert_allclose(r["U"][0, 1], r["U"][0, 2], atol=1e-8)
    assert np.abs(r["U"][0, 3]).max() < np.abs(r["U"][0, 0]).max()


def test_love_mode_profile_is_shear_horizontal_and_decays():
    """L0 of an isotropic film on a fast isotropic half-space moves only along x3; its amplitude at the
    surface is the largest and it decays in the substrate (kh = 3)."""
    fast = {"E": 400.0, "nu": 0.25, "rho": 3500.0}
    film = [{"E": 73.0, "nu": 0.17, "rho": 2200.0, "thickness": 1e-6}]
    depth = np.linspace(0, 6, 25)
    r = mode_profile(fast, film, [3.0], depth, mode="L0")
    U = r["U"][0]
    assert np.abs(U[:, :2]).max() == 0
    amp = np.abs(U[:, 2])
    assert amp[0] == amp.max() and amp[-1] < 0.2 * amp[0]
    assert np.all(np.diff(amp[depth > 1]) < 0)
