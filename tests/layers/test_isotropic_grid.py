"""The speed grid of the isotropic path (surfwave.layers.isotropic_modes.speed_grid) at its floor.

Reference: the general Stroh solver of surfwave.layers (forced with ``solve.FAST_ISOTROPIC = False``).
"""
from __future__ import annotations

import numpy as np

import surfwave
import surfwave.layers.solve as solve
from surfwave.layers.isotropic import iso_stack
from surfwave.layers.isotropic_modes import Rows, slowest_speed, speed_grid
from surfwave.layers.stack import resolve_stack

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
    assert grid[0] == 0.95 * slowest_speed(st)
    fast = surfwave.layered(SUB, FILMS, kh=kh)
    try:
        solve.FAST_ISOTROPIC = False
        gen = surfwave.layered(SUB, FILMS, kh=kh)
    finally:
        solve.FAST_ISOTROPIC = True
    assert (fast["mode"] == gen["mode"]).all()
    ok = np.isfinite(gen["c"])
    assert np.allclose(fast["c"][ok], gen["c"][ok], rtol=1e-10, atol=0)
    nxt = grid[grid > grid[0] * (1 + 1e-9)][0]                            # the next distinct grid speed
    assert grid[0] < fast["c"][0, 0] < nxt
