"""The speed grid of the isotropic path (surfwave.layers.isotropic_modes.speed_grid) at and below c_lo.

Reference: the general Stroh solver of surfwave.layers (forced with ``solve.FAST_ISOTROPIC = False``).
"""
from __future__ import annotations

import numpy as np
from general_path import layered_general

import surfwave
from surfwave.layers.isotropic import iso_stack
from surfwave.layers.isotropic_modes import Rows, slowest_speed, speed_grid
from surfwave.layers.stack import resolve_stack


def _general(sub, films, kh):
    return layered_general(sub, films, kh=kh)

SUB = {"E": 573.25, "nu": 0.1077, "rho": 8614.9}
FILMS = [{"E": 294.41, "nu": 0.1905, "rho": 16726.3, "thickness": 0.848e-6},
         {"E": 503.64, "nu": 0.0124, "rho": 15316.7, "thickness": 1.099e-6}]


def test_rayleigh_mode_just_above_the_grid_floor():
    """A heavy top film: at large kh its Rayleigh wave (the slowest of any layer) is the R mode, 5 %
    above the floor c_lo of the grid and below its next point; c_lo is a grid point, so the mode is
    bracketed: labels and speeds (1e-10) as the general solver's."""
    kh = np.array([30.0, 38.8, 39.2])
    st = iso_stack(resolve_stack(SUB, FILMS))
    grid = speed_grid(st, Rows(kh, freq=False))
    c_lo = 0.95 * slowest_speed(st)
    assert c_lo in grid
    fast, gen = surfwave.layered(SUB, FILMS, kh=kh), _general(SUB, FILMS, kh)
    assert (fast["mode"] == gen["mode"]).all()
    ok = np.isfinite(gen["c"])
    assert np.allclose(fast["c"][ok], gen["c"][ok], rtol=1e-10, atol=0)
    nxt = grid[grid > c_lo * (1 + 1e-9)][0]                               # the next distinct grid speed
    assert c_lo < fast["c"][0, 0] < nxt


def test_mass_loading_below_every_rayleigh_speed():
    """A dense, stiff film (10900 kg/m^3) on a slower substrate: at kh ~ 1 its mass takes the R mode
    below the Rayleigh speed of every layer (0.93 x the slowest), under the dense part of the grid;
    the grid reaches down to 0.05 x the slowest shear speed: labels and speeds as the general
    solver's (1e-10)."""
    sub = {"E": 391.4, "nu": 0.3817, "rho": 5235.4}
    films = [{"E": 629.4, "nu": 0.1526, "rho": 10933.7, "thickness": 0.4716e-6}]
    kh = np.array([0.27, 0.8, 1.5, 4.0])
    fast, gen = surfwave.layered(sub, films, kh=kh), _general(sub, films, kh)
    assert (fast["mode"] == gen["mode"]).all()
    ok = np.isfinite(gen["c"])
    assert np.allclose(fast["c"][ok], gen["c"][ok], rtol=1e-10, atol=0)
    st = iso_stack(resolve_stack(sub, films))
    assert np.nanmin(fast["c"][:, 0]) < 0.95 * slowest_speed(st)            # below c_lo
